// Serial divider: unsigned restoring division N / D, BitsPerCycle quotient
// bits a cycle, for a QuoBits-bit quotient and a DenBits-bit remainder.
//
// Cycle behaviour, with Cycles = ceil(QuoBits / BitsPerCycle):
//  - start_i high in cycle t latches numerator_i and denominator_i (nonzero)
//    at the rising edge that ends cycle t, which also resolves the first
//    quotient bits;
//  - from cycle t + Cycles on (Cycles rising edges after cycle t) up to and
//    including the cycle of the next start, quotient_o = floor(N / D),
//    remainder_o = N mod D and overflow_o = 0, provided N < D 2^QuoBits;
//  - otherwise overflow_o = 1 from the cycle after the start on, so in
//    particular from cycle t + Cycles, and quotient_o and remainder_o are
//    unspecified;
//  - in cycles t+1 .. t+Cycles-1 quotient_o and remainder_o are partial
//    results; a start in one of them abandons the division and begins the new
//    one (a start in cycle t + Cycles is the fastest back-to-back use);
//  - after reset (rst_ni low, asynchronous) the divider is idle with
//    overflow_o = 0; quotient_o and remainder_o are unspecified until a
//    division has finished.
//
// Each cycle runs BitsPerCycle chained restoring steps. The first cycle's
// steps start Cycles*BitsPerCycle - QuoBits numerator bits above the quotient
// (on bits whose quotient bits are zero when there is no overflow), so it
// resolves only the rest. With NumBits <= QuoBits there is no overflow and
// overflow_o is tied to 0. A step shifts the next numerator bit into the partial remainder r < D:
// t = 2r + bit < 2D; quotient bit = (t >= D); r = t - D if so, else t. t - D
// lies in (-D, D), so DenBits+1 bits hold it and its top bit is the borrow.
// State: the partial remainder, a quotient register that holds the numerator
// bits still to come above the quotient bits resolved so far, the
// denominator, a count of the cycles left and the overflow flag.
module serial_divider #(
  parameter int NumBits      = 32,
  parameter int DenBits      = 16,
  parameter int QuoBits      = 16,
  parameter int BitsPerCycle = 1
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               start_i,
  input  logic [NumBits-1:0] numerator_i,
  input  logic [DenBits-1:0] denominator_i,
  output logic [QuoBits-1:0] quotient_o,
  output logic [DenBits-1:0] remainder_o,
  output logic               overflow_o
);

  if (NumBits < 1 || DenBits < 1 || QuoBits < 1) begin : gen_widths_check
    $error("serial_divider needs NumBits, DenBits and QuoBits >= 1");
  end
  if (BitsPerCycle < 1 || BitsPerCycle > 16) begin : gen_bits_per_cycle_check
    $error("serial_divider needs 1 <= BitsPerCycle <= 16");
  end

  // Elaboration-time arithmetic, without a divider.
  function automatic int ceil_div(input int num, input int den);
    int quotient;
    begin
      quotient = 0;
      while (quotient * den < num) quotient = quotient + 1;
      ceil_div = quotient;
    end
  endfunction

  localparam int Cycles    = ceil_div(QuoBits, BitsPerCycle);
  // Numerator bits consumed over the whole division, and in the first cycle
  // the real (not leading-zero) quotient bits.
  localparam int ConsumedBits   = Cycles * BitsPerCycle;
  localparam int FirstBits = QuoBits - (Cycles - 1) * BitsPerCycle;
  localparam int HighBits  = NumBits > QuoBits ? NumBits - QuoBits : 0;

  // One cycle's chained restoring steps.
  logic [DenBits-1:0]      step_den, step_rem_in, step_rem_out;
  logic [BitsPerCycle-1:0] step_bits_in, step_quo_bits;
  logic [DenBits:0]        step_shifted, step_trial;

  always_comb begin
    step_rem_out = step_rem_in;
    for (int j = 0; j < BitsPerCycle; j++) begin
      step_shifted = {step_rem_out, step_bits_in[BitsPerCycle-1-j]};
      step_trial   = step_shifted - {1'b0, step_den};
      step_quo_bits[BitsPerCycle-1-j] = ~step_trial[DenBits];
      step_rem_out = step_trial[DenBits] ? step_shifted[DenBits-1:0] : step_trial[DenBits-1:0];
    end
  end

  // At a start the steps work on the operands directly: the partial remainder
  // is N >> ConsumedBits, the next numerator bits follow it.
  logic [DenBits-1:0]      start_rem;
  logic [BitsPerCycle-1:0] start_bits;
  logic [QuoBits-1:0]      start_quo;
  assign start_rem  = DenBits'(numerator_i >> ConsumedBits);
  assign start_bits = BitsPerCycle'(numerator_i >> ((Cycles - 1) * BitsPerCycle));
  assign start_quo  = (QuoBits'(numerator_i) << FirstBits) |
                      QuoBits'(step_quo_bits[FirstBits-1:0]);

  logic [DenBits-1:0] rem_q;
  logic [QuoBits-1:0] quo_q;

  if (Cycles == 1) begin : gen_one_cycle
    // Everything happens in the start cycle: no denominator to keep, no count.
    // The leading quotient bits are zero (or overflow), and with no overflow
    // to flag there is nothing to reset.
    logic unused_one_cycle;
    assign unused_one_cycle = ^{step_quo_bits, rst_ni};

    assign step_den     = denominator_i;
    assign step_rem_in  = start_rem;
    assign step_bits_in = start_bits;

    always_ff @(posedge clk_i) begin
      if (start_i) begin
        rem_q <= step_rem_out;
        quo_q <= start_quo;
      end
    end
  end else begin : gen_cycles
    localparam int CountBits = $clog2(Cycles);
    localparam logic [CountBits-1:0] CountStart = CountBits'(Cycles - 1);

    logic [DenBits-1:0]   den_q;
    logic [CountBits-1:0] count_d, count_q;
    logic                 busy;

    assign busy         = count_q != '0;
    assign step_den     = start_i ? denominator_i : den_q;
    assign step_rem_in  = start_i ? start_rem : rem_q;
    assign step_bits_in = start_i ? start_bits : quo_q[QuoBits-1 -: BitsPerCycle];

    always_comb begin
      count_d = count_q;
      if (start_i) begin
        count_d = CountStart;
      end else if (busy) begin
        count_d = count_q - 1'b1;
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        count_q <= '0;
      end else begin
        count_q <= count_d;
      end
    end

    always_ff @(posedge clk_i) begin
      if (start_i) begin
        den_q <= denominator_i;
        rem_q <= step_rem_out;
        quo_q <= start_quo;
      end else if (busy) begin
        rem_q <= step_rem_out;
        quo_q <= {quo_q[QuoBits-BitsPerCycle-1:0], step_quo_bits};
      end
    end
  end

  // Overflow: floor(N / 2^QuoBits) >= D, decided from the operands at the start.
  if (HighBits == 0) begin : gen_no_overflow
    assign overflow_o = 1'b0;
  end else begin : gen_overflow
    localparam int CompareBits = HighBits > DenBits ? HighBits : DenBits;
    logic overflow_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        overflow_q <= 1'b0;
      end else if (start_i) begin
        overflow_q <= CompareBits'(numerator_i >> QuoBits) >= CompareBits'(denominator_i);
      end
    end
    assign overflow_o = overflow_q;
  end

  assign quotient_o  = quo_q;
  assign remainder_o = rem_q;

endmodule
