// Correction adder: u_line = T_k + o S_k for the pixel's line and, with a
// usable neighbour, the correction u = u_line(k) + round(t (u_line(k') -
// u_line(k)) 2^-d_frac), then rounding and saturation to the output format.
// t is the column's |d| (the paper's linear correction) or, for cd-persp, the
// perspective-correct weight t' = |d| + c e r, c = |d| (1 - |d|), e = +-eps_k,
// r ~ 1 / (1 + |d| e) from a ROM of 1/m and a chord (docs/designs.md,
// "cd-persp"). Twin of model/correction_adder.hpp and of line_value in
// model/column_walker.hpp, at the widths of model/derived_widths.cpp.
// With Stages = 0 combinational (one cycle with the table read; cd-persp's
// weight adds three multiplies to that path: docs/rtl.md); with Stages = 1 a
// pipeline register (correction_stages) holds the line values, the weight and
// what the flags need, and the correction, rounding and saturation follow in
// the next cycle, from valid_o. Evaluated only while valid_i (and, after the
// register, while valid_o).
`include "cd_widths.svh"
`default_nettype none

module correction_adder #(
  parameter bit HasCorrection = 1'b1,  // 0: no correction hardware (designs without it)
  // cd-persp's weight (eps in the word, its ROM and multiplies), chosen per
  // pixel by persp_i.
  parameter bit HasPersp = 1'b0,
  // Pipeline registers between the weight and the correction: 0 or 1.
  parameter int Stages = 0,
  localparam int WordBits = HasPersp ? `CD_PERSP_WORD_BITS : `CD_WORD_BITS
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          advance_i,  // the register loads (a held unit keeps it)
  input  logic                          valid_i,
  input  logic [WordBits-1:0]           own_entry_i,
  input  logic [WordBits-1:0]           neighbour_entry_i,
  // Correction wanted: a design with correction and a pixel off its line.
  input  logic                          correct_i,
  input  logic [`CD_PIXEL_BITS-1:0]     offset_i,
  input  logic [`CD_WEIGHT_BITS-1:0]    weight_i,
  // cd-persp: the perspective-correct weight, toward the neighbour at
  // k + direction_i (+1 or -1).
  input  logic                          persp_i,
  input  logic signed [1:0]             direction_i,
  output logic                          valid_o,    // u_o, v_o and flags_o hold a pixel
  output logic signed [`CD_OUT_BITS-1:0] u_o,
  output logic signed [`CD_OUT_BITS-1:0] v_o,
  output logic [7:0]                    flags_o
);

  localparam int TBits      = `CD_T_BITS;
  localparam int SBits      = `CD_S_BITS;
  localparam int TFrac      = `CD_T_FRAC;
  localparam int SFrac      = `CD_S_FRAC;
  localparam int DFrac      = `CD_D_FRAC;
  localparam int OutFrac    = `CD_OUT_FRAC;
  localparam int OutBits    = `CD_OUT_BITS;
  localparam int PixelBits  = `CD_PIXEL_BITS;
  localparam int WeightBits = `CD_WEIGHT_BITS;
  localparam int Frac       = `CD_LINE_VALUE_FRAC;
  localparam int ValueBits  = `CD_LINE_VALUE_BITS;
  localparam int SumBits    = `CD_CORRECTED_BITS;
  // The weight applied: |d| <= 1/2 (WeightBits), or cd-persp's t' <= 1.
  localparam int AppliedBits = HasPersp ? DFrac + 1 : WeightBits;
  localparam int ProductBits = AppliedBits + ValueBits + 2;
  localparam int OutShift   = Frac - OutFrac;
  localparam int OutLeft    = OutShift < 0 ? -OutShift : 0;

  // u_line or v_line of one entry at column offset o, Frac fraction bits.
  function automatic logic signed [ValueBits-1:0] line_value(input logic signed [TBits-1:0] t,
                                                             input logic signed [SBits-1:0] s,
                                                             input logic [PixelBits-1:0] offset);
    line_value = (ValueBits'(t) <<< (Frac - TFrac)) +
                 ValueBits'($signed({1'b0, offset})) * (ValueBits'(s) <<< (Frac - SFrac));
  endfunction

  // own + round(weight (other - own) 2^-d_frac), ties toward +inf.
  function automatic logic signed [SumBits-1:0] corrected(input logic signed [ValueBits-1:0] own,
                                                          input logic signed [ValueBits-1:0] other,
                                                          input logic [AppliedBits-1:0] weight);
    logic signed [ProductBits-1:0] product;
    begin
      product = ProductBits'($signed({1'b0, weight})) * (ProductBits'(other) - ProductBits'(own));
      product = (product + ProductBits'(1 <<< (DFrac - 1))) >>> DFrac;
      corrected = SumBits'(own) + SumBits'(product);
    end
  endfunction

  // cd-persp's formats (docs/designs.md, "cd-persp").
  localparam int EpsInt  = `CD_EPS_INT;
  localparam int EpsFrac = `CD_EPS_FRAC;
  localparam int EpsBits = `CD_EPS_BITS;
  localparam int PFrac   = `CD_PERSP_FRAC;
  localparam int TableLog2 = `CD_PERSP_TABLE_LOG2;
  localparam int Entries = (1 << TableLog2) + 1;
  localparam int EntryBits = PFrac + 1;             // 1 / m in (1/2, 1]
  localparam int Fine = PFrac - TableLog2;          // bits between two entries
  localparam int IndexBits = TableLog2 > 0 ? TableLog2 : 1;
  localparam int XBits = PFrac + EpsInt;            // x in [-1/2, 2^(EpsInt - 2)), signed
  localparam int ShiftBits = $clog2(EpsInt + 1) + 1;  // s in [-1, EpsInt - 2], signed
  localparam int CBits = 2 * DFrac + 1;             // c = |d| (1 - |d|) <= 1/4, signed
  localparam int CeBits = PFrac + EpsInt;           // |c e| < 2^(EpsInt - 3)
  localparam int TpBits = DFrac + 3;                // |d| + c e r in (-1, 3/2)
  localparam int XShift = DFrac + EpsFrac - PFrac;
  localparam int CeShift = 2 * DFrac + EpsFrac - PFrac;
  localparam int TShift = 2 * PFrac - DFrac;        // plus s

  // The ROM: entry i = round(2^PFrac K / (K + i)), ties up, i = 0 .. K,
  // computed at elaboration (64-bit: 2^(PFrac + 1) K < 2^40).
  /* verilator lint_off UNUSEDSIGNAL */  // an entry's bits above EntryBits are 0
  function automatic logic [Entries*EntryBits-1:0] rom_contents();
    logic [63:0] k, entry;
    begin
      rom_contents = '0;
      k = 64'(1) << TableLog2;
      for (int i = 0; i < Entries; i++) begin
        entry = ((k << (PFrac + 1)) / (k + 64'(i)) + 64'(1)) / 64'(2);
        rom_contents[i*EntryBits +: EntryBits] = entry[EntryBits-1:0];
      end
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */
  localparam logic [Entries*EntryBits-1:0] Rom = rom_contents();

  // Three parts, with up to two registers between them (Stages):
  //   A  the line values, what the flags need, and cd-persp's weight up to
  //      1/(1 + x) (x = |d| e, c e, the normalisation, the ROM and its chord);
  //   B  cd-persp's t' = |d| + c e r (the other designs: |d|);
  //   C  the correction, the rounding to the output format and the flags.
  // Stages = 1 registers between B and C; 2 also between A and B.

  // ---- A
  logic signed [ValueBits-1:0] own_u, own_v, other_u, other_v;
  logic                        neighbour_usable;
  logic                        own_saturated, own_depth_range, dropped, eps_saturated_used;
  logic signed [CeBits-1:0]    ce;
  logic signed [EntryBits+1:0] r;         // 1/m
  logic signed [7:0]           t_shift;
  logic                        eps_used_saturated;

  if (HasPersp && HasCorrection) begin : gen_persp
    logic signed [EpsBits-1:0]           e;
    logic signed [DFrac+EpsBits+1:0]     x_product;
    logic signed [XBits-1:0]             x_rounded, x;
    logic signed [CBits-1:0]             c;
    logic signed [CBits+EpsBits-1:0]     ce_product;
    logic [XBits-1:0]                    y;          // 1 + x > 0
    logic signed [ShiftBits-1:0]         shift;      // 1 + x = m 2^shift
    logic [PFrac-1:0]                    f;
    logic [IndexBits-1:0]                index;
    logic [EntryBits-1:0]                lo, hi;
    logic signed [EntryBits+Fine+1:0]    chord_product;
    logic signed [EntryBits:0]           chord;
    logic [2:0]                          rounding_saturated;  // never: the formats hold every value

    always_comb begin
      e = '0;
      x_product = '0;
      c = '0;
      ce_product = '0;
      if (valid_i && persp_i) begin
        e = own_entry_i[`CD_WORD_EPS_LSB +: EpsBits];
        if (direction_i < 0) e = -e;
        x_product = (DFrac+EpsBits+2)'($signed({1'b0, weight_i})) * (DFrac+EpsBits+2)'(e);
        c = CBits'($signed({1'b0, weight_i})) * (CBits'(1 <<< DFrac) - CBits'($signed({1'b0, weight_i})));
        ce_product = (CBits+EpsBits)'(c) * (CBits+EpsBits)'(e);
      end
    end

    shift_round #(.InBits(DFrac+EpsBits+2), .OutBits(XBits), .ShiftBits(8), .MaxLeft(XShift < 0 ? -XShift : 0))
      u_round_x (.enable_i(valid_i && persp_i), .in_i(x_product), .shift_i(8'(XShift)), .out_o(x_rounded),
                 .saturated_o(rounding_saturated[0]));
    shift_round #(.InBits(CBits+EpsBits), .OutBits(CeBits), .ShiftBits(8), .MaxLeft(CeShift < 0 ? -CeShift : 0))
      u_round_ce (.enable_i(valid_i && persp_i), .in_i(ce_product), .shift_i(8'(CeShift)), .out_o(ce),
                  .saturated_o(rounding_saturated[1]));

    // 1 / (1 + x) = 2^-shift / m: 1 + x = m 2^shift with m in [1, 2) by its
    // leading one (shift = -1 doubles it; a positive shift truncates m to
    // PFrac fraction bits), then 1/m between ROM entries index and index + 1
    // (f = m - 1).
    always_comb begin
      x = x_rounded;
      if (x_rounded < -(XBits'(1) <<< (PFrac - 1))) x = -(XBits'(1) <<< (PFrac - 1));
      if (x_rounded > (XBits'(1) <<< (PFrac + EpsInt - 2)) - XBits'(1)) x = (XBits'(1) <<< (PFrac + EpsInt - 2)) - XBits'(1);
      y = (XBits'(1) <<< PFrac) + $unsigned(x);
      shift = -ShiftBits'(1);
      for (int b = PFrac; b < XBits; b++)
        if (y[b]) shift = ShiftBits'(b - PFrac);
      // f = m - 1: the fraction bits of m.
      if (shift < 0) f = PFrac'({y, 1'b0});
      else f = PFrac'(y >> shift[ShiftBits-2:0]);
      index = IndexBits'(f >> Fine);
      lo = Rom[32'(index) * EntryBits +: EntryBits];
      hi = Rom[(32'(index) + 1) * EntryBits +: EntryBits];
      chord_product = ((EntryBits+Fine+2)'($signed({1'b0, hi})) - (EntryBits+Fine+2)'($signed({1'b0, lo}))) *
                      (EntryBits+Fine+2)'($signed({1'b0, f & PFrac'((1 <<< Fine) - 1)}));
    end

    shift_round #(.InBits(EntryBits+Fine+2), .OutBits(EntryBits+1), .ShiftBits(8), .MaxLeft(0))
      u_round_chord (.enable_i(valid_i && persp_i), .in_i(chord_product), .shift_i(8'(Fine)), .out_o(chord),
                     .saturated_o(rounding_saturated[2]));

    always_comb begin
      r = (EntryBits+2)'($signed({1'b0, lo})) + (EntryBits+2)'(chord);
      t_shift = 8'(TShift) + 8'(shift);
      eps_used_saturated = persp_i && own_entry_i[`CD_WORD_EPS_SATURATED_BIT];
    end

`ifndef SYNTHESIS
    always_comb begin
      if (valid_i && persp_i)
        assert (rounding_saturated == '0)
          else $error("correction_adder: a cd-persp intermediate left its format (%b)", rounding_saturated);
    end
`else
    logic unused_rounding;
    assign unused_rounding = ^rounding_saturated;
`endif
  end else begin : gen_linear
    assign ce = '0;
    assign r = '0;
    assign t_shift = '0;
    assign eps_used_saturated = 1'b0;
    logic unused_persp;
    assign unused_persp = ^{persp_i, direction_i};
  end
  // The neighbour's eps is never read: only the own line's eps enters t'.
  if (HasPersp) begin : gen_unused_eps
    logic unused_eps;
    assign unused_eps = ^{own_entry_i[WordBits-1:`CD_WORD_BITS], neighbour_entry_i[WordBits-1:`CD_WORD_BITS]};
  end

  always_comb begin
    own_u = '0;
    own_v = '0;
    other_u = '0;
    other_v = '0;
    neighbour_usable = 1'b0;
    own_saturated = 1'b0;
    own_depth_range = 1'b0;
    dropped = 1'b0;
    eps_saturated_used = 1'b0;
    if (valid_i) begin
      own_u = line_value(own_entry_i[`CD_WORD_TU_LSB +: TBits], own_entry_i[`CD_WORD_SU_LSB +: SBits], offset_i);
      own_v = line_value(own_entry_i[`CD_WORD_TV_LSB +: TBits], own_entry_i[`CD_WORD_SV_LSB +: SBits], offset_i);
      other_u = line_value(neighbour_entry_i[`CD_WORD_TU_LSB +: TBits],
                           neighbour_entry_i[`CD_WORD_SU_LSB +: SBits], offset_i);
      other_v = line_value(neighbour_entry_i[`CD_WORD_TV_LSB +: TBits],
                           neighbour_entry_i[`CD_WORD_SV_LSB +: SBits], offset_i);
      // A flagged neighbour is never used: it would spread a bad value.
      neighbour_usable = HasCorrection && correct_i && !neighbour_entry_i[`CD_WORD_SATURATED_BIT] &&
                         !neighbour_entry_i[`CD_WORD_DEPTH_RANGE_BIT];
      own_saturated = own_entry_i[`CD_WORD_SATURATED_BIT];
      own_depth_range = own_entry_i[`CD_WORD_DEPTH_RANGE_BIT];
      dropped = HasCorrection && correct_i && !neighbour_usable;
      // A saturated eps counts where it is used: a pixel corrected with it.
      eps_saturated_used = neighbour_usable && eps_used_saturated;
    end
  end

  // ---- the register between A and B (Stages = 2), or wires
  localparam int ValuesBits = 4 * ValueBits + 5;  // the line values and the flags' bits
  localparam int ABits = ValuesBits + WeightBits + 1 + CeBits + EntryBits + 2 + 8;
  logic [ABits-1:0]            a_d, a_q;
  logic [ValuesBits-1:0]       a_values;
  logic [WeightBits-1:0]       a_weight;
  logic                        a_persp, a_valid;
  logic signed [CeBits-1:0]    a_ce;
  logic signed [EntryBits+1:0] a_r;
  logic signed [7:0]           a_t_shift;
  assign a_d = {own_u, own_v, other_u, other_v, neighbour_usable, own_saturated, own_depth_range, dropped,
                eps_saturated_used, weight_i, persp_i, ce, r, t_shift};
  // Each register loads only with a pixel: between pixels it keeps its last
  // one, unread (its valid is low).
  context_register #(.Bits(ABits), .Present(Stages > 1)) u_stage_a (
    .clk_i, .load_i(advance_i && valid_i), .d_i(a_d), .q_o(a_q));
  assign {a_values, a_weight, a_persp, a_ce, a_r, a_t_shift} = a_q;

  // ---- B: the weight applied
  logic [AppliedBits-1:0]      applied_weight;
  if (HasPersp && HasCorrection) begin : gen_persp_weight
    logic signed [CeBits+EntryBits+1:0]  cer_product;
    logic signed [TpBits-1:0]            cer, t;
    logic                                rounding_saturated;  // never: the formats hold every value
    assign cer_product = a_valid && a_persp ? (CeBits+EntryBits+2)'(a_ce) * (CeBits+EntryBits+2)'(a_r) : '0;
    // c e / m 2^-shift, rounded once to d_frac bits.
    shift_round #(.InBits(CeBits+EntryBits+2), .OutBits(TpBits), .ShiftBits(8),
                  .MaxLeft(TShift < 1 ? 1 - TShift : 0))
      u_round_t (.enable_i(a_valid && a_persp), .in_i(cer_product), .shift_i(a_t_shift), .out_o(cer),
                 .saturated_o(rounding_saturated));
    // t' = |d| + c e r, clamped to [0, 1], where the true t' lies.
    always_comb begin
      t = TpBits'($signed({1'b0, a_weight})) + cer;
      if (t < 0) t = '0;
      if (t > TpBits'(1 <<< DFrac)) t = TpBits'(1 <<< DFrac);
      applied_weight = AppliedBits'($unsigned(a_weight));
      if (a_persp) applied_weight = AppliedBits'(t);
    end
`ifndef SYNTHESIS
    always_comb begin
      if (a_valid && a_persp)
        assert (!rounding_saturated) else $error("correction_adder: cd-persp's c e r left its format");
    end
`else
    logic unused_rounding;
    assign unused_rounding = rounding_saturated;
`endif
  end else begin : gen_linear_weight
    assign applied_weight = AppliedBits'(a_weight);
    logic unused_weight;
    assign unused_weight = ^{a_persp, a_ce, a_r, a_t_shift};
  end

  // ---- the register between B and C (Stages >= 1), or wires
  localparam int BBits = ValuesBits + AppliedBits;
  logic [BBits-1:0]            b_q;
  logic signed [ValueBits-1:0] s_own_u, s_own_v, s_other_u, s_other_v;
  logic [AppliedBits-1:0]      s_weight;
  logic                        s_valid, s_usable, s_saturated, s_depth_range, s_dropped, s_eps_saturated;
  context_register #(.Bits(BBits), .Present(Stages > 0)) u_stage_b (
    .clk_i, .load_i(advance_i && a_valid), .d_i({a_values, applied_weight}), .q_o(b_q));
  // The valid bits of the two registers.
  if (Stages > 1) begin : gen_valid_a
    logic valid_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) valid_q <= 1'b0;
      else if (advance_i) valid_q <= valid_i;
    end
    assign a_valid = valid_q;
  end else begin : gen_no_valid_a
    assign a_valid = valid_i;
  end
  if (Stages > 0) begin : gen_valid_b
    logic valid_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) valid_q <= 1'b0;
      else if (advance_i) valid_q <= a_valid;
    end
    assign s_valid = valid_q;
  end else begin : gen_no_valid_b
    logic unused_reset;
    assign unused_reset = ^{rst_ni, advance_i};
    assign s_valid = a_valid;
  end
  assign {s_own_u, s_own_v, s_other_u, s_other_v, s_usable, s_saturated, s_depth_range, s_dropped,
          s_eps_saturated, s_weight} = b_q;
  assign valid_o = s_valid;

  // ---- C: the correction, rounding and saturation
  logic signed [SumBits-1:0]   sum_u, sum_v;
  logic                        saturated_u, saturated_v;

  always_comb begin
    sum_u = '0;
    sum_v = '0;
    if (s_valid) begin
      sum_u = SumBits'(s_own_u);
      sum_v = SumBits'(s_own_v);
      if (s_usable) begin
        sum_u = corrected(s_own_u, s_other_u, s_weight);
        sum_v = corrected(s_own_v, s_other_v, s_weight);
      end
    end
  end

  // To the output format: round to nearest (ties up), saturate, flag.
  shift_round #(.InBits(SumBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(OutLeft))
    u_narrow_u (.enable_i(s_valid), .in_i(sum_u), .shift_i(8'(OutShift)), .out_o(u_o), .saturated_o(saturated_u));
  shift_round #(.InBits(SumBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(OutLeft))
    u_narrow_v (.enable_i(s_valid), .in_i(sum_v), .shift_i(8'(OutShift)), .out_o(v_o), .saturated_o(saturated_v));

  always_comb begin
    flags_o = '0;
    if (s_valid) begin
      flags_o[`CD_FLAG_TABLE_SATURATED] = s_saturated || s_eps_saturated;
      flags_o[`CD_FLAG_DEPTH_RANGE] = s_depth_range;
      flags_o[`CD_FLAG_NEIGHBOUR_DROPPED] = s_dropped;
      flags_o[`CD_FLAG_OUTPUT_SATURATED] = saturated_u || saturated_v;
    end
  end

endmodule

`default_nettype wire
