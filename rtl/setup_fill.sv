// Setup engine, stage E and the table fill (rtl/setup_engine.sv): q, U and V
// on the first line of the first band, then one line per fill_valid_i cycle
// into the reciprocal pipeline, and RecipLatency cycles later (one more with
// fill_product_register, CD_FILL_LATENCY in all) the line's table word,
// T = U_k / q_k and S = SU / q_k (cd-persp: and eps = q_line / q_k). Twin of
// cdsim::fill_line (model/setup_engine.cpp). Stage E's product
// (results CD_SETUP_Q_LINE .. CD_SETUP_V_LINE) is read in stage_i.
`include "cd_widths.svh"
`default_nettype none

module setup_fill #(
  parameter int SramDepth = `CD_TABLE_DEPTH,
  // The fill keeps its own copy of what it needs, loaded by fill_load_i
  // (setup_engine.sv); without it, it reads the setup engine's registers and
  // starts at stage E.
  parameter bit FillContext = 1'b0,
  parameter bit HasPersp = 1'b0,
  localparam int AddrBits = $clog2(SramDepth),
  localparam int WordBits = HasPersp ? `CD_PERSP_WORD_BITS : `CD_WORD_BITS,
  localparam int PlaneRefQBits  = `CD_PLANE_REF_Q_BITS,
  localparam int PlaneRefUvBits = `CD_PLANE_REF_UV_BITS,
  localparam int PlaneStepQBits  = `CD_PLANE_STEP_Q_BITS,
  localparam int PlaneStepUvBits = `CD_PLANE_STEP_UV_BITS,
  localparam int StepUvBits   = `CD_STEP_UV_BITS,
  localparam int LineBits     = `CD_LINE_BITS,
  localparam int PhaseFrac    = `CD_LINE_PHASE_FRAC,
  localparam int PhaseBits    = PhaseFrac > 0 ? PhaseFrac : 1,
  localparam int AccBits      = `CD_SETUP_ACC_BITS,
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS,
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS,
  localparam int FirstResult  = `CD_SETUP_Q_LINE,
  localparam int Results      = `CD_SETUP_RESULT_COUNT - `CD_SETUP_Q_LINE,
  localparam int FirstTerm    = `CD_SETUP_TERM_Q_LINE,
  localparam int Terms        = `CD_SETUP_TERM_COUNT - `CD_SETUP_TERM_Q_LINE
) (
  input  logic                             clk_i,
  input  logic                             rst_ni,
  input  logic                             hold_i,
  input  logic                             stage_i,
  // Stage D's registers and the triangle's guard (correction: one line more
  // on each side of a band).
  input  logic signed [PlaneRefQBits-1:0]  q_at_ref_i,
  input  logic signed [PlaneRefUvBits-1:0] u_at_ref_i,
  input  logic signed [PlaneRefUvBits-1:0] v_at_ref_i,
  input  logic signed [PlaneStepQBits-1:0] q_per_line_i,
  input  logic signed [PlaneStepUvBits-1:0] u_per_line_i,
  input  logic signed [PlaneStepUvBits-1:0] v_per_line_i,
  input  logic signed [StepUvBits-1:0]     step_u_i,
  input  logic signed [StepUvBits-1:0]     step_v_i,
  input  logic signed [LineBits-1:0]       line_lo_i,
  input  logic [PhaseBits-1:0]             line_phase_i,  // CD_LINE_PHASE_FRAC fraction bits of a gap
  input  logic                             guard_i,
  input  logic [Results*AccBits-1:0]       products_i,
  output logic [Terms*OperandABits-1:0]    term_a_o,
  output logic [Terms*OperandBBits-1:0]    term_b_o,
  // Fill: one line per cycle; fill_last_i marks the band's last line.
  input  logic                             fill_load_i,
  input  logic                             fill_valid_i,
  input  logic                             fill_last_i,
  input  logic [AddrBits-1:0]              fill_addr_i,
  output logic                             write_valid_o,
  output logic [AddrBits-1:0]              write_addr_o,
  output logic [WordBits-1:0]              write_entry_o
);

  localparam int UvInFrac     = `CD_UV_IN_FRAC;
  localparam int RecipBits    = `CD_RECIP_BITS;
  localparam int TFrac        = `CD_T_FRAC;
  localparam int SFrac        = `CD_S_FRAC;
  localparam int FillQBits    = `CD_FILL_Q_BITS;
  localparam int FillUvBits   = `CD_FILL_UV_BITS;
  localparam int ExponentBits = `CD_EXPONENT_BITS;
  localparam int TBits        = `CD_T_BITS;
  localparam int SBits        = `CD_S_BITS;
  // The quotients (cdsim::quotient): each numerator narrowed by the line's
  // exponent e to its format's fraction bits plus Guard, and one integer bit
  // more; its product with the reciprocal read with RecipBits + that many
  // fraction bits, so rounded by the constant QuotientShift.
  localparam int Guard        = `CD_QUOTIENT_GUARD_BITS;
  localparam int EpsFrac      = `CD_EPS_FRAC;
  localparam int EpsBits      = `CD_EPS_BITS;
  localparam int OperandTBits = TBits + 1 + Guard;
  localparam int OperandSBits = SBits + 1 + Guard;
  localparam int OperandEpsBits = EpsBits + 1 + Guard;
  localparam int OperandTFrac = TFrac + Guard;
  localparam int OperandSFrac = SFrac + Guard;
  localparam int OperandEpsFrac = EpsFrac + Guard;
  localparam int ProductTBits = OperandTBits + RecipBits + 2;      // U_k R
  localparam int ProductSBits = OperandSBits + RecipBits + 2;      // SU R
  localparam int ProductEpsBits = OperandEpsBits + RecipBits + 2;  // q_line R
  localparam int ProductShiftBits = 10;  // e + uv_in_frac - frac - guard lies in (-64, 256)
  localparam logic signed [ProductShiftBits-1:0] QuotientShift = ProductShiftBits'(RecipBits + Guard);
  // The largest left shifts of the numerators (at e = 0).
  localparam int MaxTLeft = OperandTFrac > UvInFrac ? OperandTFrac - UvInFrac : 0;
  localparam int MaxSLeft = OperandSFrac > UvInFrac ? OperandSFrac - UvInFrac : 0;
  localparam int MaxEpsLeft = OperandEpsFrac;

  // Stage E's operands: the first line of the first band, line_lo - guard,
  // plus the phase (cdsim::plane_on_line): (line 2^PhaseFrac + phi) per_line,
  // rounded to nearest by PhaseFrac bits below.
  logic signed [LineBits-1:0] first_line;
  logic signed [LineBits+PhaseFrac-1:0] first_position;
  assign first_line = line_lo_i - LineBits'($signed({1'b0, guard_i}));
  if (PhaseFrac > 0) begin : gen_phase
    assign first_position = {first_line, line_phase_i};
  end else begin : gen_no_phase
    assign first_position = first_line;
    logic unused_phase;
    assign unused_phase = ^line_phase_i;
  end
  // A stage E product, rounded to nearest by PhaseFrac bits (ties toward +inf).
  function automatic logic signed [AccBits-1:0] on_line(input logic signed [AccBits-1:0] product);
    on_line = PhaseFrac > 0 ? (product + AccBits'(1 <<< (PhaseFrac > 0 ? PhaseFrac - 1 : 0))) >>> PhaseFrac
                            : product;
  endfunction
  always_comb begin
    term_a_o = '0;
    term_b_o = '0;
    term_a_o[OperandABits*(`CD_SETUP_TERM_Q_LINE - FirstTerm) +: OperandABits] = OperandABits'(q_per_line_i);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_LINE - FirstTerm) +: OperandBBits] = OperandBBits'(first_position);
    term_a_o[OperandABits*(`CD_SETUP_TERM_U_LINE - FirstTerm) +: OperandABits] = OperandABits'(u_per_line_i);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_U_LINE - FirstTerm) +: OperandBBits] = OperandBBits'(first_position);
    term_a_o[OperandABits*(`CD_SETUP_TERM_V_LINE - FirstTerm) +: OperandABits] = OperandABits'(v_per_line_i);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_V_LINE - FirstTerm) +: OperandBBits] = OperandBBits'(first_position);
  end

  // q, U, V on the line being issued: loaded with the first line of the first
  // band (line_lo - guard), stepped by one line per issue; after a band's last
  // line it steps back 2 guard lines to the next band's first.
  logic signed [FillQBits-1:0]     q_line_d, q_line_q;
  logic signed [FillUvBits-1:0]    u_line_d, u_line_q, v_line_d, v_line_q;
  logic                            load;
  // What the fill reads while it runs: the setup engine's registers, or its copy.
  logic signed [PlaneStepQBits-1:0]  fill_q_per_line;
  logic signed [PlaneStepUvBits-1:0] fill_u_per_line, fill_v_per_line;
  logic signed [StepUvBits-1:0]      fill_step_u, fill_step_v;
  logic                              fill_guard;

  if (FillContext) begin : gen_fill_context
    logic signed [PlaneStepQBits-1:0]  q_per_line_c;
    logic signed [PlaneStepUvBits-1:0] u_per_line_c, v_per_line_c;
    logic signed [StepUvBits-1:0]      step_u_c, step_v_c;
    logic                              guard_c;
    always_ff @(posedge clk_i) begin
      if (fill_load_i) begin
        q_per_line_c <= q_per_line_i;
        u_per_line_c <= u_per_line_i;
        v_per_line_c <= v_per_line_i;
        step_u_c <= step_u_i;
        step_v_c <= step_v_i;
        guard_c <= guard_i;
      end
    end
    assign {fill_q_per_line, fill_u_per_line, fill_v_per_line, fill_step_u, fill_step_v, fill_guard} =
           {q_per_line_c, u_per_line_c, v_per_line_c, step_u_c, step_v_c, guard_c};
    assign load = fill_load_i;
    logic unused_stage;
    assign unused_stage = stage_i;
  end else begin : gen_fill_shared
    assign {fill_q_per_line, fill_u_per_line, fill_v_per_line, fill_step_u, fill_step_v, fill_guard} =
           {q_per_line_i, u_per_line_i, v_per_line_i, step_u_i, step_v_i, guard_i};
    assign load = stage_i;
    logic unused_fill_load;
    assign unused_fill_load = fill_load_i;
  end

  always_comb begin
    q_line_d = q_line_q;
    u_line_d = u_line_q;
    v_line_d = v_line_q;
    if (load) begin
      // at the reference + first line x per line
      q_line_d = FillQBits'(q_at_ref_i) + FillQBits'(on_line(products_i[AccBits*(`CD_SETUP_Q_LINE - FirstResult) +: AccBits]));
      u_line_d = FillUvBits'(u_at_ref_i) + FillUvBits'(on_line(products_i[AccBits*(`CD_SETUP_U_LINE - FirstResult) +: AccBits]));
      v_line_d = FillUvBits'(v_at_ref_i) + FillUvBits'(on_line(products_i[AccBits*(`CD_SETUP_V_LINE - FirstResult) +: AccBits]));
    end else if (fill_valid_i) begin
      if (fill_last_i && fill_guard) begin
        q_line_d = q_line_q - FillQBits'(fill_q_per_line);
        u_line_d = u_line_q - FillUvBits'(fill_u_per_line);
        v_line_d = v_line_q - FillUvBits'(fill_v_per_line);
      end else begin
        q_line_d = q_line_q + FillQBits'(fill_q_per_line);
        u_line_d = u_line_q + FillUvBits'(fill_u_per_line);
        v_line_d = v_line_q + FillUvBits'(fill_v_per_line);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    q_line_q <= q_line_d;
    u_line_q <= u_line_d;
    v_line_q <= v_line_d;
  end

  // Issue: q <= 0 raises depth_range and uses q = 1; e = bitlen(q) - 1; the
  // mantissa keeps RecipBits fraction bits, truncated. U and V on the line
  // are narrowed by e at once (cdsim::quotient: to t_frac + guard fraction
  // bits, round to nearest, saturate), so that the reciprocal pipeline
  // carries them at the width of their product, not the fill's.
  localparam int TagBits = AddrBits + 1 + ExponentBits + 2 * OperandTBits + 1;
  logic                       depth_out;
  logic [ExponentBits-1:0]    exponent;
  logic [RecipBits:0]         mantissa;
  logic [TagBits-1:0]         issue_tag, result_tag;
  logic                       result_valid;
  logic [RecipBits:0]         recip;
  logic signed [ProductShiftBits-1:0] issue_shift_t;
  logic signed [OperandTBits-1:0] issue_tu, issue_tv;
  logic [1:0]                 issue_saturated;

  reciprocal_operand #(
    .QBits(FillQBits), .RecipBits(RecipBits), .ExponentBits(ExponentBits)
  ) u_operand (
    .enable_i   (fill_valid_i),
    .q_i        (q_line_q),
    .depth_out_o(depth_out),
    .exponent_o (exponent),
    .mantissa_o (mantissa)
  );
  assign issue_shift_t = ProductShiftBits'($signed({1'b0, exponent})) + ProductShiftBits'(UvInFrac - OperandTFrac);
  shift_round #(.InBits(FillUvBits), .OutBits(OperandTBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxTLeft))
    u_operand_tu (.enable_i(fill_valid_i), .in_i(u_line_q), .shift_i(issue_shift_t), .out_o(issue_tu),
                  .saturated_o(issue_saturated[0]));
  shift_round #(.InBits(FillUvBits), .OutBits(OperandTBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxTLeft))
    u_operand_tv (.enable_i(fill_valid_i), .in_i(v_line_q), .shift_i(issue_shift_t), .out_o(issue_tv),
                  .saturated_o(issue_saturated[1]));
  assign issue_tag = fill_valid_i ? {fill_addr_i, depth_out, exponent, issue_tu, issue_tv, |issue_saturated} : '0;

  reciprocal #(
    .RecipBits(RecipBits), .Latency(`CD_RECIP_LATENCY), .TagBits(TagBits)
  ) u_reciprocal (
    .clk_i, .rst_ni,
    .advance_i (!hold_i),
    .valid_i   (fill_valid_i),
    .mantissa_i(mantissa),
    .tag_i     (issue_tag),
    .valid_o   (result_valid),
    .recip_o   (recip),
    .tag_o     (result_tag)
  );

  // Result: S's numerators narrowed by e as U and V were; then T = U_k R and
  // S = SU R, each read with RecipBits + frac + guard fraction bits and
  // rounded to its format by a constant shift (round to nearest, saturate,
  // flag).
  logic [AddrBits-1:0]              result_addr;
  logic                             result_depth_out;
  logic [ExponentBits-1:0]          result_exponent;
  logic signed [OperandTBits-1:0]   operand_tu, operand_tv;
  logic                             operand_t_saturated;
  logic signed [OperandSBits-1:0]   operand_su, operand_sv;
  logic signed [ProductTBits-1:0]   product_tu, product_tv;
  logic signed [ProductSBits-1:0]   product_su, product_sv;
  logic signed [ProductShiftBits-1:0] shift_s;
  logic signed [TBits-1:0]          t_u, t_v;
  logic signed [SBits-1:0]          s_u, s_v;
  logic [1:0]                       s_operand_saturated;  // S's numerators narrowed
  logic [3:0]                       entry_saturated;      // the products rounded

  always_comb begin
    {result_addr, result_depth_out, result_exponent, operand_tu, operand_tv, operand_t_saturated} =
        result_valid ? result_tag : '0;
    shift_s = result_valid ? ProductShiftBits'($signed({1'b0, result_exponent})) + ProductShiftBits'(UvInFrac - OperandSFrac)
                           : '0;
  end
  shift_round #(.InBits(StepUvBits), .OutBits(OperandSBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxSLeft))
    u_operand_su (.enable_i(result_valid), .in_i(fill_step_u), .shift_i(shift_s), .out_o(operand_su),
                  .saturated_o(s_operand_saturated[0]));
  shift_round #(.InBits(StepUvBits), .OutBits(OperandSBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxSLeft))
    u_operand_sv (.enable_i(result_valid), .in_i(fill_step_v), .shift_i(shift_s), .out_o(operand_sv),
                  .saturated_o(s_operand_saturated[1]));

  always_comb begin
    product_tu = '0;
    product_tv = '0;
    product_su = '0;
    product_sv = '0;
    if (result_valid) begin
      product_tu = ProductTBits'(operand_tu) * ProductTBits'($signed({1'b0, recip}));
      product_tv = ProductTBits'(operand_tv) * ProductTBits'($signed({1'b0, recip}));
      product_su = ProductSBits'(operand_su) * ProductSBits'($signed({1'b0, recip}));
      product_sv = ProductSBits'(operand_sv) * ProductSBits'($signed({1'b0, recip}));
    end
  end

  // cd-persp's eps = q_line R (below): its product and its operand's
  // saturation go through the product stage with the others.
  logic signed [ProductEpsBits-1:0] product_eps, n_product_eps;
  logic                             eps_operand_saturated, n_eps_operand_saturated;

  // The product stage: with fill_product_register the products, and what the
  // word takes beside them, are registered before they are rounded (n_*: the
  // stage's outputs, the same values a cycle later); a held unit keeps them.
  localparam bit ProductRegister = `CD_FILL_PRODUCT_REGISTER != 0;
  localparam int StageBits = AddrBits + 4 + 2 * ProductTBits + 2 * ProductSBits + ProductEpsBits + 1;
  logic                             n_valid;
  logic [AddrBits-1:0]              n_addr;
  logic                             n_depth_out, n_t_saturated;
  logic [1:0]                       n_s_saturated;
  logic signed [ProductTBits-1:0]   n_product_tu, n_product_tv;
  logic signed [ProductSBits-1:0]   n_product_su, n_product_sv;
  context_register #(.Bits(StageBits), .Present(ProductRegister)) u_product_stage (
    .clk_i, .load_i(!hold_i),
    .d_i({result_addr, result_depth_out, operand_t_saturated, s_operand_saturated, product_tu, product_tv,
          product_su, product_sv, product_eps, eps_operand_saturated}),
    .q_o({n_addr, n_depth_out, n_t_saturated, n_s_saturated, n_product_tu, n_product_tv,
          n_product_su, n_product_sv, n_product_eps, n_eps_operand_saturated}));
  if (ProductRegister) begin : gen_product_valid
    logic valid_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) valid_q <= 1'b0;
      else if (!hold_i) valid_q <= result_valid;
    end
    assign n_valid = valid_q;
  end else begin : gen_no_product_valid
    assign n_valid = result_valid;
  end

  shift_round #(.InBits(ProductTBits), .OutBits(TBits), .ShiftBits(ProductShiftBits))
    u_narrow_tu (.enable_i(n_valid), .in_i(n_product_tu), .shift_i(QuotientShift), .out_o(t_u),
                 .saturated_o(entry_saturated[0]));
  shift_round #(.InBits(ProductTBits), .OutBits(TBits), .ShiftBits(ProductShiftBits))
    u_narrow_tv (.enable_i(n_valid), .in_i(n_product_tv), .shift_i(QuotientShift), .out_o(t_v),
                 .saturated_o(entry_saturated[1]));
  shift_round #(.InBits(ProductSBits), .OutBits(SBits), .ShiftBits(ProductShiftBits))
    u_narrow_su (.enable_i(n_valid), .in_i(n_product_su), .shift_i(QuotientShift), .out_o(s_u),
                 .saturated_o(entry_saturated[2]));
  shift_round #(.InBits(ProductSBits), .OutBits(SBits), .ShiftBits(ProductShiftBits))
    u_narrow_sv (.enable_i(n_valid), .in_i(n_product_sv), .shift_i(QuotientShift), .out_o(s_v),
                 .saturated_o(entry_saturated[3]));

  // cd-persp: eps = q_line R: q_line narrowed by e to eps_frac + guard
  // fraction bits, its product read with RecipBits + eps_frac + guard
  // fraction bits, to s2.eps_frac (round to nearest, saturate); its most
  // negative code is moved up by one, so that -eps fits as well, and flagged.
  // eps and its flag are placed in the word here, in a generate block, so
  // that a word without them never names their bits.
  logic [WordBits-1:0] eps_part;
  if (HasPersp) begin : gen_eps
    logic signed [EpsBits-1:0]          eps, eps_rounded;
    logic                               eps_saturated, eps_rounding_saturated;
    logic signed [OperandEpsBits-1:0]   operand_eps;
    logic signed [ProductShiftBits-1:0] shift_eps;
    assign shift_eps = result_valid ? ProductShiftBits'($signed({1'b0, result_exponent})) - ProductShiftBits'(OperandEpsFrac)
                                    : '0;
    shift_round #(.InBits(PlaneStepQBits), .OutBits(OperandEpsBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxEpsLeft))
      u_operand_eps (.enable_i(result_valid), .in_i(fill_q_per_line), .shift_i(shift_eps), .out_o(operand_eps),
                     .saturated_o(eps_operand_saturated));
    always_comb begin
      product_eps = '0;
      if (result_valid) product_eps = ProductEpsBits'(operand_eps) * ProductEpsBits'($signed({1'b0, recip}));
    end
    shift_round #(.InBits(ProductEpsBits), .OutBits(EpsBits), .ShiftBits(ProductShiftBits))
      u_narrow_eps (.enable_i(n_valid), .in_i(n_product_eps), .shift_i(QuotientShift), .out_o(eps_rounded),
                    .saturated_o(eps_rounding_saturated));
    always_comb begin
      eps = eps_rounded;
      eps_saturated = n_eps_operand_saturated || eps_rounding_saturated;
      if (eps_rounded == {1'b1, {(EpsBits - 1){1'b0}}}) begin
        eps = eps_rounded + EpsBits'(1);
        eps_saturated = 1'b1;
      end
    end
    always_comb begin
      eps_part = '0;
      eps_part[`CD_WORD_EPS_LSB +: EpsBits] = eps;
      eps_part[`CD_WORD_EPS_SATURATED_BIT] = eps_saturated;
    end
  end else begin : gen_no_eps
    assign product_eps = '0;
    assign eps_operand_saturated = 1'b0;
    assign eps_part = '0;
    logic unused_eps;
    assign unused_eps = ^{n_product_eps, n_eps_operand_saturated};
  end

  always_comb begin
    write_entry_o = eps_part;
    write_entry_o[`CD_WORD_TU_LSB +: TBits] = t_u;
    write_entry_o[`CD_WORD_TV_LSB +: TBits] = t_v;
    write_entry_o[`CD_WORD_SU_LSB +: SBits] = s_u;
    write_entry_o[`CD_WORD_SV_LSB +: SBits] = s_v;
    write_entry_o[`CD_WORD_SATURATED_BIT] = |entry_saturated || |n_s_saturated || n_t_saturated;
    write_entry_o[`CD_WORD_DEPTH_RANGE_BIT] = n_depth_out;
  end
  assign write_valid_o = n_valid && !hold_i;
  assign write_addr_o = n_addr;

endmodule

`default_nettype wire
