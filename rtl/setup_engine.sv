// Setup engine: plane equations, orientation, slope g, per-triangle
// normalisation, line range and the column walker's edge trackers, then the
// per-line table fill (one reciprocal and four multiplies per line, five for
// cd-persp's eps). Twin of
// model/setup_engine.cpp; every value follows its integer arithmetic exactly,
// every signal has the width derived for it in model/derived_widths.cpp.
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
  output logic signed [`CD_LINE_BITS-1:0] pixel_line_lo_o,
  output logic signed [`CD_LINE_BITS-1:0] pixel_line_hi_o,
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

  localparam int SubpixelBits = `CD_SUBPIXEL_BITS;
  localparam int UvInFrac     = `CD_UV_IN_FRAC;
  localparam int QBits        = `CD_Q_BITS;
  localparam int PlaneBits    = `CD_PLANE_BITS;
  localparam int GFrac        = `CD_G_FRAC;
  localparam int RecipBits    = `CD_RECIP_BITS;
  localparam int TFrac        = `CD_T_FRAC;
  localparam int SFrac        = `CD_S_FRAC;
  localparam int CoordBits    = `CD_COORD_BITS;
  localparam int UvBits       = `CD_UV_BITS;
  localparam int DiffBits     = `CD_DIFF_BITS;
  localparam int DetBits      = `CD_DET_BITS;
  localparam int EdgeCBits    = `CD_EDGE_C_BITS;
  localparam int PixelBits    = `CD_PIXEL_BITS;
  localparam int QVertexBits  = `CD_Q_VERTEX_BITS;
  localparam int AttrQBits    = `CD_ATTR_Q_BITS;
  localparam int AttrUvBits   = `CD_ATTR_UV_BITS;
  localparam int CoefQBits    = `CD_COEF_Q_BITS;
  localparam int CoefUvBits   = `CD_COEF_UV_BITS;
  localparam int ExactRefQBits  = `CD_EXACT_REF_Q_BITS;
  localparam int ExactRefUvBits = `CD_EXACT_REF_UV_BITS;
  localparam int PeakBits     = `CD_PEAK_BITS;
  localparam int ShiftBits    = `CD_SHIFT_BITS;
  localparam int PlaneRefQBits  = `CD_PLANE_REF_Q_BITS;
  localparam int PlaneRefUvBits = `CD_PLANE_REF_UV_BITS;
  localparam int PlaneStepQBits  = `CD_PLANE_STEP_Q_BITS;
  localparam int PlaneStepUvBits = `CD_PLANE_STEP_UV_BITS;
  localparam int StepUvBits   = `CD_STEP_UV_BITS;
  localparam int GBits        = `CD_G_BITS;
  localparam int KappaBits    = `CD_KAPPA_BITS;
  localparam int LineBits     = `CD_LINE_BITS;
  localparam int EdgeNBits    = `CD_EDGE_N_BITS;
  localparam int EdgeStepBits = `CD_EDGE_STEP_BITS;
  localparam int EdgeBoundBits = `CD_EDGE_BOUND_BITS;
  localparam int EdgeSlopeBits = `CD_EDGE_SLOPE_BITS;
  localparam int FillQBits    = `CD_FILL_Q_BITS;
  localparam int FillUvBits   = `CD_FILL_UV_BITS;
  localparam int ExponentBits = `CD_EXPONENT_BITS;
  localparam int TBits        = `CD_T_BITS;
  localparam int SBits        = `CD_S_BITS;
  localparam int GDivQuoBits  = `CD_G_DIV_QUOTIENT_BITS;
  localparam int BoundDivQuoBits = `CD_BOUND_DIV_QUOTIENT_BITS;
  localparam int SlopeDivQuoBits = `CD_SLOPE_DIV_QUOTIENT_BITS;
  localparam int DivBitsPerCycle = `CD_DIV_BITS_PER_CYCLE;
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

  // Exact values before the per-triangle shift.
  localparam int AxisQBits    = CoefQBits + SubpixelBits;   // q per pixel (coef 2^sp)
  localparam int AxisUvBits   = CoefUvBits + SubpixelBits;
  localparam int StepNumBits  = AxisUvBits + GFrac + 2;      // U_major 2^gf + g U_minor
  localparam int GDivNumBits  = CoefQBits + GFrac + 1;       // |2 N' + D'|
  localparam int GDivDenBits  = CoefQBits;                   // 2 |q_minor|
  localparam int FreeBits     = DiffBits - 1;                // |free coefficient|
  localparam int BoundNumBits = EdgeNBits - SubpixelBits;    // |N0 >> sp|
  localparam int LineRangeBits = KappaBits - SubpixelBits - GFrac + 3;
  // The fill's quotients (cdsim::quotient): each numerator narrowed by the
  // line's exponent e to its format's fraction bits plus Guard, and one
  // integer bit more; its product with the reciprocal read with RecipBits +
  // that many fraction bits, so rounded by the constant QuotientShift.
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
  localparam int MaxPlaneLeft = PlaneBits + 2;

  localparam int FlagDepthRange = `CD_FLAG_DEPTH_RANGE;

  // ---------------------------------------------------------------- triangle
  logic signed [CoordBits-1:0] x_q [3];
  logic signed [CoordBits-1:0] y_q [3];
  logic signed [UvBits-1:0]    u_q [3];
  logic signed [UvBits-1:0]    v_q [3];
  logic [31:0]                 qf_q [3];
  logic [13:0]                 viewport_width_q, viewport_height_q;
  logic [1:0]                  density_log2_q;
  logic                        guard_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int i = 0; i < 3; i++) begin
        x_q[i] <= '0;
        y_q[i] <= '0;
        u_q[i] <= '0;
        v_q[i] <= '0;
        qf_q[i] <= '0;
      end
      viewport_width_q <= '0;
      viewport_height_q <= '0;
      density_log2_q <= '0;
      guard_q <= 1'b0;
    end else if (load_i) begin
      for (int i = 0; i < 3; i++) begin
        x_q[i] <= tri_x_i[32*i +: CoordBits];
        y_q[i] <= tri_y_i[32*i +: CoordBits];
        u_q[i] <= tri_u_i[32*i +: UvBits];
        v_q[i] <= tri_v_i[32*i +: UvBits];
        qf_q[i] <= tri_q_i[32*i +: 32];
      end
      viewport_width_q <= viewport_width_i;
      viewport_height_q <= viewport_height_i;
      density_log2_q <= density_log2_i;
      guard_q <= correction_i;
    end
  end

  logic stage_a, stage_b, stage_c, stage_d, stage_e;
  logic window_a, window_b, window_c, window_d;
  assign stage_a = setup_i && stage_count_i == CountBits'(StageA);
  assign stage_b = setup_i && stage_count_i == CountBits'(StageB);
  assign stage_c = setup_i && stage_count_i == CountBits'(StageC);
  assign stage_d = setup_i && stage_count_i == CountBits'(StageD);
  assign stage_e = setup_i && stage_count_i == CountBits'(StageE);
  // A stage's operands are formed from its first product cycle to its own.
  assign window_a = setup_i && stage_count_i <= CountBits'(StageA);
  assign window_b = setup_i && stage_count_i > CountBits'(StageA) && stage_count_i <= CountBits'(StageB);
  assign window_c = setup_i && stage_count_i > CountBits'(StageB) && stage_count_i <= CountBits'(StageC);
  assign window_d = setup_i && stage_count_i >= CountBits'(DivDone) && stage_count_i <= CountBits'(StageD);

  // The sums of products of every stage (model/setup_terms.def): operands in,
  // results out, on the shared multipliers or on one multiplier each.
  logic [TermCount*OperandABits-1:0]   term_a;
  logic [TermCount*OperandBBits-1:0]   term_b;
  logic [ResultCount*AccBits-1:0]      products;
  setup_multipliers u_multipliers (
    .clk_i,
    .hold_i,
    .setup_i,
    .stage_count_i,
    .a_i          (term_a),
    .b_i          (term_b),
    .result_o     (products)
  );

  // ---------------------------------------------------------------- stage A
  // Edge functions with the top-left rule (model/coverage.cpp make_edges), the
  // box, and 1/w aligned to the largest exponent.
  logic signed [DiffBits-1:0]  dx1, dy1, dx2, dy2;
  logic signed [DetBits-1:0]   det;
  logic signed [DiffBits-1:0]  edge_dx [3];
  logic signed [DiffBits-1:0]  edge_dy [3];
  logic signed [DiffBits-1:0]  edge_a_d [3];
  logic signed [DiffBits-1:0]  edge_b_d [3];
  logic signed [EdgeCBits-1:0] edge_c_d [3];
  logic [2:0]                  edge_threshold_d;
  logic signed [CoordBits:0]   min_x, max_x, min_y, max_y, x_lo, x_hi, y_lo, y_hi;
  logic                        empty_d;
  logic [PixelBits-1:0]        box_x_lo_d, box_x_hi_d, box_y_lo_d, box_y_hi_d;
  logic signed [DiffBits-1:0]  ref_x_d, ref_y_d;
  logic [7:0]                  max_exponent;
  logic signed [9:0]           q_shift [3];
  logic [33:0]                 q_wide [3];
  logic [QVertexBits-1:0]      q_vertex_d [3];
  logic signed [AttrUvBits-1:0] u_attr_d [3];
  logic signed [AttrUvBits-1:0] v_attr_d [3];
  logic                        depth_range_d;

  localparam logic signed [CoordBits:0] OnePx  = (CoordBits+1)'(1) <<< SubpixelBits;
  localparam logic signed [CoordBits:0] HalfPx = (CoordBits+1)'(1) <<< (SubpixelBits - 1);

  // Stage A's operands: vertex differences, edge vectors and the vertices' q.
  always_comb begin
    dx1 = '0;
    dy1 = '0;
    dx2 = '0;
    dy2 = '0;
    for (int i = 0; i < 3; i++) edge_dx[i] = '0;
    for (int i = 0; i < 3; i++) edge_dy[i] = '0;
    max_exponent = '0;
    depth_range_d = '0;
    for (int i = 0; i < 3; i++) q_shift[i] = '0;
    for (int i = 0; i < 3; i++) q_wide[i] = '0;
    for (int i = 0; i < 3; i++) q_vertex_d[i] = '0;
    if (window_a) begin
      dx1 = DiffBits'(x_q[1]) - DiffBits'(x_q[0]);
      dy1 = DiffBits'(y_q[1]) - DiffBits'(y_q[0]);
      dx2 = DiffBits'(x_q[2]) - DiffBits'(x_q[0]);
      dy2 = DiffBits'(y_q[2]) - DiffBits'(y_q[0]);
      for (int i = 0; i < 3; i++) begin
        edge_dx[i] = DiffBits'(x_q[(i + 2) % 3]) - DiffBits'(x_q[(i + 1) % 3]);
        edge_dy[i] = DiffBits'(y_q[(i + 2) % 3]) - DiffBits'(y_q[(i + 1) % 3]);
      end
      // q_i = round(m_i 2^-(E - e_i + 24 - q_bits)); 0 once the shift passes 25.
      max_exponent = qf_q[0][30:23];
      for (int i = 1; i < 3; i++) if (qf_q[i][30:23] > max_exponent) max_exponent = qf_q[i][30:23];
      depth_range_d = 1'b0;
      for (int i = 0; i < 3; i++) begin
        q_shift[i] = $signed({2'b00, max_exponent - qf_q[i][30:23]}) + 10'sd24 - 10'(QBits);
        q_wide[i] = {10'd0, 1'b1, qf_q[i][22:0]};
        if (q_shift[i] <= 0) q_wide[i] = q_wide[i] << (-q_shift[i]);
        else if (q_shift[i] > 10'sd25) q_wide[i] = '0;
        else q_wide[i] = (q_wide[i] + (34'd1 << (q_shift[i] - 10'sd1))) >> q_shift[i];
        q_vertex_d[i] = QVertexBits'(q_wide[i]);
        if (q_vertex_d[i] == '0) depth_range_d = 1'b1;
      end
    end
  end

  always_comb begin
    det = '0;
    for (int i = 0; i < 3; i++) edge_a_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_b_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_c_d[i] = '0;
    edge_threshold_d = '0;
    min_x = '0;
    max_x = '0;
    min_y = '0;
    max_y = '0;
    x_lo = '0;
    x_hi = '0;
    y_lo = '0;
    y_hi = '0;
    empty_d = '0;
    box_x_lo_d = '0;
    box_x_hi_d = '0;
    box_y_lo_d = '0;
    box_y_hi_d = '0;
    ref_x_d = '0;
    ref_y_d = '0;
    for (int i = 0; i < 3; i++) u_attr_d[i] = '0;
    for (int i = 0; i < 3; i++) v_attr_d[i] = '0;
    if (stage_a) begin
      det = DetBits'(products[AccBits*`CD_SETUP_DET +: AccBits]);  // dx1 dy2 - dx2 dy1
      for (int i = 0; i < 3; i++) begin
        edge_a_d[i] = det < 0 ? edge_dy[i] : -edge_dy[i];
        edge_b_d[i] = det < 0 ? -edge_dx[i] : edge_dx[i];
        // dy x(i+1) - dx y(i+1)
        edge_c_d[i] = EdgeCBits'(products[AccBits*(`CD_SETUP_EDGE_C0 + i) +: AccBits]);
        if (det < 0) edge_c_d[i] = -edge_c_d[i];
        edge_threshold_d[i] = !((edge_a_d[i] == 0 && edge_b_d[i] > 0) || edge_a_d[i] > 0);
      end

      // Pixels whose centres the vertices' extent reaches, clipped to the viewport.
      min_x = (CoordBits+1)'(x_q[0]);
      max_x = min_x;
      min_y = (CoordBits+1)'(y_q[0]);
      max_y = min_y;
      for (int i = 1; i < 3; i++) begin
        if ((CoordBits+1)'(x_q[i]) < min_x) min_x = (CoordBits+1)'(x_q[i]);
        if ((CoordBits+1)'(x_q[i]) > max_x) max_x = (CoordBits+1)'(x_q[i]);
        if ((CoordBits+1)'(y_q[i]) < min_y) min_y = (CoordBits+1)'(y_q[i]);
        if ((CoordBits+1)'(y_q[i]) > max_y) max_y = (CoordBits+1)'(y_q[i]);
      end
      // ceil((min - half) / one) and floor((max - half) / one): arithmetic shifts.
      x_lo = (min_x - HalfPx + OnePx - 1) >>> SubpixelBits;
      x_hi = (max_x - HalfPx) >>> SubpixelBits;
      y_lo = (min_y - HalfPx + OnePx - 1) >>> SubpixelBits;
      y_hi = (max_y - HalfPx) >>> SubpixelBits;
      if (x_lo < 0) x_lo = '0;
      if (y_lo < 0) y_lo = '0;
      if (x_hi > (CoordBits+1)'($signed({1'b0, viewport_width_q})) - (CoordBits+1)'(1))
        x_hi = (CoordBits+1)'($signed({1'b0, viewport_width_q})) - (CoordBits+1)'(1);
      if (y_hi > (CoordBits+1)'($signed({1'b0, viewport_height_q})) - (CoordBits+1)'(1))
        y_hi = (CoordBits+1)'($signed({1'b0, viewport_height_q})) - (CoordBits+1)'(1);
      empty_d = det == 0 || x_lo > x_hi || y_lo > y_hi;
      box_x_lo_d = PixelBits'(x_lo);
      box_x_hi_d = PixelBits'(x_hi);
      box_y_lo_d = PixelBits'(y_lo);
      box_y_hi_d = PixelBits'(y_hi);
      // The reference pixel centre (the box's top-left) relative to vertex 0.
      ref_x_d = (DiffBits'($signed({1'b0, box_x_lo_d})) <<< SubpixelBits) + DiffBits'(HalfPx) -
                DiffBits'(x_q[0]);
      ref_y_d = (DiffBits'($signed({1'b0, box_y_lo_d})) <<< SubpixelBits) + DiffBits'(HalfPx) -
                DiffBits'(y_q[0]);

      for (int i = 0; i < 3; i++) begin
        if (HasPlanes) begin
          u_attr_d[i] = AttrUvBits'(products[AccBits*(`CD_SETUP_U_ATTR0 + i) +: AccBits]);  // q u
          v_attr_d[i] = AttrUvBits'(products[AccBits*(`CD_SETUP_V_ATTR0 + i) +: AccBits]);  // q v
        end
      end
    end
  end

  logic signed [DiffBits-1:0]  dx1_q, dy1_q, dx2_q, dy2_q;
  logic signed [DetBits-1:0]   det_q;
  logic signed [DiffBits-1:0]  edge_a_q [3];
  logic signed [DiffBits-1:0]  edge_b_q [3];
  logic signed [EdgeCBits-1:0] edge_c_q [3];
  logic [2:0]                  edge_threshold_q;
  logic                        empty_q;
  logic [PixelBits-1:0]        box_x_lo_q, box_x_hi_q, box_y_lo_q, box_y_hi_q;
  logic signed [DiffBits-1:0]  ref_x_q, ref_y_q;
  logic [QVertexBits-1:0]      q_vertex_q [3];
  logic signed [AttrUvBits-1:0] u_attr_q [3];
  logic signed [AttrUvBits-1:0] v_attr_q [3];
  logic                        depth_range_q;

  always_ff @(posedge clk_i) begin
    if (stage_a) begin
      dx1_q <= dx1;
      dy1_q <= dy1;
      dx2_q <= dx2;
      dy2_q <= dy2;
      det_q <= det;
      for (int i = 0; i < 3; i++) edge_a_q[i] <= edge_a_d[i];
      for (int i = 0; i < 3; i++) edge_b_q[i] <= edge_b_d[i];
      for (int i = 0; i < 3; i++) edge_c_q[i] <= edge_c_d[i];
      edge_threshold_q <= edge_threshold_d;
      box_x_lo_q <= box_x_lo_d;
      box_x_hi_q <= box_x_hi_d;
      box_y_lo_q <= box_y_lo_d;
      box_y_hi_q <= box_y_hi_d;
      ref_x_q <= ref_x_d;
      ref_y_q <= ref_y_d;
      for (int i = 0; i < 3; i++) q_vertex_q[i] <= q_vertex_d[i];
      for (int i = 0; i < 3; i++) u_attr_q[i] <= u_attr_d[i];
      for (int i = 0; i < 3; i++) v_attr_q[i] <= v_attr_d[i];
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      empty_q <= 1'b1;
      depth_range_q <= 1'b0;
    end else if (stage_a) begin
      empty_q <= empty_d;
      depth_range_q <= depth_range_d;
    end
  end

  // ---------------------------------------------------------------- stage B
  // Plane coefficients, signed so that q |det| > 0: A_x = s (dA1 dy2 - dA2 dy1),
  // A_y = s (dA2 dx1 - dA1 dx2), per subpixel.
  logic signed [DetBits-1:0]    det_abs;
  logic signed [AttrQBits:0]    dq1, dq2;
  logic signed [AttrUvBits:0]   du1, du2, dv1, dv2;
  logic signed [CoefQBits-1:0]  q_coef_x_d, q_coef_y_d;
  logic signed [CoefUvBits-1:0] u_coef_x_d, u_coef_y_d, v_coef_x_d, v_coef_y_d;
  logic [PeakBits-1:0]          peak_candidate [3];
  logic [PeakBits-1:0]          q_peak_d;

  // Stage B's operands: differences of q, U and V, and |det|.
  always_comb begin
    det_abs = '0;
    dq1 = '0;
    dq2 = '0;
    du1 = '0;
    du2 = '0;
    dv1 = '0;
    dv2 = '0;
    if (window_b) begin
      det_abs = det_q < 0 ? -det_q : det_q;
      dq1 = (AttrQBits+1)'($signed({1'b0, q_vertex_q[1]})) - (AttrQBits+1)'($signed({1'b0, q_vertex_q[0]}));
      dq2 = (AttrQBits+1)'($signed({1'b0, q_vertex_q[2]})) - (AttrQBits+1)'($signed({1'b0, q_vertex_q[0]}));
    end
    if (window_b && HasPlanes) begin
      du1 = (AttrUvBits+1)'(u_attr_q[1]) - (AttrUvBits+1)'(u_attr_q[0]);
      du2 = (AttrUvBits+1)'(u_attr_q[2]) - (AttrUvBits+1)'(u_attr_q[0]);
      dv1 = (AttrUvBits+1)'(v_attr_q[1]) - (AttrUvBits+1)'(v_attr_q[0]);
      dv2 = (AttrUvBits+1)'(v_attr_q[2]) - (AttrUvBits+1)'(v_attr_q[0]);
    end
  end

  always_comb begin
    q_coef_x_d = '0;
    q_coef_y_d = '0;
    u_coef_x_d = '0;
    u_coef_y_d = '0;
    v_coef_x_d = '0;
    v_coef_y_d = '0;
    q_peak_d = '0;
    for (int i = 0; i < 3; i++) peak_candidate[i] = '0;
    if (stage_b) begin
      q_coef_x_d = CoefQBits'(products[AccBits*`CD_SETUP_Q_COEF_X +: AccBits]);  // dq1 dy2 - dq2 dy1
      q_coef_y_d = CoefQBits'(products[AccBits*`CD_SETUP_Q_COEF_Y +: AccBits]);  // dq2 dx1 - dq1 dx2
      if (det_q < 0) begin
        q_coef_x_d = -q_coef_x_d;
        q_coef_y_d = -q_coef_y_d;
      end
    end
    if (stage_b && HasPlanes) begin
      u_coef_x_d = CoefUvBits'(products[AccBits*`CD_SETUP_U_COEF_X +: AccBits]);
      u_coef_y_d = CoefUvBits'(products[AccBits*`CD_SETUP_U_COEF_Y +: AccBits]);
      v_coef_x_d = CoefUvBits'(products[AccBits*`CD_SETUP_V_COEF_X +: AccBits]);
      v_coef_y_d = CoefUvBits'(products[AccBits*`CD_SETUP_V_COEF_Y +: AccBits]);
      if (det_q < 0) begin
        u_coef_x_d = -u_coef_x_d;
        u_coef_y_d = -u_coef_y_d;
        v_coef_x_d = -v_coef_x_d;
        v_coef_y_d = -v_coef_y_d;
      end
      // The largest q |det| sets the shared shift.
      q_peak_d = '0;
      for (int i = 0; i < 3; i++) begin
        peak_candidate[i] = PeakBits'(products[AccBits*(`CD_SETUP_PEAK0 + i) +: AccBits]);  // q |det|
        if (peak_candidate[i] > q_peak_d) q_peak_d = peak_candidate[i];
      end
    end
  end

  logic signed [CoefQBits-1:0]  q_coef_x_q, q_coef_y_q;
  logic signed [CoefUvBits-1:0] u_coef_x_q, u_coef_y_q, v_coef_x_q, v_coef_y_q;
  logic [PeakBits-1:0]          q_peak_q;
  logic signed [DetBits-1:0]    det_abs_q;

  always_ff @(posedge clk_i) begin
    if (stage_b) begin
      q_coef_x_q <= q_coef_x_d;
      q_coef_y_q <= q_coef_y_d;
      u_coef_x_q <= u_coef_x_d;
      u_coef_y_q <= u_coef_y_d;
      v_coef_x_q <= v_coef_x_d;
      v_coef_y_q <= v_coef_y_d;
      q_peak_q <= q_peak_d;
      det_abs_q <= det_abs;
    end
  end

  // ---------------------------------------------------------------- stage C
  // Planes at the reference centre: s A0 det + A_x ref_x + A_y ref_y (exact),
  // orientation, the shared shift, and the divider operands.
  logic signed [ExactRefQBits-1:0]  q_ref_d;
  logic signed [ExactRefUvBits-1:0] u_ref_d, v_ref_d;
  logic                             x_major_d;
  logic [7:0]                       peak_length;
  logic signed [ShiftBits-1:0]      shift_d;
  logic signed [CoefQBits-1:0]      q_major, q_minor;
  logic signed [GDivNumBits:0]      g_numerator;
  logic [GDivNumBits-1:0]           g_div_num;
  logic [GDivDenBits-1:0]           g_div_den;
  logic signed [DiffBits-1:0]       edge_fixed [3];
  logic signed [DiffBits-1:0]       edge_free [3];
  logic [FreeBits-1:0]              edge_free_abs [3];
  logic [FreeBits-1:0]              edge_fixed_abs [3];
  logic signed [EdgeNBits-1:0]      edge_n [3];
  logic signed [BoundNumBits-1:0]   edge_n_high [3];
  logic [BoundNumBits-1:0]          edge_n_high_abs [3];
  logic [PixelBits-1:0]             major_lo_c;

  // Stage C's operands: the orientation, and each edge's coefficients along it.
  always_comb begin
    x_major_d = '0;
    major_lo_c = '0;
    for (int i = 0; i < 3; i++) edge_fixed[i] = '0;
    for (int i = 0; i < 3; i++) edge_free[i] = '0;
    if (window_c) begin
      // Lines run along the axis in which q changes least.
      x_major_d = (q_coef_x_q < 0 ? -q_coef_x_q : q_coef_x_q) <= (q_coef_y_q < 0 ? -q_coef_y_q : q_coef_y_q);
      major_lo_c = x_major_d ? box_x_lo_q : box_y_lo_q;
      for (int i = 0; i < 3; i++) begin
        edge_fixed[i] = x_major_d ? edge_a_q[i] : edge_b_q[i];
        edge_free[i] = x_major_d ? edge_b_q[i] : edge_a_q[i];
      end
    end
  end

  always_comb begin
    q_ref_d = '0;
    u_ref_d = '0;
    v_ref_d = '0;
    peak_length = '0;
    shift_d = '0;
    q_major = '0;
    q_minor = '0;
    g_numerator = '0;
    g_div_num = '0;
    g_div_den = '0;
    for (int i = 0; i < 3; i++) edge_free_abs[i] = '0;
    for (int i = 0; i < 3; i++) edge_fixed_abs[i] = '0;
    for (int i = 0; i < 3; i++) edge_n[i] = '0;
    for (int i = 0; i < 3; i++) edge_n_high[i] = '0;
    for (int i = 0; i < 3; i++) edge_n_high_abs[i] = '0;
    if (stage_c && HasPlanes) begin
      // A0 |det| + A_x ref_x + A_y ref_y
      q_ref_d = ExactRefQBits'(products[AccBits*`CD_SETUP_Q_REF +: AccBits]);
      u_ref_d = ExactRefUvBits'(products[AccBits*`CD_SETUP_U_REF +: AccBits]);
      v_ref_d = ExactRefUvBits'(products[AccBits*`CD_SETUP_V_REF +: AccBits]);
      peak_length = '0;
      for (int i = 0; i < PeakBits; i++) if (q_peak_q[i]) peak_length = 8'(i + 1);
      shift_d = ShiftBits'($signed({1'b0, peak_length})) - ShiftBits'(PlaneBits);
    end
    if (stage_c) begin
      // g = round(-q_major 2^g_frac / q_minor) = floor((2 N' + D') / (2 D')) with
      // N' = -q_major sign(q_minor) 2^g_frac and D' = |q_minor|.
      q_major = x_major_d ? q_coef_x_q : q_coef_y_q;
      q_minor = x_major_d ? q_coef_y_q : q_coef_x_q;
      g_numerator = ((q_minor < 0 ? (GDivNumBits+1)'(q_major) : -((GDivNumBits+1)'(q_major))) <<< (GFrac + 1)) +
                    (q_minor < 0 ? -((GDivNumBits+1)'(q_minor)) : (GDivNumBits+1)'(q_minor));
      g_div_num = GDivNumBits'(g_numerator < 0 ? -g_numerator : g_numerator);
      g_div_den = GDivDenBits'(q_minor < 0 ? -q_minor : q_minor) << 1;

      // Edge i at the first column: N0 = E - threshold there (model/coverage.cpp
      // covered_span), divided by |free| 2^sp as (N0 >> sp) / |free|.
      for (int i = 0; i < 3; i++) begin
        edge_free_abs[i] = FreeBits'(edge_free[i] < 0 ? -edge_free[i] : edge_free[i]);
        edge_fixed_abs[i] = FreeBits'(edge_fixed[i] < 0 ? -edge_fixed[i] : edge_fixed[i]);
        // fixed (major_lo 2^sp + half) + free half + c - threshold
        edge_n[i] = EdgeNBits'(products[AccBits*(`CD_SETUP_EDGE_N0 + i) +: AccBits]) +
                    EdgeNBits'(edge_free[i]) * EdgeNBits'(HalfPx) + EdgeNBits'(edge_c_q[i]) -
                    EdgeNBits'($signed({1'b0, edge_threshold_q[i]}));
        edge_n_high[i] = BoundNumBits'(edge_n[i] >>> SubpixelBits);
        edge_n_high_abs[i] = BoundNumBits'(edge_n_high[i] < 0 ? -edge_n_high[i] : edge_n_high[i]);
      end
    end
  end

  logic signed [ExactRefQBits-1:0]  q_ref_q;
  logic signed [ExactRefUvBits-1:0] u_ref_q, v_ref_q;
  logic                             x_major_q;
  logic signed [ShiftBits-1:0]      shift_q;
  logic                             g_zero_q, g_negative_q;
  logic signed [DiffBits-1:0]       edge_fixed_q [3];
  logic signed [DiffBits-1:0]       edge_free_q [3];
  logic signed [BoundNumBits-1:0]   edge_n_high_q [3];
  logic [SubpixelBits-1:0]          edge_n_low_q [3];

  always_ff @(posedge clk_i) begin
    if (stage_c) begin
      q_ref_q <= q_ref_d;
      u_ref_q <= u_ref_d;
      v_ref_q <= v_ref_d;
      x_major_q <= x_major_d;
      shift_q <= shift_d;
      g_zero_q <= q_minor == 0;
      g_negative_q <= g_numerator < 0;
      for (int i = 0; i < 3; i++) edge_fixed_q[i] <= edge_fixed[i];
      for (int i = 0; i < 3; i++) edge_free_q[i] <= edge_free[i];
      for (int i = 0; i < 3; i++) edge_n_high_q[i] <= edge_n_high[i];
      for (int i = 0; i < 3; i++) edge_n_low_q[i] <= edge_n[i][SubpixelBits-1:0];
    end
  end

  // ---------------------------------------------------------------- dividers
  // All start in stage C and finish by stage D (DivCycles later).
  logic [GDivQuoBits-1:0] g_quotient;
  logic [GDivDenBits-1:0] g_remainder;
  logic                   g_overflow;

  if (HasLines) begin : gen_g_divider
    serial_divider #(
      .NumBits(GDivNumBits), .DenBits(GDivDenBits), .QuoBits(GDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_g_divider (
      .clk_i, .rst_ni,
      .start_i      (stage_c),
      .numerator_i  (g_div_num),
      .denominator_i(g_div_den),
      .quotient_o   (g_quotient),
      .remainder_o  (g_remainder),
      .overflow_o   (g_overflow)
    );
  end else begin : gen_no_g_divider
    logic unused_g_operands;
    assign unused_g_operands = ^{g_div_num, g_div_den};
    assign g_quotient = '0;
    assign g_remainder = '0;
    assign g_overflow = 1'b0;
  end

  logic [BoundDivQuoBits-1:0] bound_quotient [3];
  logic [FreeBits-1:0]        bound_remainder [3];
  logic [SlopeDivQuoBits-1:0] slope_quotient [3];
  logic [FreeBits-1:0]        slope_remainder [3];
  logic [2:0]                 bound_overflow, slope_overflow;

  for (genvar i = 0; i < 3; i++) begin : gen_edge_dividers
    serial_divider #(
      .NumBits(BoundNumBits), .DenBits(FreeBits), .QuoBits(BoundDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_bound_divider (
      .clk_i, .rst_ni,
      .start_i      (stage_c),
      .numerator_i  (edge_n_high_abs[i]),
      .denominator_i(edge_free_abs[i]),
      .quotient_o   (bound_quotient[i]),
      .remainder_o  (bound_remainder[i]),
      .overflow_o   (bound_overflow[i])
    );
    serial_divider #(
      .NumBits(FreeBits), .DenBits(FreeBits), .QuoBits(SlopeDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_slope_divider (
      .clk_i, .rst_ni,
      .start_i      (stage_c),
      .numerator_i  (edge_fixed_abs[i]),
      .denominator_i(edge_free_abs[i]),
      .quotient_o   (slope_quotient[i]),
      .remainder_o  (slope_remainder[i]),
      .overflow_o   (slope_overflow[i])
    );
  end

  // ---------------------------------------------------------------- stage D
  logic signed [GBits-1:0]          g_d;
  logic [1:0]                       line_shift;
  logic signed [ShiftBits:0]        line_norm_shift;
  logic signed [ShiftBits+1:0]      step_norm_shift;
  logic signed [AxisQBits-1:0]      q_axis_major, q_axis_minor;
  logic signed [AxisUvBits-1:0]     u_axis_major, u_axis_minor, v_axis_major, v_axis_minor;
  logic signed [StepNumBits-1:0]    step_u_exact, step_v_exact;

  always_comb begin
    g_d = '0;
    line_shift = '0;
    line_norm_shift = '0;
    step_norm_shift = '0;
    q_axis_major = '0;
    q_axis_minor = '0;
    u_axis_major = '0;
    u_axis_minor = '0;
    v_axis_major = '0;
    v_axis_minor = '0;
    if (window_d) begin
      g_d = GBits'($signed({1'b0, g_quotient}));
      if (g_negative_q) g_d = -g_d - GBits'(g_remainder != '0);
      if (g_zero_q) g_d = '0;
      line_shift = density_log2_q;
      line_norm_shift = (ShiftBits+1)'(shift_q) + (ShiftBits+1)'($signed({1'b0, line_shift}));
      step_norm_shift = (ShiftBits+2)'(shift_q) + (ShiftBits+2)'(GFrac);
      q_axis_major = (x_major_q ? AxisQBits'(q_coef_x_q) : AxisQBits'(q_coef_y_q)) <<< SubpixelBits;
      q_axis_minor = (x_major_q ? AxisQBits'(q_coef_y_q) : AxisQBits'(q_coef_x_q)) <<< SubpixelBits;
      u_axis_major = (x_major_q ? AxisUvBits'(u_coef_x_q) : AxisUvBits'(u_coef_y_q)) <<< SubpixelBits;
      u_axis_minor = (x_major_q ? AxisUvBits'(u_coef_y_q) : AxisUvBits'(u_coef_x_q)) <<< SubpixelBits;
      v_axis_major = (x_major_q ? AxisUvBits'(v_coef_x_q) : AxisUvBits'(v_coef_y_q)) <<< SubpixelBits;
      v_axis_minor = (x_major_q ? AxisUvBits'(v_coef_y_q) : AxisUvBits'(v_coef_x_q)) <<< SubpixelBits;
    end
  end

  // U_major 2^g_frac + g U_minor
  always_comb begin
    step_u_exact = '0;
    step_v_exact = '0;
    if (stage_d) begin
      step_u_exact = (StepNumBits'(u_axis_major) <<< GFrac) + StepNumBits'(products[AccBits*`CD_SETUP_STEP_U +: AccBits]);
      step_v_exact = (StepNumBits'(v_axis_major) <<< GFrac) + StepNumBits'(products[AccBits*`CD_SETUP_STEP_V +: AccBits]);
    end
  end

  // Normalisation: every plane value of the triangle shifted by the same n.
  logic signed [PlaneRefQBits-1:0]   q_at_ref_d;
  logic signed [PlaneRefUvBits-1:0]  u_at_ref_d, v_at_ref_d;
  logic signed [PlaneStepQBits-1:0]  q_per_line_d;
  logic signed [PlaneStepUvBits-1:0] u_per_line_d, v_per_line_d;
  logic signed [StepUvBits-1:0]      step_u_d, step_v_d;
  logic signed [PlaneStepQBits-1:0]  q_per_major_d;
  logic signed [PlaneStepUvBits-1:0] u_per_major_d, v_per_major_d;
  logic [11:0]                       normalise_saturated;

  if (HasPlanes) begin : gen_normalise
    shift_round #(.InBits(ExactRefQBits), .OutBits(PlaneRefQBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_q_ref (.enable_i(stage_d), .in_i(q_ref_q), .shift_i(shift_q), .out_o(q_at_ref_d), .saturated_o(normalise_saturated[0]));
    shift_round #(.InBits(ExactRefUvBits), .OutBits(PlaneRefUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_ref (.enable_i(stage_d), .in_i(u_ref_q), .shift_i(shift_q), .out_o(u_at_ref_d), .saturated_o(normalise_saturated[1]));
    shift_round #(.InBits(ExactRefUvBits), .OutBits(PlaneRefUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_ref (.enable_i(stage_d), .in_i(v_ref_q), .shift_i(shift_q), .out_o(v_at_ref_d), .saturated_o(normalise_saturated[2]));
    shift_round #(.InBits(AxisQBits), .OutBits(PlaneStepQBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_q_line (.enable_i(stage_d), .in_i(q_axis_minor), .shift_i(line_norm_shift), .out_o(q_per_line_d), .saturated_o(normalise_saturated[3]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_line (.enable_i(stage_d), .in_i(u_axis_minor), .shift_i(line_norm_shift), .out_o(u_per_line_d), .saturated_o(normalise_saturated[4]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_line (.enable_i(stage_d), .in_i(v_axis_minor), .shift_i(line_norm_shift), .out_o(v_per_line_d), .saturated_o(normalise_saturated[5]));
  end else begin : gen_no_normalise
    logic unused_exact_planes;
    assign unused_exact_planes = ^{q_ref_q, u_ref_q, v_ref_q, q_axis_minor, u_axis_minor, v_axis_minor,
                                   line_norm_shift};
    assign q_at_ref_d = '0;
    assign u_at_ref_d = '0;
    assign v_at_ref_d = '0;
    assign q_per_line_d = '0;
    assign u_per_line_d = '0;
    assign v_per_line_d = '0;
    assign normalise_saturated[5:0] = '0;
  end
  if (HasLines) begin : gen_step_numerators
    shift_round #(.InBits(StepNumBits), .OutBits(StepUvBits), .ShiftBits(ShiftBits+2),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_step_u (.enable_i(stage_d), .in_i(step_u_exact), .shift_i(step_norm_shift), .out_o(step_u_d), .saturated_o(normalise_saturated[6]));
    shift_round #(.InBits(StepNumBits), .OutBits(StepUvBits), .ShiftBits(ShiftBits+2),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_step_v (.enable_i(stage_d), .in_i(step_v_exact), .shift_i(step_norm_shift), .out_o(step_v_d), .saturated_o(normalise_saturated[7]));
  end else begin : gen_no_step_numerators
    logic unused_step_exact;
    assign unused_step_exact = ^{step_u_exact, step_v_exact, step_norm_shift};
    assign step_u_d = '0;
    assign step_v_d = '0;
    assign normalise_saturated[7:6] = '0;
  end
  assign normalise_saturated[8] = g_overflow && !g_zero_q;
  // Per pixel along the major axis, for the per-pixel planes of divide and
  // the other per-pixel designs (along the minor axis that is per_line at m = 1).
  if (HasPixelPlanes) begin : gen_major_planes
    shift_round #(.InBits(AxisQBits), .OutBits(PlaneStepQBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_q_major (.enable_i(stage_d), .in_i(q_axis_major), .shift_i(shift_q), .out_o(q_per_major_d), .saturated_o(normalise_saturated[9]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_major (.enable_i(stage_d), .in_i(u_axis_major), .shift_i(shift_q), .out_o(u_per_major_d), .saturated_o(normalise_saturated[10]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_major (.enable_i(stage_d), .in_i(v_axis_major), .shift_i(shift_q), .out_o(v_per_major_d), .saturated_o(normalise_saturated[11]));
  end else begin : gen_no_major_planes
    logic unused_axis_major;
    assign unused_axis_major = ^q_axis_major;
    assign q_per_major_d = '0;
    assign u_per_major_d = '0;
    assign v_per_major_d = '0;
    assign normalise_saturated[11:9] = '0;
  end

  // Walk geometry and the line range: kappa = m ((minor - minor_ref) 2^g_frac
  // - g (major - major_ref)) at each vertex; pixel lines lie within 1/2 of it.
  logic [PixelBits-1:0]            major_lo_d, minor_lo_d, minor_hi_d;
  logic [PixelBits:0]              major_count_d;
  logic signed [DiffBits:0]        vertex_major [3];
  logic signed [DiffBits:0]        vertex_minor [3];
  logic signed [PixelBits+1:0]     columns_less_one;
  logic signed [KappaBits-1:0]     kappa, kappa_lo, kappa_hi;
  logic signed [LineRangeBits-1:0] line_lo, line_hi, round_last, minor_extent;
  logic signed [GBits+PixelBits+3:0] round_product;
  logic                            no_lines_d;
  localparam logic signed [KappaBits-1:0] KappaScale = KappaBits'(1) <<< (SubpixelBits + GFrac);

  // Stage D's operands: the walk's axes, each vertex's offsets along them,
  // and the box's last column.
  always_comb begin
    major_lo_d = '0;
    major_count_d = '0;
    minor_lo_d = '0;
    minor_hi_d = '0;
    for (int i = 0; i < 3; i++) vertex_major[i] = '0;
    for (int i = 0; i < 3; i++) vertex_minor[i] = '0;
    columns_less_one = '0;
    if (window_d) begin
      major_lo_d = x_major_q ? box_x_lo_q : box_y_lo_q;
      major_count_d = x_major_q ? (PixelBits+1)'(box_x_hi_q) - (PixelBits+1)'(box_x_lo_q) + 1
                                : (PixelBits+1)'(box_y_hi_q) - (PixelBits+1)'(box_y_lo_q) + 1;
      minor_lo_d = x_major_q ? box_y_lo_q : box_x_lo_q;
      minor_hi_d = x_major_q ? box_y_hi_q : box_x_hi_q;
    end
    if (window_d && HasLines) begin
      for (int i = 0; i < 3; i++) begin
        vertex_major[i] = (x_major_q ? (DiffBits+1)'(x_q[i]) - (DiffBits+1)'(x_q[0]) - (DiffBits+1)'(ref_x_q)
                                  : (DiffBits+1)'(y_q[i]) - (DiffBits+1)'(y_q[0]) - (DiffBits+1)'(ref_y_q));
        vertex_minor[i] = (x_major_q ? (DiffBits+1)'(y_q[i]) - (DiffBits+1)'(y_q[0]) - (DiffBits+1)'(ref_y_q)
                                  : (DiffBits+1)'(x_q[i]) - (DiffBits+1)'(x_q[0]) - (DiffBits+1)'(ref_x_q));
      end
      columns_less_one = (PixelBits+2)'($signed({1'b0, major_count_d})) - (PixelBits+2)'(1);
    end
  end

  always_comb begin
    kappa_lo = '0;
    kappa_hi = '0;
    kappa = '0;
    line_lo = '0;
    line_hi = '0;
    round_product = '0;
    round_last = '0;
    minor_extent = '0;
    no_lines_d = '0;
    if (stage_d && HasLines) begin
      for (int i = 0; i < 3; i++) begin
        kappa = ((KappaBits'(vertex_minor[i]) <<< GFrac) -
                 KappaBits'(products[AccBits*(`CD_SETUP_KAPPA0 + i) +: AccBits]))  // g major offset
                <<< density_log2_q;
        if (i == 0 || kappa < kappa_lo) kappa_lo = kappa;
        if (i == 0 || kappa > kappa_hi) kappa_hi = kappa;
      end
      // ceil((2 kappa - scale) / (2 scale)) and ceil((2 kappa + scale) / (2 scale)) - 1.
      line_lo = LineRangeBits'(-((KappaScale - (kappa_lo <<< 1)) >>> (SubpixelBits + GFrac + 1)));
      line_hi = LineRangeBits'(-((-(kappa_hi <<< 1) - KappaScale) >>> (SubpixelBits + GFrac + 1))) - 1;
      // The box bounds them too: line = m minor_offset - round(m g o).
      round_product = (GBits+PixelBits+4)'(products[AccBits*`CD_SETUP_ROUND_LAST +: AccBits])  // g (columns - 1)
                      <<< density_log2_q;
      round_last = LineRangeBits'((GBits+PixelBits+4)'((round_product + (GBits+PixelBits+4)'(1 <<< (GFrac - 1))) >>> GFrac));
      minor_extent = (LineRangeBits'($signed({1'b0, minor_hi_d})) - LineRangeBits'($signed({1'b0, minor_lo_d})))
                     <<< density_log2_q;
      if (round_last > 0) begin
        if (line_lo < -round_last) line_lo = -round_last;
      end else if (line_lo < 0) begin
        line_lo = '0;
      end
      if (round_last < 0) begin
        if (line_hi > minor_extent - round_last) line_hi = minor_extent - round_last;
      end else if (line_hi > minor_extent) begin
        line_hi = minor_extent;
      end
      no_lines_d = line_lo > line_hi;
    end
  end

  // Edge trackers (column_walker.sv): span end = floor(N / S) with remainder,
  // and its step per column floor(fixed 2^sp / S) with remainder, S = |free| 2^sp.
  // An edge with free = 0 keeps floor(N / 2^sp): only its sign matters.
  logic [1:0]                     edge_kind_d [3];
  logic signed [EdgeBoundBits-1:0] edge_bound_d [3];
  logic [EdgeStepBits-1:0]        edge_rem_d [3];
  logic [EdgeStepBits-1:0]        edge_step_d [3];
  logic signed [EdgeSlopeBits-1:0] edge_slope_d [3];
  logic [EdgeStepBits-1:0]        edge_slope_rem_d [3];
  logic [FreeBits-1:0]            rem_high, slope_rem_high;
  logic [FreeBits-1:0]            free_abs;

  always_comb begin
    free_abs = '0;
    for (int i = 0; i < 3; i++) edge_kind_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_bound_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_rem_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_step_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_slope_d[i] = '0;
    for (int i = 0; i < 3; i++) edge_slope_rem_d[i] = '0;
    rem_high = '0;
    slope_rem_high = '0;
    if (stage_d) begin
      for (int i = 0; i < 3; i++) begin
        free_abs = FreeBits'(edge_free_q[i] < 0 ? -edge_free_q[i] : edge_free_q[i]);
        edge_kind_d[i] = edge_free_q[i] > 0 ? 2'd1 : (edge_free_q[i] < 0 ? 2'd2 : 2'd0);
        if (edge_free_q[i] == 0) begin
          edge_bound_d[i] = EdgeBoundBits'(edge_n_high_q[i]);
          edge_rem_d[i] = EdgeStepBits'(edge_n_low_q[i]);
          edge_step_d[i] = EdgeStepBits'(1) << SubpixelBits;
          edge_slope_d[i] = EdgeSlopeBits'(edge_fixed_q[i]);
          edge_slope_rem_d[i] = '0;
          rem_high = '0;
          slope_rem_high = '0;
        end else begin
          // floor for a negative numerator: -q - (r != 0), remainder |free| - r.
          edge_bound_d[i] = EdgeBoundBits'($signed({1'b0, bound_quotient[i]}));
          rem_high = bound_remainder[i];
          if (edge_n_high_q[i] < 0) begin
            edge_bound_d[i] = -edge_bound_d[i] - EdgeBoundBits'(bound_remainder[i] != '0);
            rem_high = bound_remainder[i] != '0 ? free_abs - bound_remainder[i] : '0;
          end
          edge_rem_d[i] = (EdgeStepBits'(rem_high) << SubpixelBits) | EdgeStepBits'(edge_n_low_q[i]);
          edge_step_d[i] = EdgeStepBits'(free_abs) << SubpixelBits;
          edge_slope_d[i] = EdgeSlopeBits'($signed({1'b0, slope_quotient[i]}));
          slope_rem_high = slope_remainder[i];
          if (edge_fixed_q[i] < 0) begin
            edge_slope_d[i] = -edge_slope_d[i] - EdgeSlopeBits'(slope_remainder[i] != '0);
            slope_rem_high = slope_remainder[i] != '0 ? free_abs - slope_remainder[i] : '0;
          end
          edge_slope_rem_d[i] = EdgeStepBits'(slope_rem_high) << SubpixelBits;
        end
      end
    end
  end

  logic signed [GBits-1:0]           g_q;
  logic [PixelBits-1:0]              major_lo_q, minor_lo_q, minor_hi_q;
  logic [PixelBits:0]                major_count_q;
  logic signed [LineBits-1:0]        line_lo_q, line_hi_q;
  logic                              no_lines_q;
  logic signed [PlaneRefQBits-1:0]   q_at_ref_q;
  logic signed [PlaneRefUvBits-1:0]  u_at_ref_q, v_at_ref_q;
  logic signed [PlaneStepQBits-1:0]  q_per_line_q, q_per_major_q;
  logic signed [PlaneStepUvBits-1:0] u_per_line_q, v_per_line_q, u_per_major_q, v_per_major_q;
  logic signed [StepUvBits-1:0]      step_u_q, step_v_q;
  logic [1:0]                        edge_kind_q [3];
  logic signed [EdgeBoundBits-1:0]   edge_bound_q [3];
  logic [EdgeStepBits-1:0]           edge_rem_q [3];
  logic [EdgeStepBits-1:0]           edge_step_q [3];
  logic signed [EdgeSlopeBits-1:0]   edge_slope_q [3];
  logic [EdgeStepBits-1:0]           edge_slope_rem_q [3];

  always_ff @(posedge clk_i) begin
    if (stage_d) begin
      g_q <= g_d;
      major_lo_q <= major_lo_d;
      major_count_q <= major_count_d;
      minor_lo_q <= minor_lo_d;
      minor_hi_q <= minor_hi_d;
      line_lo_q <= LineBits'(line_lo);
      line_hi_q <= LineBits'(line_hi);
      no_lines_q <= no_lines_d;
      q_at_ref_q <= q_at_ref_d;
      u_at_ref_q <= u_at_ref_d;
      v_at_ref_q <= v_at_ref_d;
      q_per_line_q <= q_per_line_d;
      u_per_line_q <= u_per_line_d;
      v_per_line_q <= v_per_line_d;
      q_per_major_q <= q_per_major_d;
      u_per_major_q <= u_per_major_d;
      v_per_major_q <= v_per_major_d;
      step_u_q <= step_u_d;
      step_v_q <= step_v_d;
      for (int i = 0; i < 3; i++) edge_kind_q[i] <= edge_kind_d[i];
      for (int i = 0; i < 3; i++) edge_bound_q[i] <= edge_bound_d[i];
      for (int i = 0; i < 3; i++) edge_rem_q[i] <= edge_rem_d[i];
      for (int i = 0; i < 3; i++) edge_step_q[i] <= edge_step_d[i];
      for (int i = 0; i < 3; i++) edge_slope_q[i] <= edge_slope_d[i];
      for (int i = 0; i < 3; i++) edge_slope_rem_q[i] <= edge_slope_rem_d[i];
    end
  end

  assign empty_o = empty_q;
  assign x_major_o = x_major_q;
  assign g_o = g_q;
  assign major_lo_o = major_lo_q;
  assign major_count_o = major_count_q;
  assign minor_lo_o = minor_lo_q;
  assign minor_hi_o = minor_hi_q;
  assign no_lines_o = no_lines_q;
  assign pixel_line_lo_o = line_lo_q;
  assign pixel_line_hi_o = line_hi_q;
  assign q_at_ref_o = q_at_ref_q;
  assign u_vertex_o = {u_q[2], u_q[1], u_q[0]};
  assign v_vertex_o = {v_q[2], v_q[1], v_q[0]};
  assign dx1_o = dx1_q;
  assign dy1_o = dy1_q;
  assign dx2_o = dx2_q;
  assign dy2_o = dy2_q;
  assign det_o = det_q;
  assign ref_x_o = ref_x_q;
  assign ref_y_o = ref_y_q;
  assign u_at_ref_o = u_at_ref_q;
  assign v_at_ref_o = v_at_ref_q;
  assign q_per_major_o = q_per_major_q;
  assign u_per_major_o = u_per_major_q;
  assign v_per_major_o = v_per_major_q;
  assign q_per_minor_o = q_per_line_q;
  assign u_per_minor_o = u_per_line_q;
  assign v_per_minor_o = v_per_line_q;
  always_comb begin
    flags_o = '0;
    flags_o[FlagDepthRange] = depth_range_q;
  end
  for (genvar i = 0; i < 3; i++) begin : gen_edge_outputs
    assign edge_kind_o[2*i +: 2] = edge_kind_q[i];
    assign edge_bound_o[EdgeBoundBits*i +: EdgeBoundBits] = edge_bound_q[i];
    assign edge_rem_o[EdgeStepBits*i +: EdgeStepBits] = edge_rem_q[i];
    assign edge_step_o[EdgeStepBits*i +: EdgeStepBits] = edge_step_q[i];
    assign edge_slope_o[EdgeSlopeBits*i +: EdgeSlopeBits] = edge_slope_q[i];
    assign edge_slope_rem_o[EdgeStepBits*i +: EdgeStepBits] = edge_slope_rem_q[i];
  end

  // ---------------------------------------------------------------- operands
  // Each term's operands (model/setup_terms.def), sign-extended. Outside its
  // stage's window a stage's signals are zero, and so are its products. Stage
  // E's (the fill's first line) are registers that hold until the next
  // triangle's stage D, since the fill may load them after setup.
  logic signed [LineBits-1:0] first_line;
  assign first_line = line_lo_q - LineBits'($signed({1'b0, guard_q}));

  always_comb begin
    term_a = '0;
    term_b = '0;
    // stage A
    term_a[OperandABits*(`CD_SETUP_TERM_DET + 0) +: OperandABits] = OperandABits'(dx1);
    term_b[OperandBBits*(`CD_SETUP_TERM_DET + 0) +: OperandBBits] = OperandBBits'(dy2);
    term_a[OperandABits*(`CD_SETUP_TERM_DET + 1) +: OperandABits] = OperandABits'(dx2);
    term_b[OperandBBits*(`CD_SETUP_TERM_DET + 1) +: OperandBBits] = OperandBBits'(dy1);
    for (int i = 0; i < 3; i++) begin
      term_a[OperandABits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 0) +: OperandABits] = OperandABits'(edge_dy[i]);
      term_b[OperandBBits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 0) +: OperandBBits] = OperandBBits'(x_q[(i + 1) % 3]);
      term_a[OperandABits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 1) +: OperandABits] = OperandABits'(edge_dx[i]);
      term_b[OperandBBits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 1) +: OperandBBits] = OperandBBits'(y_q[(i + 1) % 3]);
      term_a[OperandABits*(`CD_SETUP_TERM_U_ATTR0 + i) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_d[i]}));
      term_b[OperandBBits*(`CD_SETUP_TERM_U_ATTR0 + i) +: OperandBBits] = OperandBBits'(u_q[i]);
      term_a[OperandABits*(`CD_SETUP_TERM_V_ATTR0 + i) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_d[i]}));
      term_b[OperandBBits*(`CD_SETUP_TERM_V_ATTR0 + i) +: OperandBBits] = OperandBBits'(v_q[i]);
    end
    // stage B
    term_a[OperandABits*(`CD_SETUP_TERM_Q_COEF_X + 0) +: OperandABits] = OperandABits'(dq1);
    term_b[OperandBBits*(`CD_SETUP_TERM_Q_COEF_X + 0) +: OperandBBits] = OperandBBits'(dy2_q);
    term_a[OperandABits*(`CD_SETUP_TERM_Q_COEF_X + 1) +: OperandABits] = OperandABits'(dq2);
    term_b[OperandBBits*(`CD_SETUP_TERM_Q_COEF_X + 1) +: OperandBBits] = OperandBBits'(dy1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_Q_COEF_Y + 0) +: OperandABits] = OperandABits'(dq2);
    term_b[OperandBBits*(`CD_SETUP_TERM_Q_COEF_Y + 0) +: OperandBBits] = OperandBBits'(dx1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_Q_COEF_Y + 1) +: OperandABits] = OperandABits'(dq1);
    term_b[OperandBBits*(`CD_SETUP_TERM_Q_COEF_Y + 1) +: OperandBBits] = OperandBBits'(dx2_q);
    term_a[OperandABits*(`CD_SETUP_TERM_U_COEF_X + 0) +: OperandABits] = OperandABits'(du1);
    term_b[OperandBBits*(`CD_SETUP_TERM_U_COEF_X + 0) +: OperandBBits] = OperandBBits'(dy2_q);
    term_a[OperandABits*(`CD_SETUP_TERM_U_COEF_X + 1) +: OperandABits] = OperandABits'(du2);
    term_b[OperandBBits*(`CD_SETUP_TERM_U_COEF_X + 1) +: OperandBBits] = OperandBBits'(dy1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_U_COEF_Y + 0) +: OperandABits] = OperandABits'(du2);
    term_b[OperandBBits*(`CD_SETUP_TERM_U_COEF_Y + 0) +: OperandBBits] = OperandBBits'(dx1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_U_COEF_Y + 1) +: OperandABits] = OperandABits'(du1);
    term_b[OperandBBits*(`CD_SETUP_TERM_U_COEF_Y + 1) +: OperandBBits] = OperandBBits'(dx2_q);
    term_a[OperandABits*(`CD_SETUP_TERM_V_COEF_X + 0) +: OperandABits] = OperandABits'(dv1);
    term_b[OperandBBits*(`CD_SETUP_TERM_V_COEF_X + 0) +: OperandBBits] = OperandBBits'(dy2_q);
    term_a[OperandABits*(`CD_SETUP_TERM_V_COEF_X + 1) +: OperandABits] = OperandABits'(dv2);
    term_b[OperandBBits*(`CD_SETUP_TERM_V_COEF_X + 1) +: OperandBBits] = OperandBBits'(dy1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_V_COEF_Y + 0) +: OperandABits] = OperandABits'(dv2);
    term_b[OperandBBits*(`CD_SETUP_TERM_V_COEF_Y + 0) +: OperandBBits] = OperandBBits'(dx1_q);
    term_a[OperandABits*(`CD_SETUP_TERM_V_COEF_Y + 1) +: OperandABits] = OperandABits'(dv1);
    term_b[OperandBBits*(`CD_SETUP_TERM_V_COEF_Y + 1) +: OperandBBits] = OperandBBits'(dx2_q);
    for (int i = 0; i < 3; i++) begin
      if (window_b && HasPlanes) begin
        term_a[OperandABits*(`CD_SETUP_TERM_PEAK0 + i) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_q[i]}));
        term_b[OperandBBits*(`CD_SETUP_TERM_PEAK0 + i) +: OperandBBits] = OperandBBits'(det_abs);
      end
    end
    // stage C
    if (window_c && HasPlanes) begin
      term_a[OperandABits*(`CD_SETUP_TERM_Q_REF + 0) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_q[0]}));
      term_b[OperandBBits*(`CD_SETUP_TERM_Q_REF + 0) +: OperandBBits] = OperandBBits'(det_abs_q);
      term_a[OperandABits*(`CD_SETUP_TERM_Q_REF + 1) +: OperandABits] = OperandABits'(q_coef_x_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_Q_REF + 1) +: OperandBBits] = OperandBBits'(ref_x_q);
      term_a[OperandABits*(`CD_SETUP_TERM_Q_REF + 2) +: OperandABits] = OperandABits'(q_coef_y_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_Q_REF + 2) +: OperandBBits] = OperandBBits'(ref_y_q);
      term_a[OperandABits*(`CD_SETUP_TERM_U_REF + 0) +: OperandABits] = OperandABits'(u_attr_q[0]);
      term_b[OperandBBits*(`CD_SETUP_TERM_U_REF + 0) +: OperandBBits] = OperandBBits'(det_abs_q);
      term_a[OperandABits*(`CD_SETUP_TERM_U_REF + 1) +: OperandABits] = OperandABits'(u_coef_x_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_U_REF + 1) +: OperandBBits] = OperandBBits'(ref_x_q);
      term_a[OperandABits*(`CD_SETUP_TERM_U_REF + 2) +: OperandABits] = OperandABits'(u_coef_y_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_U_REF + 2) +: OperandBBits] = OperandBBits'(ref_y_q);
      term_a[OperandABits*(`CD_SETUP_TERM_V_REF + 0) +: OperandABits] = OperandABits'(v_attr_q[0]);
      term_b[OperandBBits*(`CD_SETUP_TERM_V_REF + 0) +: OperandBBits] = OperandBBits'(det_abs_q);
      term_a[OperandABits*(`CD_SETUP_TERM_V_REF + 1) +: OperandABits] = OperandABits'(v_coef_x_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_V_REF + 1) +: OperandBBits] = OperandBBits'(ref_x_q);
      term_a[OperandABits*(`CD_SETUP_TERM_V_REF + 2) +: OperandABits] = OperandABits'(v_coef_y_q);
      term_b[OperandBBits*(`CD_SETUP_TERM_V_REF + 2) +: OperandBBits] = OperandBBits'(ref_y_q);
    end
    for (int i = 0; i < 3; i++) begin
      term_a[OperandABits*(`CD_SETUP_TERM_EDGE_N0 + i) +: OperandABits] = OperandABits'(edge_fixed[i]);
      if (window_c)
        term_b[OperandBBits*(`CD_SETUP_TERM_EDGE_N0 + i) +: OperandBBits] =
            (OperandBBits'($signed({1'b0, major_lo_c})) <<< SubpixelBits) + OperandBBits'(HalfPx);
    end
    // stage D
    term_a[OperandABits*`CD_SETUP_TERM_STEP_U +: OperandABits] = OperandABits'(u_axis_minor);
    term_b[OperandBBits*`CD_SETUP_TERM_STEP_U +: OperandBBits] = OperandBBits'(g_d);
    term_a[OperandABits*`CD_SETUP_TERM_STEP_V +: OperandABits] = OperandABits'(v_axis_minor);
    term_b[OperandBBits*`CD_SETUP_TERM_STEP_V +: OperandBBits] = OperandBBits'(g_d);
    for (int i = 0; i < 3; i++) begin
      term_a[OperandABits*(`CD_SETUP_TERM_KAPPA0 + i) +: OperandABits] = OperandABits'(vertex_major[i]);
      term_b[OperandBBits*(`CD_SETUP_TERM_KAPPA0 + i) +: OperandBBits] = OperandBBits'(g_d);
    end
    term_a[OperandABits*`CD_SETUP_TERM_ROUND_LAST +: OperandABits] = OperandABits'(columns_less_one);
    term_b[OperandBBits*`CD_SETUP_TERM_ROUND_LAST +: OperandBBits] = OperandBBits'(g_d);
    // stage E
    if (HasLines) begin
      term_a[OperandABits*`CD_SETUP_TERM_Q_LINE +: OperandABits] = OperandABits'(q_per_line_q);
      term_b[OperandBBits*`CD_SETUP_TERM_Q_LINE +: OperandBBits] = OperandBBits'(first_line);
      term_a[OperandABits*`CD_SETUP_TERM_U_LINE +: OperandABits] = OperandABits'(u_per_line_q);
      term_b[OperandBBits*`CD_SETUP_TERM_U_LINE +: OperandBBits] = OperandBBits'(first_line);
      term_a[OperandABits*`CD_SETUP_TERM_V_LINE +: OperandABits] = OperandABits'(v_per_line_q);
      term_b[OperandBBits*`CD_SETUP_TERM_V_LINE +: OperandBBits] = OperandBBits'(first_line);
    end
  end

  // ---------------------------------------------------------------- stage E and fill
  if (HasLines) begin : gen_fill
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
          q_per_line_c <= q_per_line_q;
          u_per_line_c <= u_per_line_q;
          v_per_line_c <= v_per_line_q;
          step_u_c <= step_u_q;
          step_v_c <= step_v_q;
          guard_c <= guard_q;
        end
      end
      assign {fill_q_per_line, fill_u_per_line, fill_v_per_line, fill_step_u, fill_step_v, fill_guard} =
             {q_per_line_c, u_per_line_c, v_per_line_c, step_u_c, step_v_c, guard_c};
      assign load = fill_load_i;
    end else begin : gen_fill_shared
      assign {fill_q_per_line, fill_u_per_line, fill_v_per_line, fill_step_u, fill_step_v, fill_guard} =
             {q_per_line_q, u_per_line_q, v_per_line_q, step_u_q, step_v_q, guard_q};
      assign load = stage_e;
      logic unused_fill_load;
      assign unused_fill_load = fill_load_i;
    end

    always_comb begin
      q_line_d = q_line_q;
      u_line_d = u_line_q;
      v_line_d = v_line_q;
      if (load) begin
        // at the reference + first line x per line
        q_line_d = FillQBits'(q_at_ref_q) + FillQBits'(products[AccBits*`CD_SETUP_Q_LINE +: AccBits]);
        u_line_d = FillUvBits'(u_at_ref_q) + FillUvBits'(products[AccBits*`CD_SETUP_U_LINE +: AccBits]);
        v_line_d = FillUvBits'(v_at_ref_q) + FillUvBits'(products[AccBits*`CD_SETUP_V_LINE +: AccBits]);
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
    logic [5:0]                       entry_saturated;

    always_comb begin
      {result_addr, result_depth_out, result_exponent, operand_tu, operand_tv, operand_t_saturated} =
          result_valid ? result_tag : '0;
      shift_s = result_valid ? ProductShiftBits'($signed({1'b0, result_exponent})) + ProductShiftBits'(UvInFrac - OperandSFrac)
                             : '0;
    end
    shift_round #(.InBits(StepUvBits), .OutBits(OperandSBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxSLeft))
      u_operand_su (.enable_i(result_valid), .in_i(fill_step_u), .shift_i(shift_s), .out_o(operand_su),
                    .saturated_o(entry_saturated[4]));
    shift_round #(.InBits(StepUvBits), .OutBits(OperandSBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxSLeft))
      u_operand_sv (.enable_i(result_valid), .in_i(fill_step_v), .shift_i(shift_s), .out_o(operand_sv),
                    .saturated_o(entry_saturated[5]));

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

    shift_round #(.InBits(ProductTBits), .OutBits(TBits), .ShiftBits(ProductShiftBits))
      u_narrow_tu (.enable_i(result_valid), .in_i(product_tu), .shift_i(QuotientShift), .out_o(t_u),
                   .saturated_o(entry_saturated[0]));
    shift_round #(.InBits(ProductTBits), .OutBits(TBits), .ShiftBits(ProductShiftBits))
      u_narrow_tv (.enable_i(result_valid), .in_i(product_tv), .shift_i(QuotientShift), .out_o(t_v),
                   .saturated_o(entry_saturated[1]));
    shift_round #(.InBits(ProductSBits), .OutBits(SBits), .ShiftBits(ProductShiftBits))
      u_narrow_su (.enable_i(result_valid), .in_i(product_su), .shift_i(QuotientShift), .out_o(s_u),
                   .saturated_o(entry_saturated[2]));
    shift_round #(.InBits(ProductSBits), .OutBits(SBits), .ShiftBits(ProductShiftBits))
      u_narrow_sv (.enable_i(result_valid), .in_i(product_sv), .shift_i(QuotientShift), .out_o(s_v),
                   .saturated_o(entry_saturated[3]));

    // cd-persp: eps = q_line R: q_line narrowed by e to eps_frac + guard
    // fraction bits, its product read with RecipBits + eps_frac + guard
    // fraction bits, to s2.eps_frac (round to nearest, saturate); its most
    // negative code is moved up by one, so that -eps fits as well, and flagged.
    logic signed [EpsBits-1:0] eps, eps_rounded;
    logic                      eps_saturated;
    if (HasPersp) begin : gen_eps
      logic signed [OperandEpsBits-1:0]   operand_eps;
      logic signed [ProductEpsBits-1:0]   product_eps;
      logic signed [ProductShiftBits-1:0] shift_eps;
      logic [1:0]                         eps_overflow;
      assign shift_eps = result_valid ? ProductShiftBits'($signed({1'b0, result_exponent})) - ProductShiftBits'(OperandEpsFrac)
                                      : '0;
      shift_round #(.InBits(PlaneStepQBits), .OutBits(OperandEpsBits), .ShiftBits(ProductShiftBits), .MaxLeft(MaxEpsLeft))
        u_operand_eps (.enable_i(result_valid), .in_i(fill_q_per_line), .shift_i(shift_eps), .out_o(operand_eps),
                       .saturated_o(eps_overflow[0]));
      always_comb begin
        product_eps = '0;
        if (result_valid) product_eps = ProductEpsBits'(operand_eps) * ProductEpsBits'($signed({1'b0, recip}));
      end
      shift_round #(.InBits(ProductEpsBits), .OutBits(EpsBits), .ShiftBits(ProductShiftBits))
        u_narrow_eps (.enable_i(result_valid), .in_i(product_eps), .shift_i(QuotientShift), .out_o(eps_rounded),
                      .saturated_o(eps_overflow[1]));
      always_comb begin
        eps = eps_rounded;
        eps_saturated = |eps_overflow;
        if (eps_rounded == {1'b1, {(EpsBits - 1){1'b0}}}) begin
          eps = eps_rounded + EpsBits'(1);
          eps_saturated = 1'b1;
        end
      end
    end else begin : gen_no_eps
      assign eps = '0;
      assign eps_rounded = '0;
      assign eps_saturated = 1'b0;
    end

    always_comb begin
      write_entry_o = '0;
      write_entry_o[`CD_WORD_TU_LSB +: TBits] = t_u;
      write_entry_o[`CD_WORD_TV_LSB +: TBits] = t_v;
      write_entry_o[`CD_WORD_SU_LSB +: SBits] = s_u;
      write_entry_o[`CD_WORD_SV_LSB +: SBits] = s_v;
      write_entry_o[`CD_WORD_SATURATED_BIT] = |entry_saturated || operand_t_saturated;
      write_entry_o[`CD_WORD_DEPTH_RANGE_BIT] = result_depth_out;
      if (HasPersp) begin
        write_entry_o[`CD_WORD_EPS_LSB +: EpsBits] = eps;
        write_entry_o[`CD_WORD_EPS_SATURATED_BIT] = eps_saturated;
      end
    end
    assign write_valid_o = result_valid && !hold_i;
    assign write_addr_o = result_addr;
  end else begin : gen_no_fill
    logic unused_fill;
    assign unused_fill = ^{hold_i, fill_load_i, fill_valid_i, fill_last_i, fill_addr_i, q_at_ref_q, u_at_ref_q, v_at_ref_q,
                           q_per_line_q, u_per_line_q, v_per_line_q, step_u_q, step_v_q, line_lo_q,
                           guard_q};
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
        assert (edge_free_q[i] == 0 || (!bound_overflow[i] && !slope_overflow[i]))
          else $error("setup_engine: edge %0d divider quotient overflow", i);
      end
    end
  end
`endif

endmodule

`default_nettype wire
