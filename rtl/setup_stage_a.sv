// Setup engine, stage A (rtl/setup_engine.sv): edge functions with the
// top-left rule, the determinant, the box clipped to the viewport, the
// reference pixel centre, 1/w aligned to the largest exponent and U = u q,
// V = v q at the vertices. Twin of cdsim::setup_stage_a
// (model/setup_engine.cpp).
//
// Its operands are formed in its window (window_i: from its first product
// cycle on the shared multipliers to its own cycle) and are zero outside it;
// it reads its products (results CD_SETUP_DET .. CD_SETUP_V_ATTR2) and
// registers what it forms in its own cycle (stage_i).
`include "cd_widths.svh"
`default_nettype none

module setup_stage_a #(
  parameter bit HasPlanes = 1'b1,
  localparam int CoordBits    = `CD_COORD_BITS,
  localparam int UvBits       = `CD_UV_BITS,
  localparam int DiffBits     = `CD_DIFF_BITS,
  localparam int DetBits      = `CD_DET_BITS,
  localparam int EdgeCBits    = `CD_EDGE_C_BITS,
  localparam int PixelBits    = `CD_PIXEL_BITS,
  localparam int QVertexBits  = `CD_Q_VERTEX_BITS,
  localparam int AttrUvBits   = `CD_ATTR_UV_BITS,
  localparam int AccBits      = `CD_SETUP_ACC_BITS,
  localparam int OperandABits = `CD_SETUP_OPERAND_A_BITS,
  localparam int OperandBBits = `CD_SETUP_OPERAND_B_BITS,
  localparam int FirstResult  = `CD_SETUP_DET,
  localparam int Results      = `CD_SETUP_Q_COEF_X - `CD_SETUP_DET,
  localparam int FirstTerm    = `CD_SETUP_TERM_DET,
  localparam int Terms        = `CD_SETUP_TERM_Q_COEF_X - `CD_SETUP_TERM_DET
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          window_i,
  input  logic                          stage_i,
  // The triangle as loaded: vertex i in bits i*W +: W; q is binary32 1/w.
  input  logic [3*CoordBits-1:0]        x_i,
  input  logic [3*CoordBits-1:0]        y_i,
  input  logic [3*UvBits-1:0]           u_i,
  input  logic [3*UvBits-1:0]           v_i,
  input  logic [95:0]                   qf_i,
  input  logic [13:0]                   viewport_width_i,
  input  logic [13:0]                   viewport_height_i,
  input  logic [Results*AccBits-1:0]    products_i,
  output logic [Terms*OperandABits-1:0] term_a_o,
  output logic [Terms*OperandBBits-1:0] term_b_o,
  // Registered in stage_i; edge i in bits i*W +: W.
  output logic signed [DiffBits-1:0]    dx1_o,
  output logic signed [DiffBits-1:0]    dy1_o,
  output logic signed [DiffBits-1:0]    dx2_o,
  output logic signed [DiffBits-1:0]    dy2_o,
  output logic signed [DetBits-1:0]     det_o,
  output logic [3*DiffBits-1:0]         edge_a_o,
  output logic [3*DiffBits-1:0]         edge_b_o,
  output logic [3*EdgeCBits-1:0]        edge_c_o,
  output logic [2:0]                    edge_threshold_o,
  output logic                          empty_o,
  output logic [PixelBits-1:0]          box_x_lo_o,
  output logic [PixelBits-1:0]          box_x_hi_o,
  output logic [PixelBits-1:0]          box_y_lo_o,
  output logic [PixelBits-1:0]          box_y_hi_o,
  output logic signed [DiffBits-1:0]    ref_x_o,
  output logic signed [DiffBits-1:0]    ref_y_o,
  output logic [3*QVertexBits-1:0]      q_vertex_o,
  output logic [3*AttrUvBits-1:0]       u_attr_o,
  output logic [3*AttrUvBits-1:0]       v_attr_o,
  output logic                          depth_range_o
);

  localparam int SubpixelBits = `CD_SUBPIXEL_BITS;
  localparam int QBits        = `CD_Q_BITS;

  logic signed [CoordBits-1:0] x_q [3];
  logic signed [CoordBits-1:0] y_q [3];
  logic signed [UvBits-1:0]    u_q [3];
  logic signed [UvBits-1:0]    v_q [3];
  logic [31:0]                 qf_q [3];
  for (genvar i = 0; i < 3; i++) begin : gen_vertices
    assign x_q[i] = x_i[CoordBits*i +: CoordBits];
    assign y_q[i] = y_i[CoordBits*i +: CoordBits];
    assign u_q[i] = u_i[UvBits*i +: UvBits];
    assign v_q[i] = v_i[UvBits*i +: UvBits];
    assign qf_q[i] = qf_i[32*i +: 32];
  end

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

  // The operands: vertex differences, edge vectors and the vertices' q.
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
    if (window_i) begin
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
    if (stage_i) begin
      det = DetBits'(products_i[AccBits*(`CD_SETUP_DET - FirstResult) +: AccBits]);  // dx1 dy2 - dx2 dy1
      for (int i = 0; i < 3; i++) begin
        edge_a_d[i] = det < 0 ? edge_dy[i] : -edge_dy[i];
        edge_b_d[i] = det < 0 ? -edge_dx[i] : edge_dx[i];
        // dy x(i+1) - dx y(i+1)
        edge_c_d[i] = EdgeCBits'(products_i[AccBits*(`CD_SETUP_EDGE_C0 + i - FirstResult) +: AccBits]);
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
      if (x_hi > (CoordBits+1)'($signed({1'b0, viewport_width_i})) - (CoordBits+1)'(1))
        x_hi = (CoordBits+1)'($signed({1'b0, viewport_width_i})) - (CoordBits+1)'(1);
      if (y_hi > (CoordBits+1)'($signed({1'b0, viewport_height_i})) - (CoordBits+1)'(1))
        y_hi = (CoordBits+1)'($signed({1'b0, viewport_height_i})) - (CoordBits+1)'(1);
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
          u_attr_d[i] = AttrUvBits'(products_i[AccBits*(`CD_SETUP_U_ATTR0 + i - FirstResult) +: AccBits]);  // q u
          v_attr_d[i] = AttrUvBits'(products_i[AccBits*(`CD_SETUP_V_ATTR0 + i - FirstResult) +: AccBits]);  // q v
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
    if (stage_i) begin
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
    end else if (stage_i) begin
      empty_q <= empty_d;
      depth_range_q <= depth_range_d;
    end
  end

  // Each term's operands (model/setup_terms.def), sign-extended.
  always_comb begin
    term_a_o = '0;
    term_b_o = '0;
    term_a_o[OperandABits*(`CD_SETUP_TERM_DET + 0 - FirstTerm) +: OperandABits] = OperandABits'(dx1);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_DET + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(dy2);
    term_a_o[OperandABits*(`CD_SETUP_TERM_DET + 1 - FirstTerm) +: OperandABits] = OperandABits'(dx2);
    term_b_o[OperandBBits*(`CD_SETUP_TERM_DET + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(dy1);
    for (int i = 0; i < 3; i++) begin
      term_a_o[OperandABits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 0 - FirstTerm) +: OperandABits] = OperandABits'(edge_dy[i]);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 0 - FirstTerm) +: OperandBBits] = OperandBBits'(x_q[(i + 1) % 3]);
      term_a_o[OperandABits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 1 - FirstTerm) +: OperandABits] = OperandABits'(edge_dx[i]);
      term_b_o[OperandBBits*(`CD_SETUP_TERM_EDGE_C0 + 2*i + 1 - FirstTerm) +: OperandBBits] = OperandBBits'(y_q[(i + 1) % 3]);
      term_a_o[OperandABits*(`CD_SETUP_TERM_U_ATTR0 + i - FirstTerm) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_d[i]}));
      term_b_o[OperandBBits*(`CD_SETUP_TERM_U_ATTR0 + i - FirstTerm) +: OperandBBits] = OperandBBits'(u_q[i]);
      term_a_o[OperandABits*(`CD_SETUP_TERM_V_ATTR0 + i - FirstTerm) +: OperandABits] = OperandABits'($signed({1'b0, q_vertex_d[i]}));
      term_b_o[OperandBBits*(`CD_SETUP_TERM_V_ATTR0 + i - FirstTerm) +: OperandBBits] = OperandBBits'(v_q[i]);
    end
  end

  assign dx1_o = dx1_q;
  assign dy1_o = dy1_q;
  assign dx2_o = dx2_q;
  assign dy2_o = dy2_q;
  assign det_o = det_q;
  assign edge_threshold_o = edge_threshold_q;
  assign empty_o = empty_q;
  assign box_x_lo_o = box_x_lo_q;
  assign box_x_hi_o = box_x_hi_q;
  assign box_y_lo_o = box_y_lo_q;
  assign box_y_hi_o = box_y_hi_q;
  assign ref_x_o = ref_x_q;
  assign ref_y_o = ref_y_q;
  assign depth_range_o = depth_range_q;
  for (genvar i = 0; i < 3; i++) begin : gen_outputs
    assign edge_a_o[DiffBits*i +: DiffBits] = edge_a_q[i];
    assign edge_b_o[DiffBits*i +: DiffBits] = edge_b_q[i];
    assign edge_c_o[EdgeCBits*i +: EdgeCBits] = edge_c_q[i];
    assign q_vertex_o[QVertexBits*i +: QVertexBits] = q_vertex_q[i];
    assign u_attr_o[AttrUvBits*i +: AttrUvBits] = u_attr_q[i];
    assign v_attr_o[AttrUvBits*i +: AttrUvBits] = v_attr_q[i];
  end

endmodule

`default_nettype wire
