// Reciprocal: R = floor(2^(2 RecipBits) / M) for a normalised mantissa
// 2^RecipBits <= M < 2^(RecipBits+1), exact, so 2^(RecipBits-1) <= R <= 2^RecipBits
// (RecipBits+1 bits; R = 2^RecipBits only for M = 2^RecipBits, and
// R = 2^(RecipBits-1) only for M = 2^(RecipBits+1) - 1).
//
// A pipelined restoring divider of exactly Latency register stages and one
// operand a cycle, which a stall holds:
//  - every stage moves on at a rising edge where advance_i is 1 and holds
//    (valid, tag and partial results) where it is 0;
//  - an operand presented with valid_i in a cycle with advance_i is on
//    valid_o, recip_o and tag_o Latency advancing edges later, and stays there
//    until the next advancing edge; tag_o is the tag_i it came with. With
//    advance_i always 1 that is cycle t + Latency, for that one cycle only;
//  - valid_o is 0 in every other cycle; an asynchronous reset (rst_ni low)
//    clears it at once and drops the operands in flight; recip_o and tag_o
//    are unspecified while valid_o is 0 (data registers have no reset);
//  - mantissa_i[RecipBits] is taken to be 1 and not looked at.
// Stage s resolves quotient bits RecipBits - s*StageBits downwards, StageBits =
// ceil((RecipBits+1) / Latency) of them by chained restoring steps; the last
// stages resolve fewer, or none when Latency > RecipBits+1, and are then plain
// registers.
//
// Restoring step, with partial remainder r < M (RecipBits+1 bits): the
// dividend 2^(2 RecipBits) is a one followed by zeros, so the first partial
// remainder is 2^(RecipBits-1) and each step shifts a zero in:
// t = 2r < 2M; quotient bit = (t >= M); r = t - M if so, else t. t - M lies in
// (-M, M), so RecipBits+2 bits hold it and its top bit is the borrow.
module reciprocal #(
  parameter int RecipBits = 24,
  parameter int Latency   = 4,
  parameter int TagBits   = 1
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               advance_i,
  input  logic               valid_i,
  input  logic [RecipBits:0] mantissa_i,
  input  logic [TagBits-1:0] tag_i,
  output logic               valid_o,
  output logic [RecipBits:0] recip_o,
  output logic [TagBits-1:0] tag_o
);

  if (RecipBits < 4 || RecipBits > 32) begin : gen_recip_bits_check
    $error("reciprocal needs 4 <= RecipBits <= 32");
  end
  if (Latency < 1 || Latency > 64) begin : gen_latency_check
    $error("reciprocal needs 1 <= Latency <= 64");
  end
  if (TagBits < 1) begin : gen_tag_bits_check
    $error("reciprocal needs TagBits >= 1");
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

  localparam int QuoBits       = RecipBits + 1;
  localparam int StageBits     = ceil_div(QuoBits, Latency);
  localparam int ComputeStages = ceil_div(QuoBits, StageBits);

  // Quotient bits resolved once stage `stage` has run (0 before stage 0).
  function automatic int resolved_after(input int stage);
    begin
      if (stage < 0) resolved_after = 0;
      else if ((stage + 1) * StageBits < QuoBits) resolved_after = (stage + 1) * StageBits;
      else resolved_after = QuoBits;
    end
  endfunction

  // Offset of stage `stage`'s quotient register in quo_chain, where the
  // registers sit side by side at their own widths.
  function automatic int quo_offset(input int stage);
    int offset;
    begin
      offset = 0;
      for (int k = 0; k < stage; k++) offset = offset + resolved_after(k);
      quo_offset = offset;
    end
  endfunction

  localparam int QuoChainBits = quo_offset(Latency);

  // Slot s of each chain is the input of stage s (slot 0: the module inputs).
  // The remainder and mantissa travel only as far as a stage still divides.
  logic [Latency:0]                   valid_chain;
  logic [(Latency+1)*TagBits-1:0]     tag_chain;
  logic [ComputeStages*QuoBits-1:0]   rem_chain;
  logic [ComputeStages*RecipBits-1:0] mantissa_chain;
  // Slot s: stage s's quotient register, resolved_after(s) bits (the quotient
  // so far, most significant bit first).
  logic [QuoChainBits-1:0]            quo_chain;

  assign valid_chain[0]                 = valid_i;
  assign tag_chain[0 +: TagBits]        = tag_i;
  assign rem_chain[0 +: QuoBits]        = {2'b01, {(RecipBits - 1){1'b0}}};  // 2^(RecipBits-1)
  assign mantissa_chain[0 +: RecipBits] = mantissa_i[RecipBits-1:0];

  logic unused_mantissa_msb;
  assign unused_mantissa_msb = mantissa_i[RecipBits];

  for (genvar s = 0; s < Latency; s++) begin : gen_stage
    localparam int BitsIn  = resolved_after(s - 1);
    localparam int BitsOut = resolved_after(s);
    localparam int NewBits = BitsOut - BitsIn;

    logic               valid_q;
    logic [TagBits-1:0] tag_q;
    logic [BitsOut-1:0] quo_d, quo_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q <= 1'b0;
      end else if (advance_i) begin
        valid_q <= valid_chain[s];
      end
    end

    always_ff @(posedge clk_i) begin
      if (advance_i) begin
        tag_q <= tag_chain[s*TagBits +: TagBits];
        quo_q <= quo_d;
      end
    end

    assign valid_chain[s+1]                    = valid_q;
    assign tag_chain[(s+1)*TagBits +: TagBits] = tag_q;
    assign quo_chain[quo_offset(s) +: BitsOut] = quo_q;

    if (NewBits == 0) begin : gen_plain  // every bit resolved: a plain register
      assign quo_d = quo_chain[quo_offset(s-1) +: BitsOut];
    end else begin : gen_divide
      logic [RecipBits:0]   rem_in, rem_step;
      logic [RecipBits-1:0] mantissa_in;
      logic [RecipBits+1:0] trial;
      logic [NewBits-1:0]   new_bits;

      assign rem_in      = rem_chain[s*QuoBits +: QuoBits];
      assign mantissa_in = mantissa_chain[s*RecipBits +: RecipBits];

      // NewBits chained restoring steps.
      always_comb begin
        rem_step = rem_in;
        for (int j = 0; j < NewBits; j++) begin
          trial = {rem_step, 1'b0} - {2'b01, mantissa_in};
          new_bits[NewBits-1-j] = ~trial[RecipBits+1];
          rem_step = trial[RecipBits+1] ? {rem_step[RecipBits-1:0], 1'b0} : trial[RecipBits:0];
        end
      end

      if (s == 0) begin : gen_first
        assign quo_d = new_bits;
      end else begin : gen_next
        assign quo_d = {quo_chain[quo_offset(s-1) +: BitsIn], new_bits};
      end

      // The last dividing stage's remainder is not needed: only the quotient goes on.
      if (s + 1 < ComputeStages) begin : gen_pass_remainder
        logic [RecipBits:0]   rem_q;
        logic [RecipBits-1:0] mantissa_q;
        always_ff @(posedge clk_i) begin
          if (advance_i) begin
            rem_q      <= rem_step;
            mantissa_q <= mantissa_in;
          end
        end
        assign rem_chain[(s+1)*QuoBits +: QuoBits]          = rem_q;
        assign mantissa_chain[(s+1)*RecipBits +: RecipBits] = mantissa_q;
      end
    end
  end

  assign valid_o = valid_chain[Latency];
  assign tag_o   = tag_chain[Latency*TagBits +: TagBits];
  assign recip_o = quo_chain[quo_offset(Latency-1) +: QuoBits];

endmodule
