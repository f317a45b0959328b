// The setup engine's multiplies (model/setup_terms.def): each result a sum of
// signed products, its terms listed in the generated cd_widths.svh with the
// schedule that model/setup_schedule.cpp derives.
//
// With CD_SETUP_MULTIPLIERS = 0 every product has a multiplier of its own and
// result_o is combinational: the sums are ready in the cycle that reads them
// (stage A to E of setup_engine.sv), as in a fully parallel engine. With
// CD_SETUP_PRODUCT_REGISTER each sum is registered in its terms' cycle and
// read by its stage a cycle later (the schedule puts the stage there).
//
// With M >= 1 the products share M unsigned L x L multipliers (L =
// CD_SETUP_MUL_BITS). Term t runs on multiplier CD_SETUP_TERM_MULTIPLIER[t]
// from setup cycle CD_SETUP_TERM_START[t] for LimbsA x LimbsB cycles: each
// cycle multiplies an L-bit piece of |a| by one of |b| and adds it, shifted
// into place and signed, to the multiplier's accumulator. A result's terms
// run back to back on one multiplier; after its last piece the accumulator
// is registered as the result, which holds until the term runs again.
// Operands must hold still from a term's first cycle to its last. A held
// unit (hold_i) repeats the cycle: the accumulators keep their value.
`include "cd_widths.svh"
`default_nettype none

