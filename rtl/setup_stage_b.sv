// Setup engine, stage B (rtl/setup_engine.sv): the plane coefficients of q,
// U and V, signed so that q |det| > 0, A_x = s (dA1 dy2 - dA2 dy1) and
// A_y = s (dA2 dx1 - dA1 dx2) per subpixel, and the largest q |det|, which
// sets the shared shift. Twin of cdsim::setup_stage_b (model/setup_engine.cpp).
// Window, stage and products as in setup_stage_a.sv (results
// CD_SETUP_Q_COEF_X .. CD_SETUP_PEAK2).
`include "cd_widths.svh"
`default_nettype none

module setup_stage_b #(
  parameter bit HasPlanes = 1'b1,
  localparam int DiffBits     = `CD_DIFF_BITS,
  localparam int DetBits      = `CD_DET_BITS,
  localparam int QVertexBits  = `CD_Q_VERTEX_BITS,
  localparam int AttrQBits    = `CD_ATTR_Q_BITS,
  localparam int AttrUvBits   = `CD_ATTR_UV_BITS,
  localparam int CoefQBits    = `CD_COEF_Q_BITS,
  localparam int CoefUvBits   = `CD_COEF_UV_BITS,
  localparam int PeakBits     = `CD_PEAK_BITS,
  localparam int AccBits      = `CD_SETUP_ACC_BITS,
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS,
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS,
  localparam int FirstResult  = `CD_SETUP_Q_COEF_X,
  localparam int Results      = `CD_SETUP_Q_REF - `CD_SETUP_Q_COEF_X,
  localparam int FirstTerm    = `CD_SETUP_TERM_Q_COEF_X,
  localparam int Terms        = `CD_SETUP_TERM_Q_REF - `CD_SETUP_TERM_Q_COEF_X
) (
  input  logic                          clk_i,
  input  logic                          window_i,
  input  logic                          stage_i,
  // Stage A's registers.
  input  logic signed [DiffBits-1:0]    dx1_i,
  input  logic signed [DiffBits-1:0]    dy1_i,
  input  logic signed [DiffBits-1:0]    dx2_i,
  input  logic signed [DiffBits-1:0]    dy2_i,
  input  logic signed [DetBits-1:0]     det_i,
  input  logic [3*QVertexBits-1:0]      q_vertex_i,
  input  logic [3*AttrUvBits-1:0]       u_attr_i,
  input  logic [3*AttrUvBits-1:0]       v_attr_i,
  input  logic [Results*AccBits-1:0]    products_i,
  output logic [Terms*OperandABits-1:0] term_a_o,
  output logic [Terms*OperandBBits-1:0] term_b_o,
  // Registered in stage_i.
  output logic signed [CoefQBits-1:0]   q_coef_x_o,
  output logic signed [CoefQBits-1:0]   q_coef_y_o,
  output logic signed [CoefUvBits-1:0]  u_coef_x_o,
  output logic signed [CoefUvBits-1:0]  u_coef_y_o,
  output logic signed [CoefUvBits-1:0]  v_coef_x_o,
  output logic signed [CoefUvBits-1:0]  v_coef_y_o,
  output logic [PeakBits-1:0]           q_peak_o,
  output logic [PeakBits-1:0]           q_floor_o,   // the smallest q |det|: the far vertex's
  output logic signed [DetBits-1:0]     det_abs_o
);

  logic [QVertexBits-1:0]       q_vertex [3];
  logic signed [AttrUvBits-1:0] u_attr [3];
  logic signed [AttrUvBits-1:0] v_attr [3];
  for (genvar i = 0; i < 3; i++) begin : gen_vertices
    assign q_vertex[i] = q_vertex_i[QVertexBits*i +: QVertexBits];
    assign u_attr[i] = u_attr_i[AttrUvBits*i +: AttrUvBits];
    assign v_attr[i] = v_attr_i[AttrUvBits*i +: AttrUvBits];
  end

  logic signed [DetBits-1:0]    det_abs;
  logic signed [AttrQBits:0]    dq1, dq2;
  logic signed [AttrUvBits:0]   du1, du2, dv1, dv2;
  logic signed [CoefQBits-1:0]  q_coef_x_d, q_coef_y_d;
  logic signed [CoefUvBits-1:0] u_coef_x_d, u_coef_y_d, v_coef_x_d, v_coef_y_d;
  logic [PeakBits-1:0]          peak_candidate [3];
  logic [PeakBits-1:0]          q_peak_d, q_floor_d;

  // The operands: differences of q, U and V, and |det|.
  always_comb begin
    det_abs = '0;
    dq1 = '0;
    dq2 = '0;
    du1 = '0;
    du2 = '0;
    dv1 = '0;
    dv2 = '0;
    if (window_i) begin
      det_abs = det_i < 0 ? -det_i : det_i;
      dq1 = (AttrQBits+1)'($signed({1'b0, q_vertex[1]})) - (AttrQBits+1)'($signed({1'b0, q_vertex[0]}));
      dq2 = (AttrQBits+1)'($signed({1'b0, q_vertex[2]})) - (AttrQBits+1)'($signed({1'b0, q_vertex[0]}));
    end
    if (window_i && HasPlanes) begin
      du1 = (AttrUvBits+1)'(u_attr[1]) - (AttrUvBits+1)'(u_attr[0]);
      du2 = (AttrUvBits+1)'(u_attr[2]) - (AttrUvBits+1)'(u_attr[0]);
      dv1 = (AttrUvBits+1)'(v_attr[1]) - (AttrUvBits+1)'(v_attr[0]);
      dv2 = (AttrUvBits+1)'(v_attr[2]) - (AttrUvBits+1)'(v_attr[0]);
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
    q_floor_d = '0;
    for (int i = 0; i < 3; i++) peak_candidate[i] = '0;
    if (stage_i) begin
      q_coef_x_d = CoefQBits'(products_i[AccBits*(`CD_SETUP_Q_COEF_X - FirstResult) +: AccBits]);  // dq1 dy2 - dq2 dy1
      q_coef_y_d = CoefQBits'(products_i[AccBits*(`CD_SETUP_Q_COEF_Y - FirstResult) +: AccBits]);  // dq2 dx1 - dq1 dx2
      if (det_i < 0) begin
        q_coef_x_d = -q_coef_x_d;
        q_coef_y_d = -q_coef_y_d;
      end
    end
    if (stage_i && HasPlanes) begin
      u_coef_x_d = CoefUvBits'(products_i[AccBits*(`CD_SETUP_U_COEF_X - FirstResult) +: AccBits]);
      u_coef_y_d = CoefUvBits'(products_i[AccBits*(`CD_SETUP_U_COEF_Y - FirstResult) +: AccBits]);
      v_coef_x_d = CoefUvBits'(products_i[AccBits*(`CD_SETUP_V_COEF_X - FirstResult) +: AccBits]);
      v_coef_y_d = CoefUvBits'(products_i[AccBits*(`CD_SETUP_V_COEF_Y - FirstResult) +: AccBits]);
      if (det_i < 0) begin
        u_coef_x_d = -u_coef_x_d;
        u_coef_y_d = -u_coef_y_d;
        v_coef_x_d = -v_coef_x_d;
        v_coef_y_d = -v_coef_y_d;
      end
      // The largest q |det| sets the shared shift.
      q_peak_d = '0;
      for (int i = 0; i < 3; i++) begin
        peak_candidate[i] = PeakBits'(products_i[AccBits*(`CD_SETUP_PEAK0 + i - FirstResult) +: AccBits]);  // q |det|
        if (peak_candidate[i] > q_peak_d) q_peak_d = peak_candidate[i];
        if (i == 0 || peak_candidate[i] < q_floor_d) q_floor_d = peak_candidate[i];
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_i) begin
      q_coef_x_o <= q_coef_x_d;
      q_coef_y_o <= q_coef_y_d;
      u_coef_x_o <= u_coef_x_d;
      u_coef_y_o <= u_coef_y_d;
      v_coef_x_o <= v_coef_x_d;
      v_coef_y_o <= v_coef_y_d;
      q_peak_o <= q_peak_d;
      q_floor_o <= q_floor_d;
      det_abs_o <= det_abs;
    end
  end

  // Each term's operands (model/setup_terms.def), sign-extended.
  always_comb begin
    term_a_o = '0;
    term_b_o = '0;
    term_a_o[OperandABits*(`CD_SETUP_TERM_Q_COEF_X + 0 - FirstTerm) +: OperandABits] = OperandABits'(dq1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_COEF_X + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dy2_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_Q_COEF_X + 1 - FirstTerm) +: OperandABits] = OperandABits'(dq2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_COEF_X + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dy1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_Q_COEF_Y + 0 - FirstTerm) +: OperandABits] = OperandABits'(dq2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_COEF_Y + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dx1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_Q_COEF_Y + 1 - FirstTerm) +: OperandABits] = OperandABits'(dq1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_Q_COEF_Y + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dx2_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_U_COEF_X + 0 - FirstTerm) +: OperandABits] = OperandABits'(du1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_U_COEF_X + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dy2_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_U_COEF_X + 1 - FirstTerm) +: OperandABits] = OperandABits'(du2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_U_COEF_X + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dy1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_U_COEF_Y + 0 - FirstTerm) +: OperandABits] = OperandABits'(du2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_U_COEF_Y + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dx1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_U_COEF_Y + 1 - FirstTerm) +: OperandABits] = OperandABits'(du1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_U_COEF_Y + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dx2_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_V_COEF_X + 0 - FirstTerm) +: OperandABits] = OperandABits'(dv1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_V_COEF_X + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dy2_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_V_COEF_X + 1 - FirstTerm) +: OperandABits] = OperandABits'(dv2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_V_COEF_X + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dy1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_V_COEF_Y + 0 - FirstTerm) +: OperandABits] = OperandABits'(dv2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_V_COEF_Y + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dx1_i);
    term_a_o[OperandABits*(`CD_SETUP_TERM_V_COEF_Y + 1 - FirstTerm) +: OperandABits] = OperandABits'(dv1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_V_COEF_Y + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dx2_i);
    for (int i = 0; i < 3; i++) begin
      if (window_i && HasPlanes) begin
        term_a_o[OperandABits*(`CD_SETUP_TERM_PEAK0 + i - FirstTerm) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex[i]}));
        term_b_o[OperandBBits*(`CD_SETUP_TERM_PEAK0 + i - FirstTerm) +: OperandBBits] = OperandBBits'(det_abs);
      end
    end
  end

endmodule

`default_nettype wire
