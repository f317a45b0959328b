// Exact integer helpers shared by the blocks of the scan unit, included inside a
// module body (Yosys 0.23 has no package functions in module headers). They are
// the SystemVerilog twins of model/fixed.cpp: floor division, bit length and
// shift-with-rounding on 128-bit signed values. Functions assign their name
// instead of using `return`, which Yosys 0.23 does not parse.

// floor(num / den) for any signs; `/` truncates toward zero.
function automatic logic signed [127:0] cd_floor_div(input logic signed [127:0] num,
                                                     input logic signed [127:0] den);
  logic signed [127:0] quo;
  logic signed [127:0] rem;
  begin
    quo = num / den;
    rem = num % den;
    if (rem != 128'sd0 && ((num < 128'sd0) != (den < 128'sd0))) quo = quo - 128'sd1;
    cd_floor_div = quo;
  end
endfunction

// Bits needed to write |x| (0 for x == 0).
function automatic logic [7:0] cd_bit_length(input logic signed [127:0] x);
  logic [127:0] mag;
  logic [7:0] len;
  begin
    mag = x < 128'sd0 ? -x : x;
    len = 8'd0;
    for (int i = 0; i < 128; i++) begin
      if (mag[i]) len = 8'(i + 1);
    end
    cd_bit_length = len;
  end
endfunction

// x * 2^-shift; a right shift rounds to nearest with ties toward +inf when
// `nearest` (SC_RND) or floors (SC_TRN); a left shift is exact, clamped to
// +-2^125 where it would leave 125 bits (as fx::shift_round does).
function automatic logic signed [127:0] cd_shift_round(input logic signed [127:0] x,
                                                       input logic signed [31:0] shift,
                                                       input logic nearest);
  logic signed [127:0] y;
  logic signed [31:0] left;
  begin
    if (shift <= 32'sd0) begin
      left = -shift;
      if (x != 128'sd0 && ($signed({24'd0, cd_bit_length(x)}) + left > 32'sd125)) begin
        y = x > 128'sd0 ? (128'sd1 <<< 125) : -(128'sd1 <<< 125);
      end else begin
        y = x <<< left;
      end
    end else begin
      y = x;
      if (nearest) y = y + (128'sd1 <<< (shift - 32'sd1));
      y = y >>> shift;
    end
    cd_shift_round = y;
  end
endfunction

// Saturates x into a signed format of `bits` bits; *sat is raised on overflow.
function automatic logic signed [127:0] cd_saturate(input logic signed [127:0] x,
                                                    input int bits);
  logic signed [127:0] hi;
  logic signed [127:0] lo;
  begin
    hi = (128'sd1 <<< (bits - 1)) - 128'sd1;
    lo = -(128'sd1 <<< (bits - 1));
    cd_saturate = x > hi ? hi : (x < lo ? lo : x);
  end
endfunction
