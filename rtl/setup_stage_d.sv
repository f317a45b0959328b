// Setup engine, stage D (rtl/setup_engine.sv): the dividers' results, the
// planes normalised by the shared shift, the numerators of S, the walk's axes,
// the range of lines the covered pixels use and the column walker's edge
// trackers. Twin of cdsim::setup_stage_d (model/setup_engine.cpp). Window,
// stage and products as in setup_stage_a.sv (results CD_SETUP_STEP_U ..
// CD_SETUP_ROUND_LAST); its window opens when the dividers are done.
`include "cd_widths.svh"
`default_nettype none

module setup_stage_d #(
  // The constant-depth designs' hardware: g, the S numerators, the line range.
  parameter bit HasLines = 1'b1,
  // The per-pixel designs' planes along the major axis.
  parameter bit HasPixelPlanes = 1'b1,
  // The normalised planes of q, U and V.
  parameter bit HasPlanes = 1'b1,
  localparam int SubpixelBits = `CD_SUBPIXEL_BITS,
  localparam int GFrac        = `CD_G_FRAC,
  localparam int CoordBits    = `CD_COORD_BITS,
  localparam int DiffBits     = `CD_DIFF_BITS,
  localparam int PixelBits    = `CD_PIXEL_BITS,
  localparam int CoefQBits    = `CD_COEF_Q_BITS,
  localparam int CoefUvBits   = `CD_COEF_UV_BITS,
  localparam int ExactRefQBits  = `CD_EXACT_REF_Q_BITS,
  localparam int ExactRefUvBits = `CD_EXACT_REF_UV_BITS,
  localparam int ShiftBits    = `CD_SHIFT_BITS,
  localparam int PlaneRefQBits  = `CD_PLANE_REF_Q_BITS,
  localparam int PlaneRefUvBits = `CD_PLANE_REF_UV_BITS,
  localparam int PlaneStepQBits  = `CD_PLANE_STEP_Q_BITS,
  localparam int PlaneStepUvBits = `CD_PLANE_STEP_UV_BITS,
  localparam int StepUvBits   = `CD_STEP_UV_BITS,
  localparam int GBits        = `CD_G_BITS,
  localparam int LineBits     = `CD_LINE_BITS,
  localparam int EdgeNBits    = `CD_EDGE_N_BITS,
  localparam int EdgeStepBits = `CD_EDGE_STEP_BITS,
  localparam int EdgeBoundBits = `CD_EDGE_BOUND_BITS,
  localparam int EdgeSlopeBits = `CD_EDGE_SLOPE_BITS,
  localparam int GDivQuoBits  = `CD_G_DIV_QUOTIENT_BITS,
  localparam int BoundDivQuoBits = `CD_BOUND_DIV_QUOTIENT_BITS,
  localparam int SlopeDivQuoBits = `CD_SLOPE_DIV_QUOTIENT_BITS,
  localparam int AccBits      = `CD_SETUP_ACC_BITS,
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS,
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS,
  localparam int GDivDenBits  = CoefQBits,
  localparam int FreeBits     = DiffBits - 1,
  localparam int BoundNumBits = EdgeNBits - SubpixelBits,
  localparam int PeakBits     = `CD_PEAK_BITS,
  localparam int PhaseBits    = `CD_LINE_PHASE_FRAC > 0 ? `CD_LINE_PHASE_FRAC : 1,
  localparam int FirstResult  = `CD_SETUP_STEP_U,
  localparam int Results      = `CD_SETUP_Q_LINE - `CD_SETUP_STEP_U,
  localparam int FirstTerm    = `CD_SETUP_TERM_STEP_U,
  localparam int Terms        = `CD_SETUP_TERM_Q_LINE - `CD_SETUP_TERM_STEP_U
) (
  input  logic                             clk_i,
  input  logic                             window_i,
  input  logic                             stage_i,
  // The cycle that forms kappa's extremes: stage_i, or the one before it
  // with CD_SETUP_LINE_REGISTER.
  input  logic                             kappa_stage_i,
  // The triangle as loaded (vertex i in bits i*W +: W).
  input  logic [3*CoordBits-1:0]           x_i,
  input  logic [3*CoordBits-1:0]           y_i,
  input  logic [1:0]                       density_log2_i,
  input  logic                             lines_i,  // a constant-depth triangle: its lines may take a phase
  input  logic                             fallback_i,  // ... of a design with a divide fallback
  // Stage A's registers.
  input  logic [PixelBits-1:0]             box_x_lo_i,
  input  logic [PixelBits-1:0]             box_x_hi_i,
  input  logic [PixelBits-1:0]             box_y_lo_i,
  input  logic [PixelBits-1:0]             box_y_hi_i,
  input  logic signed [DiffBits-1:0]       ref_x_i,
  input  logic signed [DiffBits-1:0]       ref_y_i,
  // Stage B's registers.
  input  logic signed [CoefQBits-1:0]      q_coef_x_i,
  input  logic signed [CoefQBits-1:0]      q_coef_y_i,
  input  logic signed [CoefUvBits-1:0]     u_coef_x_i,
  input  logic signed [CoefUvBits-1:0]     u_coef_y_i,
  input  logic signed [CoefUvBits-1:0]     v_coef_x_i,
  input  logic signed [CoefUvBits-1:0]     v_coef_y_i,
  input  logic [PeakBits-1:0]              q_floor_i,  // the far vertex's q |det|
  // Stage C's registers.
  input  logic signed [ExactRefQBits-1:0]  q_ref_i,
  input  logic signed [ExactRefUvBits-1:0] u_ref_i,
  input  logic signed [ExactRefUvBits-1:0] v_ref_i,
  input  logic                             x_major_i,
  input  logic signed [ShiftBits-1:0]      shift_i,
  input  logic                             g_zero_i,
  input  logic                             g_negative_i,
  input  logic [3*DiffBits-1:0]            edge_fixed_i,
  input  logic [3*DiffBits-1:0]            edge_free_i,
  input  logic [3*BoundNumBits-1:0]        edge_n_high_i,
  input  logic [3*SubpixelBits-1:0]        edge_n_low_i,
  // The dividers' results.
  input  logic [GDivQuoBits-1:0]           g_quotient_i,
  input  logic [GDivDenBits-1:0]           g_remainder_i,
  input  logic                             g_overflow_i,
  input  logic [3*BoundDivQuoBits-1:0]     bound_quotient_i,
  input  logic [3*FreeBits-1:0]            bound_remainder_i,
  input  logic [3*SlopeDivQuoBits-1:0]     slope_quotient_i,
  input  logic [3*FreeBits-1:0]            slope_remainder_i,
  input  logic [Results*AccBits-1:0]       products_i,
  output logic [Terms*OperandABits-1:0]    term_a_o,
  output logic [Terms*OperandBBits-1:0]    term_b_o,
  // Registered in stage_i.
  output logic signed [GBits-1:0]          g_o,
  output logic [PixelBits-1:0]             major_lo_o,
  output logic [PixelBits:0]               major_count_o,
  output logic [PixelBits-1:0]             minor_lo_o,
  output logic [PixelBits-1:0]             minor_hi_o,
  output logic signed [LineBits-1:0]       line_lo_o,
  output logic signed [LineBits-1:0]       line_hi_o,
  output logic                             no_lines_o,
  // The divide fallback takes the triangle: its far vertex lies within
  // 2^CD_FALLBACK_GAPS_LOG2 line gaps of its horizon.
  output logic                             fallback_o,
  // The lines' phase, CD_LINE_PHASE_FRAC fraction bits of a line gap.
  output logic [PhaseBits-1:0]             line_phase_o,
  output logic signed [PlaneRefQBits-1:0]  q_at_ref_o,
  output logic signed [PlaneRefUvBits-1:0] u_at_ref_o,
  output logic signed [PlaneRefUvBits-1:0] v_at_ref_o,
  output logic signed [PlaneStepQBits-1:0] q_per_line_o,
  output logic signed [PlaneStepUvBits-1:0] u_per_line_o,
  output logic signed [PlaneStepUvBits-1:0] v_per_line_o,
  output logic signed [PlaneStepQBits-1:0] q_per_major_o,
  output logic signed [PlaneStepUvBits-1:0] u_per_major_o,
  output logic signed [PlaneStepUvBits-1:0] v_per_major_o,
  output logic signed [StepUvBits-1:0]     step_u_o,
  output logic signed [StepUvBits-1:0]     step_v_o,
  output logic [5:0]                       edge_kind_o,  // 2 bits per edge: 0 none, 1 lower, 2 upper
  output logic [3*EdgeBoundBits-1:0]       edge_bound_o,
  output logic [3*EdgeStepBits-1:0]        edge_rem_o,
  output logic [3*EdgeStepBits-1:0]        edge_step_o,
  output logic [3*EdgeSlopeBits-1:0]       edge_slope_o,
  output logic [3*EdgeStepBits-1:0]        edge_slope_rem_o,
  // In stage_i: a normalised value left its derived width (never, when the
  // derived widths hold; setup_engine.sv asserts it).
  output logic [11:0]                      normalise_saturated_o
);

  localparam int KappaBits    = `CD_KAPPA_BITS;
  // Exact values before the per-triangle shift.
  localparam int AxisQBits    = CoefQBits + SubpixelBits;   // q per pixel (coef 2^sp)
  localparam int AxisUvBits   = CoefUvBits + SubpixelBits;
  localparam int StepNumBits  = AxisUvBits + GFrac + 2;      // U_major 2^gf + g U_minor
  localparam int LineRangeBits = KappaBits - SubpixelBits - GFrac + 3;
  localparam int MaxPlaneLeft = `CD_PLANE_BITS + 2;

  logic signed [CoordBits-1:0]     x_q [3];
  logic signed [CoordBits-1:0]     y_q [3];
  logic signed [DiffBits-1:0]      edge_fixed_q [3];
  logic signed [DiffBits-1:0]      edge_free_q [3];
  logic signed [BoundNumBits-1:0]  edge_n_high_q [3];
  logic [SubpixelBits-1:0]         edge_n_low_q [3];
  logic [BoundDivQuoBits-1:0]      bound_quotient [3];
  logic [FreeBits-1:0]             bound_remainder [3];
  logic [SlopeDivQuoBits-1:0]      slope_quotient [3];
  logic [FreeBits-1:0]             slope_remainder [3];
  for (genvar i = 0; i < 3; i++) begin : gen_inputs
    assign x_q[i] = x_i[CoordBits*i +: CoordBits];
    assign y_q[i] = y_i[CoordBits*i +: CoordBits];
    assign edge_fixed_q[i] = edge_fixed_i[DiffBits*i +: DiffBits];
    assign edge_free_q[i] = edge_free_i[DiffBits*i +: DiffBits];
    assign edge_n_high_q[i] = edge_n_high_i[BoundNumBits*i +: BoundNumBits];
    assign edge_n_low_q[i] = edge_n_low_i[SubpixelBits*i +: SubpixelBits];
    assign bound_quotient[i] = bound_quotient_i[BoundDivQuoBits*i +: BoundDivQuoBits];
    assign bound_remainder[i] = bound_remainder_i[FreeBits*i +: FreeBits];
    assign slope_quotient[i] = slope_quotient_i[SlopeDivQuoBits*i +: SlopeDivQuoBits];
    assign slope_remainder[i] = slope_remainder_i[FreeBits*i +: FreeBits];
  end

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
    if (window_i) begin
      g_d = GBits'($signed({1'b0, g_quotient_i}));
      if (g_negative_i) g_d = -g_d - GBits'(g_remainder_i != '0);
      if (g_zero_i) g_d = '0;
      line_shift = density_log2_i;
      line_norm_shift = (ShiftBits+1)'(shift_i) + (ShiftBits+1)'($signed({1'b0, line_shift}));
      step_norm_shift = (ShiftBits+2)'(shift_i) + (ShiftBits+2)'(GFrac);
      q_axis_major = (x_major_i ? AxisQBits'(q_coef_x_i) : AxisQBits'(q_coef_y_i)) <<< SubpixelBits;
      q_axis_minor = (x_major_i ? AxisQBits'(q_coef_y_i) : AxisQBits'(q_coef_x_i)) <<< SubpixelBits;
      u_axis_major = (x_major_i ? AxisUvBits'(u_coef_x_i) : AxisUvBits'(u_coef_y_i)) <<< SubpixelBits;
      u_axis_minor = (x_major_i ? AxisUvBits'(u_coef_y_i) : AxisUvBits'(u_coef_x_i)) <<< SubpixelBits;
      v_axis_major = (x_major_i ? AxisUvBits'(v_coef_x_i) : AxisUvBits'(v_coef_y_i)) <<< SubpixelBits;
      v_axis_minor = (x_major_i ? AxisUvBits'(v_coef_y_i) : AxisUvBits'(v_coef_x_i)) <<< SubpixelBits;
    end
  end

  // U_major 2^g_frac + g U_minor
  always_comb begin
    step_u_exact = '0;
    step_v_exact = '0;
    if (stage_i) begin
      step_u_exact = (StepNumBits'(u_axis_major) <<< GFrac) + StepNumBits'(products_i[AccBits*(`CD_SETUP_STEP_U - FirstResult) +: AccBits]);
      step_v_exact = (StepNumBits'(v_axis_major) <<< GFrac) + StepNumBits'(products_i[AccBits*(`CD_SETUP_STEP_V - FirstResult) +: AccBits]);
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
      u_norm_q_ref (.enable_i(stage_i), .in_i(q_ref_i), .shift_i(shift_i), .out_o(q_at_ref_d), .saturated_o(normalise_saturated[0]));
    shift_round #(.InBits(ExactRefUvBits), .OutBits(PlaneRefUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_ref (.enable_i(stage_i), .in_i(u_ref_i), .shift_i(shift_i), .out_o(u_at_ref_d), .saturated_o(normalise_saturated[1]));
    shift_round #(.InBits(ExactRefUvBits), .OutBits(PlaneRefUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_ref (.enable_i(stage_i), .in_i(v_ref_i), .shift_i(shift_i), .out_o(v_at_ref_d), .saturated_o(normalise_saturated[2]));
    shift_round #(.InBits(AxisQBits), .OutBits(PlaneStepQBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_q_line (.enable_i(stage_i), .in_i(q_axis_minor), .shift_i(line_norm_shift), .out_o(q_per_line_d), .saturated_o(normalise_saturated[3]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_line (.enable_i(stage_i), .in_i(u_axis_minor), .shift_i(line_norm_shift), .out_o(u_per_line_d), .saturated_o(normalise_saturated[4]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits+1),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_line (.enable_i(stage_i), .in_i(v_axis_minor), .shift_i(line_norm_shift), .out_o(v_per_line_d), .saturated_o(normalise_saturated[5]));
  end else begin : gen_no_normalise
    logic unused_exact_planes;
    assign unused_exact_planes = ^{q_ref_i, u_ref_i, v_ref_i, q_axis_minor, u_axis_minor, v_axis_minor,
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
      u_norm_step_u (.enable_i(stage_i), .in_i(step_u_exact), .shift_i(step_norm_shift), .out_o(step_u_d), .saturated_o(normalise_saturated[6]));
    shift_round #(.InBits(StepNumBits), .OutBits(StepUvBits), .ShiftBits(ShiftBits+2),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_step_v (.enable_i(stage_i), .in_i(step_v_exact), .shift_i(step_norm_shift), .out_o(step_v_d), .saturated_o(normalise_saturated[7]));
  end else begin : gen_no_step_numerators
    logic unused_step_exact;
    assign unused_step_exact = ^{step_u_exact, step_v_exact, step_norm_shift};
    assign step_u_d = '0;
    assign step_v_d = '0;
    assign normalise_saturated[7:6] = '0;
  end
  assign normalise_saturated[8] = g_overflow_i && !g_zero_i;
  // Per pixel along the major axis, for the per-pixel planes of divide and
  // the other per-pixel designs (along the minor axis that is per_line at m = 1).
  if (HasPixelPlanes) begin : gen_major_planes
    shift_round #(.InBits(AxisQBits), .OutBits(PlaneStepQBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_q_major (.enable_i(stage_i), .in_i(q_axis_major), .shift_i(shift_i), .out_o(q_per_major_d), .saturated_o(normalise_saturated[9]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_u_major (.enable_i(stage_i), .in_i(u_axis_major), .shift_i(shift_i), .out_o(u_per_major_d), .saturated_o(normalise_saturated[10]));
    shift_round #(.InBits(AxisUvBits), .OutBits(PlaneStepUvBits), .ShiftBits(ShiftBits),
                  .MaxLeft(MaxPlaneLeft))
      u_norm_v_major (.enable_i(stage_i), .in_i(v_axis_major), .shift_i(shift_i), .out_o(v_per_major_d), .saturated_o(normalise_saturated[11]));
  end else begin : gen_no_major_planes
    logic unused_axis_major;
    assign unused_axis_major = ^q_axis_major;
    assign q_per_major_d = '0;
    assign u_per_major_d = '0;
    assign v_per_major_d = '0;
    assign normalise_saturated[11:9] = '0;
  end
  assign normalise_saturated_o = normalise_saturated;

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
  // The line phase (model/setup_engine.cpp, setup_stage_d): phi = the far
  // vertex's kappa modulo one gap, rounded away from the triangle to
  // PhaseFrac bits; taken when the farthest line without it, less than
  // (quarters + 1) / 4 gaps beyond the far vertex, may lie within half a gap
  // of the horizon, h = q_floor m / |q per minor pixel| gaps beyond it:
  // 4 q_floor m < |q per minor pixel| (quarters + 3).
  localparam int PhaseFrac      = `CD_LINE_PHASE_FRAC;
  localparam int PhaseUnitLog2  = SubpixelBits + GFrac - PhaseFrac;  // 2^-PhaseFrac gaps in kappa's units
  localparam int HorizonBits    = (PeakBits > AxisQBits ? PeakBits : AxisQBits) + 6;
  logic [HorizonBits-1:0]          floor_lines, minor_gaps;
  logic [PhaseBits-1:0]            phi, beyond;
  logic [2:0]                      quarters, multiple;  // multiple = quarters + 3
  logic                            phased;
  // The divide fallback (model/setup_engine.cpp): q_floor m < |q per minor pixel| 2^k.
  localparam int FallbackLog2   = `CD_FALLBACK_GAPS_LOG2;
  localparam int FallbackBits   = (PeakBits > AxisQBits ? PeakBits : AxisQBits) + 3 + FallbackLog2;
  logic [FallbackBits-1:0]         fallback_floor, fallback_gaps;
  logic                            fallback_d;
  logic signed [KappaBits-1:0]     phase_kappa;
  logic [PhaseBits-1:0]            phase_d;
  logic signed [GFrac+1:0]         phase_g;
  logic signed [LineRangeBits-1:0] round_first;

  // The operands: the walk's axes, each vertex's offsets along them, and the
  // box's last column.
  always_comb begin
    major_lo_d = '0;
    major_count_d = '0;
    minor_lo_d = '0;
    minor_hi_d = '0;
    for (int i = 0; i < 3; i++) vertex_major[i] = '0;
    for (int i = 0; i < 3; i++) vertex_minor[i] = '0;
    columns_less_one = '0;
    if (window_i) begin
      major_lo_d = x_major_i ? box_x_lo_i : box_y_lo_i;
      major_count_d = x_major_i ? (PixelBits+1)'(box_x_hi_i) - (PixelBits+1)'(box_x_lo_i) + 1
                                : (PixelBits+1)'(box_y_hi_i) - (PixelBits+1)'(box_y_lo_i) + 1;
      minor_lo_d = x_major_i ? box_y_lo_i : box_x_lo_i;
      minor_hi_d = x_major_i ? box_y_hi_i : box_x_hi_i;
    end
    if (window_i && HasLines) begin
      for (int i = 0; i < 3; i++) begin
        vertex_major[i] = (x_major_i ? (DiffBits+1)'(x_q[i]) - (DiffBits+1)'(x_q[0]) - (DiffBits+1)'(ref_x_i)
                                  : (DiffBits+1)'(y_q[i]) - (DiffBits+1)'(y_q[0]) - (DiffBits+1)'(ref_y_i));
        vertex_minor[i] = (x_major_i ? (DiffBits+1)'(y_q[i]) - (DiffBits+1)'(y_q[0]) - (DiffBits+1)'(ref_y_i)
                                  : (DiffBits+1)'(x_q[i]) - (DiffBits+1)'(x_q[0]) - (DiffBits+1)'(ref_x_i));
      end
      columns_less_one = (PixelBits+2)'($signed({1'b0, major_count_d})) - (PixelBits+2)'(1);
    end
  end

  // The vertices' kappa and their extremes, in kappa_stage_i: with
  // setup_line_register a cycle before stage_i, registered for the rest of
  // the line range (the phase, the horizon's comparators, the range and its
  // clamps), which then takes a cycle of its own; else in stage_i itself.
  localparam bit LineRegister = `CD_SETUP_LINE_REGISTER != 0;
  logic signed [KappaBits-1:0]     kappa_lo_d, kappa_hi_d;
  always_comb begin
    kappa_lo_d = '0;
    kappa_hi_d = '0;
    kappa = '0;
    if (kappa_stage_i && HasLines) begin
      for (int i = 0; i < 3; i++) begin
        kappa = ((KappaBits'(vertex_minor[i]) <<< GFrac) -
                 KappaBits'(products_i[AccBits*(`CD_SETUP_KAPPA0 + i - FirstResult) +: AccBits]))  // g major offset
                <<< density_log2_i;
        if (i == 0 || kappa < kappa_lo_d) kappa_lo_d = kappa;
        if (i == 0 || kappa > kappa_hi_d) kappa_hi_d = kappa;
      end
    end
  end
  context_register #(.Bits(2 * KappaBits), .Present(LineRegister)) u_kappa_stage (
    .clk_i, .load_i(kappa_stage_i), .d_i({kappa_lo_d, kappa_hi_d}), .q_o({kappa_lo, kappa_hi}));

  always_comb begin
    line_lo = '0;
    line_hi = '0;
    floor_lines = '0;
    minor_gaps = '0;
    phased = 1'b0;
    phi = '0;
    beyond = '0;
    quarters = '0;
    multiple = '0;
    phase_kappa = '0;
    phase_d = '0;
    phase_g = '0;
    round_first = '0;
    round_product = '0;
    round_last = '0;
    minor_extent = '0;
    no_lines_d = '0;
    fallback_floor = '0;
    fallback_gaps = '0;
    fallback_d = '0;
    if (stage_i && HasLines) begin
      // The phase: q grows with kappa when it grows along the minor axis, so
      // the far vertex has the least kappa (floor) or else the greatest (ceil):
      // its kappa in 2^-PhaseFrac gaps, modulo one gap.
      phi = PhaseBits'(q_axis_minor > 0 ? kappa_lo >>> PhaseUnitLog2 : -((-kappa_hi) >>> PhaseUnitLog2));
      beyond = q_axis_minor > 0 || phi == '0 ? phi : PhaseBits'(-phi);
      // The least with (beyond + 1) 2^-PhaseFrac <= (quarters + 1) / 4.
      quarters = 3'({beyond, 2'b11} >> PhaseFrac);
      floor_lines = (HorizonBits'(q_floor_i) << 2) << density_log2_i;
      multiple = quarters + 3'd3;
      minor_gaps = (q_axis_minor < 0 ? -(HorizonBits'(q_axis_minor)) : HorizonBits'(q_axis_minor)) *
                   HorizonBits'(multiple);
      // With g = 0 every pixel lies on its own line and reads no neighbour.
      phased = PhaseFrac > 0 && lines_i && q_axis_minor != '0 && g_d != '0 && floor_lines < minor_gaps;
      if (phased) phase_d = phi;
      fallback_floor = FallbackBits'(q_floor_i) << density_log2_i;
      fallback_gaps = (q_axis_minor < 0 ? -(FallbackBits'(q_axis_minor)) : FallbackBits'(q_axis_minor)) << FallbackLog2;
      // Only a unit with the per-pixel planes the fallback walks by has it.
      fallback_d = HasPixelPlanes && fallback_i && q_axis_minor != '0 && g_d != '0 && fallback_floor < fallback_gaps;
      phase_kappa = KappaBits'($signed({1'b0, phase_d})) <<< PhaseUnitLog2;
      phase_g = (GFrac+2)'($signed({1'b0, phase_d})) <<< (GFrac - PhaseFrac);
      // ceil((2 kappa' - scale) / (2 scale)) and ceil((2 kappa' + scale) / (2 scale)) - 1, kappa' = kappa - phi.
      line_lo = LineRangeBits'(-((KappaScale - ((kappa_lo - phase_kappa) <<< 1)) >>> (SubpixelBits + GFrac + 1)));
      line_hi = LineRangeBits'(-((-((kappa_hi - phase_kappa) <<< 1) - KappaScale) >>> (SubpixelBits + GFrac + 1))) - 1;
      // The box bounds them too: line = m minor_offset - round(m g o + phi).
      round_first = LineRangeBits'(phase_g >= (GFrac+2)'(1 <<< (GFrac - 1)));
      round_product = ((GBits+PixelBits+4)'(products_i[AccBits*(`CD_SETUP_ROUND_LAST - FirstResult) +: AccBits])  // g (columns - 1)
                       <<< density_log2_i) + (GBits+PixelBits+4)'(phase_g);
      round_last = LineRangeBits'((GBits+PixelBits+4)'((round_product + (GBits+PixelBits+4)'(1 <<< (GFrac - 1))) >>> GFrac));
      minor_extent = (LineRangeBits'($signed({1'b0, minor_hi_d})) - LineRangeBits'($signed({1'b0, minor_lo_d})))
                     <<< density_log2_i;
      if (round_last > round_first) begin
        if (line_lo < -round_last) line_lo = -round_last;
      end else if (line_lo < -round_first) begin
        line_lo = -round_first;
      end
      if (round_last < round_first) begin
        if (line_hi > minor_extent - round_last) line_hi = minor_extent - round_last;
      end else if (line_hi > minor_extent - round_first) begin
        line_hi = minor_extent - round_first;
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
    if (stage_i) begin
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

  always_ff @(posedge clk_i) begin
    if (stage_i) begin
      g_o <= g_d;
      major_lo_o <= major_lo_d;
      major_count_o <= major_count_d;
      minor_lo_o <= minor_lo_d;
      minor_hi_o <= minor_hi_d;
      line_lo_o <= LineBits'(line_lo);
      line_hi_o <= LineBits'(line_hi);
      no_lines_o <= no_lines_d;
      fallback_o <= fallback_d;
      line_phase_o <= phase_d;
      q_at_ref_o <= q_at_ref_d;
      u_at_ref_o <= u_at_ref_d;
      v_at_ref_o <= v_at_ref_d;
      q_per_line_o <= q_per_line_d;
      u_per_line_o <= u_per_line_d;
      v_per_line_o <= v_per_line_d;
      q_per_major_o <= q_per_major_d;
      u_per_major_o <= u_per_major_d;
      v_per_major_o <= v_per_major_d;
      step_u_o <= step_u_d;
      step_v_o <= step_v_d;
      for (int i = 0; i < 3; i++) begin
        edge_kind_o[2*i +: 2] <= edge_kind_d[i];
        edge_bound_o[EdgeBoundBits*i +: EdgeBoundBits] <= edge_bound_d[i];
        edge_rem_o[EdgeStepBits*i +: EdgeStepBits] <= edge_rem_d[i];
        edge_step_o[EdgeStepBits*i +: EdgeStepBits] <= edge_step_d[i];
        edge_slope_o[EdgeSlopeBits*i +: EdgeSlopeBits] <= edge_slope_d[i];
        edge_slope_rem_o[EdgeStepBits*i +: EdgeStepBits] <= edge_slope_rem_d[i];
      end
    end
  end

  // Each term's operands (model/setup_terms.def), sign-extended.
  always_comb begin
    term_a_o = '0;
    term_b_o = '0;
    term_a_o[OperandABits*(`CD_SETUP_TERM_STEP_U - FirstTerm) +: OperandABits] = OperandABits'(u_axis_minor);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_STEP_U - FirstTerm) +: OperandBBits] = OperandBBits'(g_d);
    term_a_o[OperandABits*(`CD_SETUP_TERM_STEP_V - FirstTerm) +: OperandABits] = OperandABits'(v_axis_minor);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_STEP_V - FirstTerm) +: OperandBBits] = OperandBBits'(g_d);
    for (int i = 0; i < 3; i++) begin
      term_a_o[OperandABits*(`CD_SETUP_TERM_KAPPA0 + i - FirstTerm) +: OperandABits] = OperandABits'(vertex_major[i]);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_KAPPA0 + i - FirstTerm) +: OperandBBits] = OperandBBits'(g_d);
    end
    term_a_o[OperandABits*(`CD_SETUP_TERM_ROUND_LAST - FirstTerm) +: OperandABits] = OperandABits'(columns_less_one);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_ROUND_LAST - FirstTerm) +: OperandBBits] = OperandBBits'(g_d);
  end

endmodule

`default_nettype wire
