// Narrowing by a variable power of two: out = round(in * 2^-shift), to nearest
// with ties toward +inf (SC_RND), then saturated to OutBits with saturated_o
// raised. A negative shift multiplies exactly by 2^-shift (up to MaxLeft
// places). Twin of fx::shift_round followed by fx::fit with Overflow::Saturate
// (model/fixed.hpp). Combinational; while enable_i is low the output is 0
// (operand isolation: the shifter does not toggle, and simulation skips it).
//
// floor((x + 2^(s-1)) / 2^s) = 0 for every s >= InBits, since |x| < 2^(InBits-1):
// the right shift only needs InBits + 1 bits of headroom.
`default_nettype none

module shift_round #(
  parameter int InBits    = 16,
  parameter int OutBits   = 8,
  parameter int ShiftBits = 8,   // signed shift amount
  parameter int MaxLeft   = 0    // the largest left shift (-shift) that can occur
) (
  input  logic                        enable_i,
  input  logic signed [InBits-1:0]    in_i,
  input  logic signed [ShiftBits-1:0] shift_i,
  output logic signed [OutBits-1:0]   out_o,
  output logic                        saturated_o
);

  localparam int LeftBits = InBits + MaxLeft;
  localparam int ValueBits = LeftBits > InBits + 1 ? LeftBits : InBits + 1;
  localparam int WideBits = (ValueBits > OutBits ? ValueBits : OutBits) + 1;
  localparam logic signed [WideBits-1:0] OutMax = (WideBits'(1) <<< (OutBits - 1)) - WideBits'(1);
  localparam logic signed [WideBits-1:0] OutMin = -(WideBits'(1) <<< (OutBits - 1));

  // Shift amounts need only enough bits to reach past WideBits.
  localparam int AmountBits = $clog2(WideBits + 1) + 1;
  logic signed [WideBits-1:0] wide;
  logic signed [WideBits-1:0] half;
  logic signed [31:0]         shift;
  logic [AmountBits-1:0]      left, right;

  always_comb begin
    shift = 32'(shift_i);
    left = AmountBits'(-shift);
    right = AmountBits'(shift);
    wide = '0;
    half = '0;
    if (!enable_i) begin
      wide = '0;
    end else if (shift <= 0) begin
      wide = WideBits'(in_i);
      wide = wide <<< left;
    end else if (shift >= 32'(InBits)) begin
      wide = '0;
    end else begin
      half = WideBits'(1) <<< (right - AmountBits'(1));
      wide = (WideBits'(in_i) + half) >>> right;
    end
    saturated_o = wide > OutMax || wide < OutMin;
    out_o = OutBits'(saturated_o ? (wide > OutMax ? OutMax : OutMin) : wide);
  end

endmodule

`default_nettype wire