module setup_multipliers #(
  localparam int TermCount   = `CD_SETUP_TERM_COUNT,
  localparam int ResultCount = `CD_SETUP_RESULT_COUNT,
  localparam int ABits       = `CD_SETUP_OPERAND_A_BITS,
  localparam int BBits       = `CD_SETUP_OPERAND_B_BITS,
  localparam int AccBits     = `CD_SETUP_ACC_BITS,
  localparam int CountBits   = `CD_SETUP_COUNT_BITS
) (
  input  logic                           clk_i,
  input  logic                           hold_i,
  input  logic                           setup_i,
  input  logic [CountBits-1:0]           stage_count_i,
  // Term t's operands, sign-extended, in bits t*ABits +: ABits and t*BBits +: BBits.
  input  logic [TermCount*ABits-1:0]     a_i,
  input  logic [TermCount*BBits-1:0]     b_i,
  // Result r in bits r*AccBits +: AccBits; its low CD_SETUP_RESULT_BITS[r] bits hold it.
  output logic [ResultCount*AccBits-1:0] result_o
);

  localparam int Multipliers = `CD_SETUP_MULTIPLIERS;
  localparam logic [16*TermCount-1:0] TermStart      = `CD_SETUP_TERM_START;
  localparam logic [8*TermCount-1:0]  TermMultiplier = `CD_SETUP_TERM_MULTIPLIER;
  localparam logic [8*TermCount-1:0]  TermLimbsA     = `CD_SETUP_TERM_LIMBS_A;
  localparam logic [8*TermCount-1:0]  TermLimbsB     = `CD_SETUP_TERM_LIMBS_B;
  localparam logic [8*TermCount-1:0]  TermABits      = `CD_SETUP_TERM_A_BITS;
  localparam logic [8*TermCount-1:0]  TermBBits      = `CD_SETUP_TERM_B_BITS;
  localparam logic [TermCount-1:0]    TermNegate     = `CD_SETUP_TERM_NEGATE;
  localparam logic [8*TermCount-1:0]  TermResult     = `CD_SETUP_TERM_RESULT;
  localparam logic [TermCount-1:0]    TermFirst      = `CD_SETUP_TERM_FIRST;
  localparam logic [TermCount-1:0]    TermLast       = `CD_SETUP_TERM_LAST;
  localparam logic [8*ResultCount-1:0] ResultBits    = `CD_SETUP_RESULT_BITS;
  localparam bit ProductRegister = `CD_SETUP_PRODUCT_REGISTER != 0;

  localparam logic [8*ResultCount-1:0] ResultFirstTerm = `CD_SETUP_RESULT_FIRST_TERM;

  if (Multipliers == 0) begin : gen_parallel
    // One multiplier per product, its operands as wide as the term says (the
    // bus carries them sign-extended, which synthesis cannot see through the
    // port), its product as wide as its result.
    logic [TermCount*AccBits-1:0] product;
    for (genvar t = 0; t < TermCount; t++) begin : gen_product
      localparam int Bits  = 32'(ResultBits[8*TermResult[8*t +: 8] +: 8]);
      localparam int ABitsT = 32'(TermABits[8*t +: 8]);
      localparam int BBitsT = 32'(TermBBits[8*t +: 8]);
      logic signed [Bits-1:0] value, term_value;
      assign value = Bits'($signed(a_i[ABits*t +: ABitsT])) * Bits'($signed(b_i[BBits*t +: BBitsT]));
      // Signed by the term at its own width, then sign-extended (wires, no logic).
      assign term_value = TermNegate[t] ? -value : value;
      assign product[AccBits*t +: AccBits] = AccBits'(term_value);
    end
    // Each sum as wide as its result: the bus's upper bits are its sign.
    for (genvar r = 0; r < ResultCount; r++) begin : gen_sum
      localparam int Bits = 32'(ResultBits[8*r +: 8]);
      logic signed [Bits-1:0] sum;
      always_comb begin
        sum = '0;
        for (int t = 0; t < TermCount; t++)
          if (TermResult[8*t +: 8] == r) sum = sum + Bits'(product[AccBits*t +: AccBits]);
      end
      if (ProductRegister) begin : gen_registered
        // Registered in the result's product cycle (its terms' start), read
        // by the stage a cycle on; it holds until the terms run again.
        localparam int Start = 32'(TermStart[16*ResultFirstTerm[8*r +: 8] +: 16]);
        logic signed [Bits-1:0] sum_q;
        always_ff @(posedge clk_i) begin
          if (setup_i && stage_count_i == CountBits'(Start) && !hold_i) sum_q <= sum;
        end
        assign result_o[AccBits*r +: AccBits] = AccBits'(sum_q);
      end else begin : gen_combinational
        assign result_o[AccBits*r +: AccBits] = AccBits'(sum);
      end
    end
    // The buses' sign extension beyond each term's width.
    logic unused_operands;
    assign unused_operands = ^{a_i, b_i};
    if (!ProductRegister) begin : gen_unused_control
      logic unused_control;
      assign unused_control = ^{clk_i, hold_i, setup_i, stage_count_i};
    end
  end else begin : gen_shared
    localparam int L = `CD_SETUP_MUL_BITS;
    localparam int PieceBits = `CD_SETUP_PIECE_BITS;
    localparam int AccWide = AccBits > 2 * L ? AccBits : 2 * L;

    // Per term: in one of its cycles, and which pieces of |a| and |b| it multiplies.
    logic [TermCount-1:0]           term_active, term_first, term_last_piece;
    logic [TermCount*PieceBits-1:0] term_piece_a, term_piece_b;
    for (genvar t = 0; t < TermCount; t++) begin : gen_term
      localparam int Start  = 32'(TermStart[16*t +: 16]);
      localparam int LimbsB = 32'(TermLimbsB[8*t +: 8]);
      localparam int Cycles = 32'(TermLimbsA[8*t +: 8]) * LimbsB;
      always_comb begin
        term_active[t] = 1'b0;
        term_first[t] = 1'b0;
        term_last_piece[t] = 1'b0;
        term_piece_a[PieceBits*t +: PieceBits] = '0;
        term_piece_b[PieceBits*t +: PieceBits] = '0;
        for (int k = 0; k < Cycles; k++) begin
          if (setup_i && stage_count_i == CountBits'(Start + k)) begin
            term_active[t] = 1'b1;
            term_first[t] = k == 0;
            term_last_piece[t] = k == Cycles - 1;
            term_piece_a[PieceBits*t +: PieceBits] = PieceBits'(k / LimbsB);
            term_piece_b[PieceBits*t +: PieceBits] = PieceBits'(k % LimbsB);
          end
        end
      end
    end

    logic [Multipliers*AccBits-1:0] acc_next;
    for (genvar m = 0; m < Multipliers; m++) begin : gen_multiplier
      logic [ABits-1:0]     a, a_magnitude;
      logic [BBits-1:0]     b, b_magnitude;
      logic [PieceBits-1:0] piece_a, piece_b;
      logic                 busy, first, negate;
      logic [L-1:0]         a_piece, b_piece;
      logic [2*L-1:0]       piece_product;
      logic [AccWide-1:0]   shifted;
      logic [AccBits-1:0]   contribution, acc_d, acc_q;

      // The operands of the term this multiplier runs now (at most one).
      always_comb begin
        a = '0;
        b = '0;
        piece_a = '0;
        piece_b = '0;
        busy = 1'b0;
        first = 1'b0;
        negate = 1'b0;
        for (int t = 0; t < TermCount; t++) begin
          if (TermMultiplier[8*t +: 8] == m && term_active[t]) begin
            a = a | a_i[ABits*t +: ABits];
            b = b | b_i[BBits*t +: BBits];
            piece_a = piece_a | term_piece_a[PieceBits*t +: PieceBits];
            piece_b = piece_b | term_piece_b[PieceBits*t +: PieceBits];
            busy = 1'b1;
            // A result starts with the first piece of its first term.
            first = first | (term_first[t] && TermFirst[t]);
            negate = negate | TermNegate[t];
          end
        end
      end

      assign a_magnitude = a[ABits-1] ? -a : a;
      assign b_magnitude = b[BBits-1] ? -b : b;
      assign a_piece = L'(a_magnitude >> (L * piece_a));
      assign b_piece = L'(b_magnitude >> (L * piece_b));
      assign piece_product = (2 * L)'(a_piece) * (2 * L)'(b_piece);
      assign shifted = AccWide'(piece_product) << (L * (32'(piece_a) + 32'(piece_b)));
      assign contribution = (a[ABits-1] ^ b[BBits-1] ^ negate) ? -(AccBits'(shifted)) : AccBits'(shifted);
      assign acc_d = (first ? '0 : acc_q) + contribution;
      assign acc_next[AccBits*m +: AccBits] = acc_d;

      always_ff @(posedge clk_i) begin
        if (busy && !hold_i) acc_q <= acc_d;
      end
    end

    // A result is registered from its multiplier after its last piece, as
    // wide as it is; the bus's upper bits are its sign.
    for (genvar r = 0; r < ResultCount; r++) begin : gen_result
      localparam int Bits = 32'(ResultBits[8*r +: 8]);
      logic signed [Bits-1:0] result_q;
      always_ff @(posedge clk_i) begin
        for (int t = 0; t < TermCount; t++) begin
          if (TermResult[8*t +: 8] == r && TermLast[t] && term_active[t] && term_last_piece[t] && !hold_i)
            result_q <= Bits'(acc_next[AccBits*TermMultiplier[8*t +: 8] +: AccBits]);
        end
      end
      assign result_o[AccBits*r +: AccBits] = AccBits'(result_q);
    end
  end

endmodule

`default_nettype wire
