// Setup engine, stage C (rtl/setup_engine.sv): the planes at the reference
// centre, s A0 det + A_x ref_x + A_y ref_y (exact), the orientation, the
// shared shift, and the operands of the dividers (setup_dividers.sv), which
// start in this stage. Twin of cdsim::setup_stage_c (model/setup_engine.cpp).
// Window, stage and products as in setup_stage_a.sv (results
// CD_SETUP_Q_REF .. CD_SETUP_EDGE_N2).
`include "cd_widths.svh"
`default_nettype none

module setup_stage_c #(
  parameter bit HasPlanes = 1'b1,
  localparam int SubpixelBits = `CD_SUBPIXEL_BITS,
  localparam int GFrac        = `CD_G_FRAC,
  localparam int DiffBits     = `CD_DIFF_BITS,
  localparam int DetBits      = `CD_DET_BITS,
  localparam int EdgeCBits    = `CD_EDGE_C_BITS,
  localparam int PixelBits    = `CD_PIXEL_BITS,
  localparam int QVertexBits  = `CD_Q_VERTEX_BITS,
  localparam int AttrUvBits   = `CD_ATTR_UV_BITS,
  localparam int CoefQBits    = `CD_COEF_Q_BITS,
  localparam int CoefUvBits   = `CD_COEF_UV_BITS,
  localparam int ExactRefQBits  = `CD_EXACT_REF_Q_BITS,
  localparam int ExactRefUvBits = `CD_EXACT_REF_UV_BITS,
  localparam int PeakBits     = `CD_PEAK_BITS,
  localparam int ShiftBits    = `CD_SHIFT_BITS,
  localparam int EdgeNBits    = `CD_EDGE_N_BITS,
  localparam int AccBits      = `CD_SETUP_ACC_BITS,
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS,
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS,
  localparam int GDivNumBits  = CoefQBits + GFrac + 1,     // |2 N' + D'|
  localparam int GDivDenBits  = CoefQBits,                 // 2 |q_minor|
  localparam int FreeBits     = DiffBits - 1,              // |free coefficient|
  localparam int BoundNumBits = EdgeNBits - SubpixelBits,  // |N0 >> sp|
  localparam int FirstResult  = `CD_SETUP_Q_REF,
  localparam int Results      = `CD_SETUP_STEP_U - `CD_SETUP_Q_REF,
  localparam int FirstTerm    = `CD_SETUP_TERM_Q_REF,
  localparam int Terms        = `CD_SETUP_TERM_STEP_U - `CD_SETUP_TERM_Q_REF
) (
  input  logic                            clk_i,
  input  logic                            window_i,
  input  logic                            stage_i,
  // Stage A's registers.
  input  logic [3*DiffBits-1:0]           edge_a_i,
  input  logic [3*DiffBits-1:0]           edge_b_i,
  input  logic [3*EdgeCBits-1:0]          edge_c_i,
  input  logic [2:0]                      edge_threshold_i,
  input  logic [PixelBits-1:0]            box_x_lo_i,
  input  logic [PixelBits-1:0]            box_y_lo_i,
  input  logic signed [DiffBits-1:0]      ref_x_i,
  input  logic signed [DiffBits-1:0]      ref_y_i,
  input  logic [QVertexBits-1:0]          q_vertex0_i,
  input  logic signed [AttrUvBits-1:0]    u_attr0_i,
  input  logic signed [AttrUvBits-1:0]    v_attr0_i,
  // Stage B's registers.
  input  logic signed [CoefQBits-1:0]     q_coef_x_i,
  input  logic signed [CoefQBits-1:0]     q_coef_y_i,
  input  logic signed [CoefUvBits-1:0]    u_coef_x_i,
  input  logic signed [CoefUvBits-1:0]    u_coef_y_i,
  input  logic signed [CoefUvBits-1:0]    v_coef_x_i,
  input  logic signed [CoefUvBits-1:0]    v_coef_y_i,
  input  logic [PeakBits-1:0]             q_peak_i,
  input  logic signed [DetBits-1:0]       det_abs_i,
  input  logic [Results*AccBits-1:0]      products_i,
  output logic [Terms*OperandABits-1:0]   term_a_o,
  output logic [Terms*OperandBBits-1:0]   term_b_o,
  // The dividers' operands, in stage_i (edge i in bits i*W +: W).
  output logic [GDivNumBits-1:0]          g_div_num_o,
  output logic [GDivDenBits-1:0]          g_div_den_o,
  output logic [3*BoundNumBits-1:0]       edge_n_high_abs_o,
  output logic [3*FreeBits-1:0]           edge_free_abs_o,
  output logic [3*FreeBits-1:0]           edge_fixed_abs_o,
  // Registered in stage_i.
  output logic signed [ExactRefQBits-1:0]  q_ref_o,
  output logic signed [ExactRefUvBits-1:0] u_ref_o,
  output logic signed [ExactRefUvBits-1:0] v_ref_o,
  output logic                            x_major_o,
  output logic signed [ShiftBits-1:0]     shift_o,
  output logic                            g_zero_o,
  output logic                            g_negative_o,
  output logic [3*DiffBits-1:0]           edge_fixed_o,
  output logic [3*DiffBits-1:0]           edge_free_o,
  output logic [3*BoundNumBits-1:0]       edge_n_high_o,
  output logic [3*SubpixelBits-1:0]       edge_n_low_o
);

  localparam int PlaneBits = `CD_PLANE_BITS;
  localparam logic signed [DiffBits-1:0] HalfPx = DiffBits'(1) <<< (SubpixelBits - 1);

  logic signed [DiffBits-1:0]  edge_a [3];
  logic signed [DiffBits-1:0]  edge_b [3];
  logic signed [EdgeCBits-1:0] edge_c [3];
  for (genvar i = 0; i < 3; i++) begin : gen_edges
    assign edge_a[i] = edge_a_i[DiffBits*i +: DiffBits];
    assign edge_b[i] = edge_b_i[DiffBits*i +: DiffBits];
    assign edge_c[i] = edge_c_i[EdgeCBits*i +: EdgeCBits];
  end

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

  // The operands: the orientation, and each edge's coefficients along it.
  always_comb begin
    x_major_d = '0;
    major_lo_c = '0;
    for (int i = 0; i < 3; i++) edge_fixed[i] = '0;
    for (int i = 0; i < 3; i++) edge_free[i] = '0;
    if (window_i) begin
      // Lines run along the axis in which q changes least.
      x_major_d = (q_coef_x_i < 0 ? -q_coef_x_i : q_coef_x_i) <= (q_coef_y_i < 0 ? -q_coef_y_i : q_coef_y_i);
      major_lo_c = x_major_d ? box_x_lo_i : box_y_lo_i;
      for (int i = 0; i < 3; i++) begin
        edge_fixed[i] = x_major_d ? edge_a[i] : edge_b[i];
        edge_free[i] = x_major_d ? edge_b[i] : edge_a[i];
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
    if (stage_i && HasPlanes) begin
      // A0 |det| + A_x ref_x + A_y ref_y
      q_ref_d = ExactRefQBits'(products_i[AccBits*(`CD_SETUP_Q_REF - FirstResult) +: AccBits]);
      u_ref_d = ExactRefUvBits'(products_i[AccBits*(`CD_SETUP_U_REF - FirstResult) +: AccBits]);
      v_ref_d = ExactRefUvBits'(products_i[AccBits*(`CD_SETUP_V_REF - FirstResult) +: AccBits]);
      peak_length = '0;
      for (int i = 0; i < PeakBits; i++) if (q_peak_i[i]) peak_length = 8'(i + 1);
      shift_d = ShiftBits'($signed({1'b0, peak_length})) - ShiftBits'(PlaneBits);
    end
    if (stage_i) begin
      // g = round(-q_major 2^g_frac / q_minor) = floor((2 N' + D') / (2 D')) with
      // N' = -q_major sign(q_minor) 2^g_frac and D' = |q_minor|.
      q_major = x_major_d ? q_coef_x_i : q_coef_y_i;
      q_minor = x_major_d ? q_coef_y_i : q_coef_x_i;
      g_numerator = ((q_minor < 0 ? (GDivNumBits+1)'(q_major) : -((GDivNumBits+1)'(q_major))) <<< (GFrac + 1)) +
                    (q_minor < 0 ? -((GDivNumBits+1)'(q_minor)) : (GDivNumBits+1)'(q_minor));
      g_div_num = GDivNumBits'(g_numerator < 0 ? -g_numerator : g_numerator);
      g_div_den = GDivDenBits'(q_minor < 0 ? -q_minor : q_minor) << 1;

      // Edge i at the first column: N0 = E - threshold there (model/pixel_coverage.cpp
      // covered_span), divided by |free| 2^sp as (N0 >> sp) / |free|.
      for (int i = 0; i < 3; i++) begin
        edge_free_abs[i] = FreeBits'(edge_free[i] < 0 ? -edge_free[i] : edge_free[i]);
        edge_fixed_abs[i] = FreeBits'(edge_fixed[i] < 0 ? -edge_fixed[i] : edge_fixed[i]);
        // fixed (major_lo 2^sp + half) + free half + c - threshold
        edge_n[i] = EdgeNBits'(products_i[AccBits*(`CD_SETUP_EDGE_N0 + i - FirstResult) +: AccBits]) +
                    EdgeNBits'(edge_free[i]) * EdgeNBits'(HalfPx) + EdgeNBits'(edge_c[i]) -
                    EdgeNBits'($signed({1'b0, edge_threshold_i[i]}));
        edge_n_high[i] = BoundNumBits'(edge_n[i] >>> SubpixelBits);
        edge_n_high_abs[i] = BoundNumBits'(edge_n_high[i] < 0 ? -edge_n_high[i] : edge_n_high[i]);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_i) begin
      q_ref_o <= q_ref_d;
      u_ref_o <= u_ref_d;
      v_ref_o <= v_ref_d;
      x_major_o <= x_major_d;
      shift_o <= shift_d;
      g_zero_o <= q_minor == 0;
      g_negative_o <= g_numerator < 0;
      for (int i = 0; i < 3; i++) edge_fixed_o[DiffBits*i +: DiffBits] <= edge_fixed[i];
      for (int i = 0; i < 3; i++) edge_free_o[DiffBits*i +: DiffBits] <= edge_free[i];
      for (int i = 0; i < 3; i++) edge_n_high_o[BoundNumBits*i +: BoundNumBits] <= edge_n_high[i];
      for (int i = 0; i < 3; i++) edge_n_low_o[SubpixelBits*i +: SubpixelBits] <= edge_n[i][SubpixelBits-1:0];
    end
  end

  assign g_div_num_o = g_div_num;
  assign g_div_den_o = g_div_den;
  for (genvar i = 0; i < 3; i++) begin : gen_divider_operands
    assign edge_n_high_abs_o[BoundNumBits*i +: BoundNumBits] = edge_n_high_abs[i];
    assign edge_free_abs_o[FreeBits*i +: FreeBits] = edge_free_abs[i];
    assign edge_fixed_abs_o[FreeBits*i +: FreeBits] = edge_fixed_abs[i];
  end

  // Each term's operands (model/setup_terms.def), sign-extended.
  always_comb begin
    term_a_o = '0;
    term_b_o = '0;
    if (window_i && HasPlanes) begin
      term_a_o[OperandABits*(`CD_SETUP_TERM_Q_REF + 0 - FirstTerm) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex0_i}));
      term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_REF + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(det_abs_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_Q_REF + 1 - FirstTerm) +: OperandABits] = OperandABits'(q_coef_x_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_REF + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_x_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_Q_REF + 2 - FirstTerm) +: OperandABits] = OperandABits'(q_coef_y_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_REF + 2 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_y_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_U_REF + 0 - FirstTerm) +: OperandABits] = OperandABits'(u_attr0_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_U_REF + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(det_abs_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_U_REF + 1 - FirstTerm) +: OperandABits] = OperandABits'(u_coef_x_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_U_REF + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_x_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_U_REF + 2 - FirstTerm) +: OperandABits] = OperandABits'(u_coef_y_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_U_REF + 2 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_y_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_V_REF + 0 - FirstTerm) +: OperandABits] = OperandABits'(v_attr0_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_V_REF + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(det_abs_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_V_REF + 1 - FirstTerm) +: OperandABits] = OperandABits'(v_coef_x_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_V_REF + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_x_i);
      term_a_o[OperandABits*(`CD_SETUP_TERM_V_REF + 2 - FirstTerm) +: OperandABits] = OperandABits'(v_coef_y_i);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_V_REF + 2 - FirstTerm) +: OperandBBits] = OperandBBits'(ref_y_i);
    end
    for (int i = 0; i < 3; i++) begin
      term_a_o[OperandABits*(`CD_SETUP_TERM_EDGE_N0 + i - FirstTerm) +: OperandABits] = OperandABits'(edge_fixed[i]);
      if (window_i)
        term_b_o[OperandBBits*(`CD_SETUP_TERM_EDGE_N0 + i - FirstTerm) +: OperandBBits] =
            (OperandBBits'($signed({1'b0, major_lo_c})) <<< SubpixelBits) + OperandBBits'(HalfPx);
    end
  end

endmodule

`default_nettype wire
