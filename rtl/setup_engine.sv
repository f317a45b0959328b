// Setup engine: plane equations, orientation, slope g, per-triangle
// normalisation, line range and the column walker's edge trackers, then the
// per-line table fill (one reciprocal and four multiplies per line, five for
// cd-persp's eps). Twin of model/setup_engine.cpp; every value follows its
// integer arithmetic exactly, every signal has the width derived for it in
// model/derived_widths.cpp.
//
// This module is the engine's structure: it captures the triangle, decodes
// the stage count, and wires the stages, one module each (setup_stage_a.sv ..
// setup_stage_d.sv, setup_dividers.sv, setup_fill.sv, each the twin of the
// model function of the same name), to the multipliers they share
// (setup_multipliers.sv). Each stage forms its operands in its window,
// reads its sums of products and registers what it forms in its own cycle.
//
// Timing (docs/rtl.md, "Setup engine"): stage_count_i counts the setup cycles
// 0 .. SetupCycles-1 after the triangle is loaded. Each stage reads its sums
// of products (setup_multipliers.sv) and registers what it forms in one
// cycle, CD_SETUP_STAGE_A .. E; with shared multipliers the products run in
// the cycles before it, while the stage's operands hold still (its window).
// With CD_SETUP_MULTIPLIERS = 0 (every product its own multiplier):
//   0        stage A: edges, det, box, q normalisation, U = u q, V = v q
//   1        stage B: plane coefficients, q |det|
//   2        stage C: planes at the reference, orientation, shift; the serial
//            dividers start (g, and per edge its first span end and its step)
//   2 + Div  stage D: divider results, normalised planes, S numerators, line
//            range, edge trackers (CD_SETUP_DIV_DONE: its products start here)
//   3 + Div  stage E: q, U, V on the first line of the first band
// The fill issues one line per fill_valid_i cycle into the reciprocal
// pipeline; RecipLatency cycles later its table word appears on write_*_o.
`include "cd_widths.svh"
`default_nettype none

module setup_engine #(
  // The constant-depth designs' hardware: the slope g and its divider, the
  // line range, the S numerators and the table fill (reciprocal, products).
  parameter bit HasLines = 1'b1,
  // The per-pixel designs' planes along the major axis (q_per_major_o ...).
  parameter bit HasPixelPlanes = 1'b1,
  // The planes of q, U = u q and V = v q and their shared shift (every design
  // but affine, which takes its own planes of u and v from affine_setup).
  parameter bit HasPlanes = 1'b1,
  parameter int SramDepth = `CD_TABLE_DEPTH,
  // The fill keeps its own copy of what it needs (q, U, V on the first line,
  // their steps per line, the S numerators and the guard), loaded by
  // fill_load_i, so that the setup engine can take the next triangle while it
  // fills (cd_scan_unit's fill stage, setup_fifo_depth 2). Without it the fill
  // reads the setup engine's registers and starts at stage E.
  parameter bit FillContext = 1'b0,
  // cd-persp: the fill also writes eps = q_line w_k and its saturation bit
  // into the word (CD_WORD_EPS_LSB, CD_WORD_EPS_SATURATED_BIT).
  parameter bit HasPersp = 1'b0,
  localparam int AddrBits = $clog2(SramDepth),
  localparam int WordBits = HasPersp ? `CD_PERSP_WORD_BITS : `CD_WORD_BITS
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  // Triangle, captured on load_i: vertex n in bits 32n +: 32 (x, y, u, v are
  // sign-extended; q is binary32 1/w).
  input  logic                       load_i,
  input  logic [95:0]                tri_x_i,
  input  logic [95:0]                tri_y_i,
  input  logic [95:0]                tri_q_i,
  input  logic [95:0]                tri_u_i,
  input  logic [95:0]                tri_v_i,
  input  logic [13:0]                viewport_width_i,
  input  logic [13:0]                viewport_height_i,
  input  logic [1:0]                 density_log2_i,
  input  logic                       correction_i,
  // A constant-depth triangle: its lines may take a phase (setup_stage_d.sv).
  input  logic                       lines_i,
  input  logic                       fallback_i,  // the triangle's design has a divide fallback
  // A held unit (a fragment refused): the fill pipeline keeps its contents and
  // writes nothing; the stages, on the held stage count, reload what they hold.
  input  logic                       hold_i,
  input  logic                       setup_i,
  input  logic [`CD_SETUP_COUNT_BITS-1:0] stage_count_i,
  // Results, valid from stage E on.
  output logic                       empty_o,
  output logic                       x_major_o,
  output logic signed [`CD_G_BITS-1:0] g_o,
  output logic [`CD_PIXEL_BITS-1:0]  major_lo_o,
  output logic [`CD_PIXEL_BITS:0]    major_count_o,
  output logic [`CD_PIXEL_BITS-1:0]  minor_lo_o,
  output logic [`CD_PIXEL_BITS-1:0]  minor_hi_o,
  output logic                       no_lines_o,
  output logic                       fallback_o,  // the divide fallback takes the triangle
  output logic signed [`CD_LINE_BITS-1:0] pixel_line_lo_o,
  output logic signed [`CD_LINE_BITS-1:0] pixel_line_hi_o,
  // The lines' phase, CD_LINE_PHASE_FRAC fraction bits of a line gap (one bit when there are none).
  output logic [(`CD_LINE_PHASE_FRAC > 0 ? `CD_LINE_PHASE_FRAC : 1)-1:0] line_phase_o,
  output logic [7:0]                 flags_o,
  // Normalised planes of q, U, V: at the reference pixel, per pixel along the
  // major axis and along the minor axis (per_minor is per line: the minor
  // step at m = 1, which every per-pixel design uses).
  output logic signed [`CD_PLANE_REF_Q_BITS-1:0]   q_at_ref_o,
  output logic signed [`CD_PLANE_REF_UV_BITS-1:0]  u_at_ref_o,
  output logic signed [`CD_PLANE_REF_UV_BITS-1:0]  v_at_ref_o,
  output logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  q_per_major_o,
  output logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_major_o,
  output logic signed [`CD_PLANE_STEP_UV_BITS-1:0] v_per_major_o,
  output logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  q_per_minor_o,
  output logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_minor_o,
  output logic signed [`CD_PLANE_STEP_UV_BITS-1:0] v_per_minor_o,
  // Geometry for affine_setup, valid from stage B: the vertices' u and v as
  // loaded, vertex differences, the determinant and the reference offsets.
  output logic [3*`CD_UV_BITS-1:0]           u_vertex_o,
  output logic [3*`CD_UV_BITS-1:0]           v_vertex_o,
  output logic signed [`CD_DIFF_BITS-1:0]    dx1_o,
  output logic signed [`CD_DIFF_BITS-1:0]    dy1_o,
  output logic signed [`CD_DIFF_BITS-1:0]    dx2_o,
  output logic signed [`CD_DIFF_BITS-1:0]    dy2_o,
  output logic signed [`CD_DET_BITS-1:0]     det_o,
  output logic signed [`CD_DIFF_BITS-1:0]    ref_x_o,
  output logic signed [`CD_DIFF_BITS-1:0]    ref_y_o,
  // Edge trackers for the column walker, edge i in bits i*W +: W.
  output logic [5:0]                 edge_kind_o,    // 2 bits per edge: 0 none, 1 lower, 2 upper
  output logic [3*`CD_EDGE_BOUND_BITS-1:0] edge_bound_o,
  output logic [3*`CD_EDGE_STEP_BITS-1:0]  edge_rem_o,
  output logic [3*`CD_EDGE_STEP_BITS-1:0]  edge_step_o,
  output logic [3*`CD_EDGE_SLOPE_BITS-1:0] edge_slope_o,
  output logic [3*`CD_EDGE_STEP_BITS-1:0]  edge_slope_rem_o,
  // Fill: one line per cycle; fill_last_i marks the band's last line.
  input  logic                       fill_load_i,
  input  logic                       fill_valid_i,
  input  logic                       fill_last_i,
  input  logic [AddrBits-1:0]        fill_addr_i,
  output logic                       write_valid_o,
  output logic [AddrBits-1:0]        write_addr_o,
  output logic [WordBits-1:0]        write_entry_o
);

  localparam int CoordBits    = `CD_COORD_BITS;
  localparam int UvBits       = `CD_UV_BITS;
  localparam int DiffBits     = `CD_DIFF_BITS;
  localparam int DetBits      = `CD_DET_BITS;
  localparam int EdgeCBits    = `CD_EDGE_C_BITS;
  localparam int PixelBits    = `CD_PIXEL_BITS;
  localparam int SubpixelBits = `CD_SUBPIXEL_BITS;
  localparam int GFrac        = `CD_G_FRAC;
  localparam int QVertexBits  = `CD_Q_VERTEX_BITS;
  localparam int AttrUvBits   = `CD_ATTR_UV_BITS;
  localparam int CoefQBits    = `CD_COEF_Q_BITS;
  localparam int CoefUvBits   = `CD_COEF_UV_BITS;
  localparam int ExactRefQBits  = `CD_EXACT_REF_Q_BITS;
  localparam int ExactRefUvBits = `CD_EXACT_REF_UV_BITS;
  localparam int PeakBits     = `CD_PEAK_BITS;
  localparam int ShiftBits    = `CD_SHIFT_BITS;
  localparam int PlaneStepQBits  = `CD_PLANE_STEP_Q_BITS;
  localparam int PlaneStepUvBits = `CD_PLANE_STEP_UV_BITS;
  localparam int StepUvBits   = `CD_STEP_UV_BITS;
  localparam int LineBits     = `CD_LINE_BITS;
  localparam int EdgeNBits    = `CD_EDGE_N_BITS;
  localparam int GDivQuoBits  = `CD_G_DIV_QUOTIENT_BITS;
  localparam int BoundDivQuoBits = `CD_BOUND_DIV_QUOTIENT_BITS;
  localparam int SlopeDivQuoBits = `CD_SLOPE_DIV_QUOTIENT_BITS;
  localparam int CountBits    = `CD_SETUP_COUNT_BITS;
  localparam int StageA       = `CD_SETUP_STAGE_A;
  localparam int StageB       = `CD_SETUP_STAGE_B;
  localparam int StageC       = `CD_SETUP_STAGE_C;
  localparam int DivDone      = `CD_SETUP_DIV_DONE;
  localparam int StageD       = `CD_SETUP_STAGE_D;
  localparam int StageE       = `CD_SETUP_STAGE_E;
  localparam int TermCount    = `CD_SETUP_TERM_COUNT;
  localparam int ResultCount  = `CD_SETUP_RESULT_COUNT;
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS;
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS;
  localparam int AccBits      = `CD_SETUP_ACC_BITS;
  localparam int GDivNumBits  = CoefQBits + GFrac + 1;
  localparam int GDivDenBits  = CoefQBits;
  localparam int FreeBits     = DiffBits - 1;
  localparam int BoundNumBits = EdgeNBits - SubpixelBits;
  // Each stage's results and terms, in the order of model/setup_terms.def.
  localparam int ResultB = `CD_SETUP_Q_COEF_X, ResultC = `CD_SETUP_Q_REF;
  localparam int ResultD = `CD_SETUP_STEP_U,   ResultE = `CD_SETUP_Q_LINE;
  localparam int TermB = `CD_SETUP_TERM_Q_COEF_X, TermC = `CD_SETUP_TERM_Q_REF;
  localparam int TermD = `CD_SETUP_TERM_STEP_U,   TermE = `CD_SETUP_TERM_Q_LINE;

  localparam int FlagDepthRange = `CD_FLAG_DEPTH_RANGE;

  // ---------------------------------------------------------------- triangle
  logic [3*CoordBits-1:0]      x_q, y_q;
  logic [3*UvBits-1:0]         u_q, v_q;
  logic [95:0]                 qf_q;
  logic [13:0]                 viewport_width_q, viewport_height_q;
  logic [1:0]                  density_log2_q;
  logic                        guard_q;
  logic                        lines_q, fallback_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      x_q <= '0;
      y_q <= '0;
      u_q <= '0;
      v_q <= '0;
      qf_q <= '0;
      viewport_width_q <= '0;
      viewport_height_q <= '0;
      density_log2_q <= '0;
      guard_q <= 1'b0;
      lines_q <= 1'b0;
      fallback_q <= 1'b0;
    end else if (load_i) begin
      for (int i = 0; i < 3; i++) begin
        x_q[CoordBits*i +: CoordBits] <= tri_x_i[32*i +: CoordBits];
        y_q[CoordBits*i +: CoordBits] <= tri_y_i[32*i +: CoordBits];
        u_q[UvBits*i +: UvBits] <= tri_u_i[32*i +: UvBits];
        v_q[UvBits*i +: UvBits] <= tri_v_i[32*i +: UvBits];
      end
      qf_q <= tri_q_i;
      viewport_width_q <= viewport_width_i;
      viewport_height_q <= viewport_height_i;
      density_log2_q <= density_log2_i;
      guard_q <= correction_i;
      lines_q <= lines_i;
      fallback_q <= fallback_i;
    end
  end

  logic stage_a, stage_b, stage_c, stage_d, stage_e, stage_d_kappa;
  logic window_a, window_b, window_c, window_d;
  assign stage_a = setup_i && stage_count_i == CountBits'(StageA);
  assign stage_b = setup_i && stage_count_i == CountBits'(StageB);
  assign stage_c = setup_i && stage_count_i == CountBits'(StageC);
  assign stage_d = setup_i && stage_count_i == CountBits'(StageD);
  assign stage_e = setup_i && stage_count_i == CountBits'(StageE);
  // Stage D's kappa extremes: a cycle before stage D with setup_line_register.
  assign stage_d_kappa = setup_i && stage_count_i == CountBits'(StageD - `CD_SETUP_LINE_REGISTER);
  // A stage's operands are formed from its first product cycle to its own.
  assign window_a = setup_i && stage_count_i <= CountBits'(StageA);
  assign window_b = setup_i && stage_count_i > CountBits'(StageA) && stage_count_i <= CountBits'(StageB);
  assign window_c = setup_i && stage_count_i > CountBits'(StageB) && stage_count_i <= CountBits'(StageC);
  assign window_d = setup_i && stage_count_i >= CountBits'(DivDone) && stage_count_i <= CountBits'(StageD);

  // The sums of products of every stage (model/setup_terms.def): operands in,
  // results out, on the shared multipliers or on one multiplier each. Outside
  // its window a stage's operands are zero, and so are its products; stage
  // E's are registers that hold until the next triangle's stage D, since the
  // fill may load them after setup.
  logic [TermB*OperandABits-1:0]               term_a_a;
  logic [TermB*OperandBBits-1:0]               term_b_a;
  logic [(TermC-TermB)*OperandABits-1:0]       term_a_b;
  logic [(TermC-TermB)*OperandBBits-1:0]       term_b_b;
  logic [(TermD-TermC)*OperandABits-1:0]       term_a_c;
  logic [(TermD-TermC)*OperandBBits-1:0]       term_b_c;
  logic [(TermE-TermD)*OperandABits-1:0]       term_a_d;
  logic [(TermE-TermD)*OperandBBits-1:0]       term_b_d;
  logic [(TermCount-TermE)*OperandABits-1:0]   term_a_e;
  logic [(TermCount-TermE)*OperandBBits-1:0]   term_b_e;
  logic [ResultCount*AccBits-1:0]              products;
  setup_multipliers u_multipliers (
    .clk_i,
    .hold_i,
    .setup_i,
    .stage_count_i,
    .a_i          ({term_a_e, term_a_d, term_a_c, term_a_b, term_a_a}),
    .b_i          ({term_b_e, term_b_d, term_b_c, term_b_b, term_b_a}),
    .result_o     (products)
  );

  // ---------------------------------------------------------------- stage A
  logic signed [DiffBits-1:0]   dx1_q, dy1_q, dx2_q, dy2_q;
  logic signed [DetBits-1:0]    det_q;
  logic [3*DiffBits-1:0]        edge_a_q, edge_b_q;
  logic [3*EdgeCBits-1:0]       edge_c_q;
  logic [2:0]                   edge_threshold_q;
  logic                         empty_q;
  logic [PixelBits-1:0]         box_x_lo_q, box_x_hi_q, box_y_lo_q, box_y_hi_q;
  logic signed [DiffBits-1:0]   ref_x_q, ref_y_q;
  logic [3*QVertexBits-1:0]     q_vertex_q;
  logic [3*AttrUvBits-1:0]      u_attr_q, v_attr_q;
  logic                         depth_range_q;

  setup_stage_a #(.HasPlanes(HasPlanes)) u_stage_a (
    .clk_i, .rst_ni,
    .window_i         (window_a),
    .stage_i          (stage_a),
    .x_i              (x_q),
    .y_i              (y_q),
    .u_i              (u_q),
    .v_i              (v_q),
    .qf_i             (qf_q),
    .viewport_width_i (viewport_width_q),
    .viewport_height_i(viewport_height_q),
    .products_i       (products[0 +: ResultB*AccBits]),
    .term_a_o         (term_a_a),
    .term_b_o         (term_b_a),
    .dx1_o            (dx1_q),
    .dy1_o            (dy1_q),
    .dx2_o            (dx2_q),
    .dy2_o            (dy2_q),
    .det_o            (det_q),
    .edge_a_o         (edge_a_q),
    .edge_b_o         (edge_b_q),
    .edge_c_o         (edge_c_q),
    .edge_threshold_o (edge_threshold_q),
    .empty_o          (empty_q),
    .box_x_lo_o       (box_x_lo_q),
    .box_x_hi_o       (box_x_hi_q),
    .box_y_lo_o       (box_y_lo_q),
    .box_y_hi_o       (box_y_hi_q),
    .ref_x_o          (ref_x_q),
    .ref_y_o          (ref_y_q),
    .q_vertex_o       (q_vertex_q),
    .u_attr_o         (u_attr_q),
    .v_attr_o         (v_attr_q),
    .depth_range_o    (depth_range_q)
  );

  // ---------------------------------------------------------------- stage B
  logic signed [CoefQBits-1:0]  q_coef_x_q, q_coef_y_q;
  logic signed [CoefUvBits-1:0] u_coef_x_q, u_coef_y_q, v_coef_x_q, v_coef_y_q;
  logic [PeakBits-1:0]          q_peak_q, q_floor_q;
  logic signed [DetBits-1:0]    det_abs_q;

  setup_stage_b #(.HasPlanes(HasPlanes)) u_stage_b (
    .clk_i,
    .window_i   (window_b),
    .stage_i    (stage_b),
    .dx1_i      (dx1_q),
    .dy1_i      (dy1_q),
    .dx2_i      (dx2_q),
    .dy2_i      (dy2_q),
    .det_i      (det_q),
    .q_vertex_i (q_vertex_q),
    .u_attr_i   (u_attr_q),
    .v_attr_i   (v_attr_q),
    .products_i (products[ResultB*AccBits +: (ResultC-ResultB)*AccBits]),
    .term_a_o   (term_a_b),
    .term_b_o   (term_b_b),
    .q_coef_x_o (q_coef_x_q),
    .q_coef_y_o (q_coef_y_q),
    .u_coef_x_o (u_coef_x_q),
    .u_coef_y_o (u_coef_y_q),
    .v_coef_x_o (v_coef_x_q),
    .v_coef_y_o (v_coef_y_q),
    .q_peak_o   (q_peak_q),
    .q_floor_o  (q_floor_q),
    .det_abs_o  (det_abs_q)
  );

  // ---------------------------------------------------------------- stage C
  logic [GDivNumBits-1:0]           g_div_num;
  logic [GDivDenBits-1:0]           g_div_den;
  logic [3*BoundNumBits-1:0]        edge_n_high_abs;
  logic [3*FreeBits-1:0]            edge_free_abs, edge_fixed_abs;
  logic signed [ExactRefQBits-1:0]  q_ref_q;
  logic signed [ExactRefUvBits-1:0] u_ref_q, v_ref_q;
  logic                             x_major_q;
  logic signed [ShiftBits-1:0]      shift_q;
  logic                             g_zero_q, g_negative_q;
  logic [3*DiffBits-1:0]            edge_fixed_q, edge_free_q;
  logic [3*BoundNumBits-1:0]        edge_n_high_q;
  logic [3*SubpixelBits-1:0]        edge_n_low_q;

  setup_stage_c #(.HasPlanes(HasPlanes)) u_stage_c (
    .clk_i,
    .window_i          (window_c),
    .stage_i           (stage_c),
    .edge_a_i          (edge_a_q),
    .edge_b_i          (edge_b_q),
    .edge_c_i          (edge_c_q),
    .edge_threshold_i  (edge_threshold_q),
    .box_x_lo_i        (box_x_lo_q),
    .box_y_lo_i        (box_y_lo_q),
    .ref_x_i           (ref_x_q),
    .ref_y_i           (ref_y_q),
    .q_vertex0_i       (q_vertex_q[0 +: QVertexBits]),
    .u_attr0_i         (u_attr_q[0 +: AttrUvBits]),
    .v_attr0_i         (v_attr_q[0 +: AttrUvBits]),
    .q_coef_x_i        (q_coef_x_q),
    .q_coef_y_i        (q_coef_y_q),
    .u_coef_x_i        (u_coef_x_q),
    .u_coef_y_i        (u_coef_y_q),
    .v_coef_x_i        (v_coef_x_q),
    .v_coef_y_i        (v_coef_y_q),
    .q_peak_i          (q_peak_q),
    .det_abs_i         (det_abs_q),
    .products_i        (products[ResultC*AccBits +: (ResultD-ResultC)*AccBits]),
    .term_a_o          (term_a_c),
    .term_b_o          (term_b_c),
    .g_div_num_o       (g_div_num),
    .g_div_den_o       (g_div_den),
    .edge_n_high_abs_o (edge_n_high_abs),
    .edge_free_abs_o   (edge_free_abs),
    .edge_fixed_abs_o  (edge_fixed_abs),
    .q_ref_o           (q_ref_q),
    .u_ref_o           (u_ref_q),
    .v_ref_o           (v_ref_q),
    .x_major_o         (x_major_q),
    .shift_o           (shift_q),
    .g_zero_o          (g_zero_q),
    .g_negative_o      (g_negative_q),
    .edge_fixed_o      (edge_fixed_q),
    .edge_free_o       (edge_free_q),
    .edge_n_high_o     (edge_n_high_q),
    .edge_n_low_o      (edge_n_low_q)
  );

  // ---------------------------------------------------------------- dividers
  // All start in stage C and finish by stage D (DivCycles later).
  logic [GDivQuoBits-1:0]       g_quotient;
  logic [GDivDenBits-1:0]       g_remainder;
  logic                         g_overflow;
  logic [3*BoundDivQuoBits-1:0] bound_quotient;
  logic [3*FreeBits-1:0]        bound_remainder, slope_remainder;
  logic [3*SlopeDivQuoBits-1:0] slope_quotient;
  logic [2:0]                   bound_overflow, slope_overflow;

  setup_dividers #(.HasLines(HasLines)) u_dividers (
    .clk_i, .rst_ni,
    .start_i          (stage_c),
    .g_num_i          (g_div_num),
    .g_den_i          (g_div_den),
    .bound_num_i      (edge_n_high_abs),
    .free_i           (edge_free_abs),
    .fixed_i          (edge_fixed_abs),
    .g_quotient_o     (g_quotient),
    .g_remainder_o    (g_remainder),
    .g_overflow_o     (g_overflow),
    .bound_quotient_o (bound_quotient),
    .bound_remainder_o(bound_remainder),
    .slope_quotient_o (slope_quotient),
    .slope_remainder_o(slope_remainder),
    .bound_overflow_o (bound_overflow),
    .slope_overflow_o (slope_overflow)
  );

  // ---------------------------------------------------------------- stage D
  logic signed [LineBits-1:0]        line_lo_q;
  logic signed [PlaneStepQBits-1:0]  q_per_line_q;
  logic signed [PlaneStepUvBits-1:0] u_per_line_q, v_per_line_q;
  logic signed [StepUvBits-1:0]      step_u_q, step_v_q;
  logic [11:0]                       normalise_saturated;

  setup_stage_d #(.HasLines(HasLines), .HasPixelPlanes(HasPixelPlanes), .HasPlanes(HasPlanes)) u_stage_d (
    .clk_i,
    .window_i          (window_d),
    .stage_i           (stage_d),
    .kappa_stage_i     (stage_d_kappa),
    .x_i               (x_q),
    .y_i               (y_q),
    .density_log2_i    (density_log2_q),
    .lines_i           (lines_q),
    .fallback_i        (fallback_q),
    .box_x_lo_i        (box_x_lo_q),
    .box_x_hi_i        (box_x_hi_q),
    .box_y_lo_i        (box_y_lo_q),
    .box_y_hi_i        (box_y_hi_q),
    .ref_x_i           (ref_x_q),
    .ref_y_i           (ref_y_q),
    .q_coef_x_i        (q_coef_x_q),
    .q_coef_y_i        (q_coef_y_q),
    .u_coef_x_i        (u_coef_x_q),
    .u_coef_y_i        (u_coef_y_q),
    .v_coef_x_i        (v_coef_x_q),
    .v_coef_y_i        (v_coef_y_q),
    .q_floor_i         (q_floor_q),
    .q_ref_i           (q_ref_q),
    .u_ref_i           (u_ref_q),
    .v_ref_i           (v_ref_q),
    .x_major_i         (x_major_q),
    .shift_i           (shift_q),
    .g_zero_i          (g_zero_q),
    .g_negative_i      (g_negative_q),
    .edge_fixed_i      (edge_fixed_q),
    .edge_free_i       (edge_free_q),
    .edge_n_high_i     (edge_n_high_q),
    .edge_n_low_i      (edge_n_low_q),
    .g_quotient_i      (g_quotient),
    .g_remainder_i     (g_remainder),
    .g_overflow_i      (g_overflow),
    .bound_quotient_i  (bound_quotient),
    .bound_remainder_i (bound_remainder),
    .slope_quotient_i  (slope_quotient),
    .slope_remainder_i (slope_remainder),
    .products_i        (products[ResultD*AccBits +: (ResultE-ResultD)*AccBits]),
    .term_a_o          (term_a_d),
    .term_b_o          (term_b_d),
    .g_o               (g_o),
    .major_lo_o        (major_lo_o),
    .major_count_o     (major_count_o),
    .minor_lo_o        (minor_lo_o),
    .minor_hi_o        (minor_hi_o),
    .line_lo_o         (line_lo_q),
    .line_hi_o         (pixel_line_hi_o),
    .no_lines_o        (no_lines_o),
    .fallback_o        (fallback_o),
    .line_phase_o      (line_phase_o),
    .q_at_ref_o        (q_at_ref_o),
    .u_at_ref_o        (u_at_ref_o),
    .v_at_ref_o        (v_at_ref_o),
    .q_per_line_o      (q_per_line_q),
    .u_per_line_o      (u_per_line_q),
    .v_per_line_o      (v_per_line_q),
    .q_per_major_o     (q_per_major_o),
    .u_per_major_o     (u_per_major_o),
    .v_per_major_o     (v_per_major_o),
    .step_u_o          (step_u_q),
    .step_v_o          (step_v_q),
    .edge_kind_o       (edge_kind_o),
    .edge_bound_o      (edge_bound_o),
    .edge_rem_o        (edge_rem_o),
    .edge_step_o       (edge_step_o),
    .edge_slope_o      (edge_slope_o),
    .edge_slope_rem_o  (edge_slope_rem_o),
    .normalise_saturated_o(normalise_saturated)
  );

  assign empty_o = empty_q;
  assign x_major_o = x_major_q;
  assign pixel_line_lo_o = line_lo_q;
  assign q_per_minor_o = q_per_line_q;
  assign u_per_minor_o = u_per_line_q;
  assign v_per_minor_o = v_per_line_q;
  assign u_vertex_o = u_q;
  assign v_vertex_o = v_q;
  assign dx1_o = dx1_q;
  assign dy1_o = dy1_q;
  assign dx2_o = dx2_q;
  assign dy2_o = dy2_q;
  assign det_o = det_q;
  assign ref_x_o = ref_x_q;
  assign ref_y_o = ref_y_q;
  always_comb begin
    flags_o = '0;
    flags_o[FlagDepthRange] = depth_range_q;
  end

  // ---------------------------------------------------------------- stage E and fill
  if (HasLines) begin : gen_fill
    setup_fill #(.SramDepth(SramDepth), .FillContext(FillContext), .HasPersp(HasPersp)) u_fill (
      .clk_i, .rst_ni,
      .hold_i,
      .stage_i       (stage_e),
      .q_at_ref_i    (q_at_ref_o),
      .u_at_ref_i    (u_at_ref_o),
      .v_at_ref_i    (v_at_ref_o),
      .q_per_line_i  (q_per_line_q),
      .u_per_line_i  (u_per_line_q),
      .v_per_line_i  (v_per_line_q),
      .step_u_i      (step_u_q),
      .step_v_i      (step_v_q),
      .line_lo_i     (line_lo_q),
      .line_phase_i  (line_phase_o),
      .guard_i       (guard_q),
      .products_i    (products[ResultE*AccBits +: (ResultCount-ResultE)*AccBits]),
      .term_a_o      (term_a_e),
      .term_b_o      (term_b_e),
      .fill_load_i,
      .fill_valid_i,
      .fill_last_i,
      .fill_addr_i,
      .write_valid_o,
      .write_addr_o,
      .write_entry_o
    );
  end else begin : gen_no_fill
    logic unused_fill;
    assign unused_fill = ^{hold_i, fill_load_i, fill_valid_i, fill_last_i, fill_addr_i,
                           q_per_line_q, u_per_line_q, v_per_line_q, step_u_q, step_v_q, guard_q,
                           products[ResultE*AccBits +: (ResultCount-ResultE)*AccBits]};
    assign term_a_e = '0;
    assign term_b_e = '0;
    assign write_valid_o = 1'b0;
    assign write_addr_o = '0;
    assign write_entry_o = '0;
  end

`ifndef SYNTHESIS
  // Derived widths hold: the normalised planes never leave their formats, and
  // the dividers' quotients fit (model/derived_widths.cpp checks the same bounds).
  always_ff @(posedge clk_i) begin
    if (stage_e && !empty_q) begin
      assert (normalise_saturated == '0)
        else $error("setup_engine: a normalised plane value left its derived width (%b)", normalise_saturated);
      for (int i = 0; i < 3; i++) begin
        assert (edge_free_q[DiffBits*i +: DiffBits] == 0 || (!bound_overflow[i] && !slope_overflow[i]))
          else $error("setup_engine: edge %0d divider quotient overflow", i);
      end
    end
  end
`endif

endmodule

`default_nettype wire
