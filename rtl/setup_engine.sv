// Setup engine: plane equations, orientation, slope g, per-triangle
// normalisation, line range (two setup stages), and the per-line table fill
// (one reciprocal and four multiplies per line, RecipLatency cycles deep).
// Twin of model/setup_engine.cpp; every value follows its integer arithmetic
// exactly. The arithmetic is behavioural (exact 128-bit products, a divider
// for g and for the reciprocal); only the cycle at which each result appears
// is architectural. Heavy logic sits behind its stage enable, which also keeps
// the Verilated model fast: it is evaluated only in the cycle that uses it.
`include "cd_widths.svh"

module setup_engine #(
  parameter int SubpixelBits = `CD_SUBPIXEL_BITS,
  parameter int UvInFrac     = `CD_UV_IN_FRAC,
  parameter int QBits        = `CD_Q_BITS,
  parameter int PlaneBits    = `CD_PLANE_BITS,
  parameter int GFrac        = `CD_G_FRAC,
  parameter int RecipBits    = `CD_RECIP_BITS,
  parameter int TInt         = `CD_T_INT,
  parameter int TFrac        = `CD_T_FRAC,
  parameter int SInt         = `CD_S_INT,
  parameter int SFrac        = `CD_S_FRAC,
  parameter int TableDepth   = `CD_TABLE_DEPTH,
  parameter int RecipLatency = `CD_RECIP_LATENCY,
  localparam int TBits       = TInt + TFrac,
  localparam int SBits       = SInt + SFrac,
  localparam int WordBits    = 2 * TBits + 2 * SBits + 2,
  localparam int AddrBits    = $clog2(TableDepth)
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  // Triangle, captured on load_i (x, y, u, v signed; q is binary32 1/w).
  input  logic                      load_i,
  input  logic [95:0]               tri_x_i,
  input  logic [95:0]               tri_y_i,
  input  logic [95:0]               tri_q_i,
  input  logic [95:0]               tri_u_i,
  input  logic [95:0]               tri_v_i,
  input  logic [15:0]               viewport_width_i,
  input  logic [15:0]               viewport_height_i,
  input  logic [1:0]                density_log2_i,
  // Setup stages: stage 0 (planes, orientation, g, shift), then stage 1
  // (normalisation, line range). Results are valid from the cycle after stage 1.
  input  logic                      stage0_i,
  input  logic                      stage1_i,
  output logic                      empty_o,
  output logic                      x_major_o,
  output logic signed [63:0]        g_o,
  output logic [31:0]               major_lo_o,
  output logic [31:0]               major_count_o,
  output logic [31:0]               minor_lo_o,
  output logic [31:0]               minor_hi_o,
  output logic signed [63:0]        pixel_line_lo_o,
  output logic signed [63:0]        pixel_line_hi_o,
  output logic [191:0]              edge_a_o,
  output logic [191:0]              edge_b_o,
  output logic [191:0]              edge_c_o,
  output logic [2:0]                edge_threshold_o,
  output logic [7:0]                flags_o,
  // Table fill: line fill_line_i enters the reciprocal pipeline and leaves as a
  // table write to fill_addr_i RecipLatency cycles later.
  input  logic                      fill_valid_i,
  input  logic signed [63:0]        fill_line_i,
  input  logic [AddrBits-1:0]       fill_addr_i,
  output logic                      write_valid_o,
  output logic [AddrBits-1:0]       write_addr_o,
  output logic [WordBits-1:0]       write_entry_o
);

  `include "cd_arith.svh"

  localparam int W = 128;
  localparam logic [7:0] FlagDepthRange     = 8'h04;

  function automatic logic signed [127:0] sext32(input logic [31:0] x);
    sext32 = $signed({{96{x[31]}}, x});
  endfunction

  function automatic logic signed [127:0] sext64(input logic [63:0] x);
    sext64 = $signed({{64{x[63]}}, x});
  endfunction

  function automatic logic signed [127:0] abs_wide(input logic signed [127:0] x);
    abs_wide = x < 128'sd0 ? -x : x;
  endfunction

  // ---------------------------------------------------------------- triangle
  logic [95:0] tri_x_q, tri_y_q, tri_q_q, tri_u_q, tri_v_q;
  logic [15:0] viewport_width_q, viewport_height_q;
  logic [1:0]  density_log2_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tri_x_q <= '0;
      tri_y_q <= '0;
      tri_q_q <= '0;
      tri_u_q <= '0;
      tri_v_q <= '0;
      viewport_width_q <= '0;
      viewport_height_q <= '0;
      density_log2_q <= '0;
    end else if (load_i) begin
      tri_x_q <= tri_x_i;
      tri_y_q <= tri_y_i;
      tri_q_q <= tri_q_i;
      tri_u_q <= tri_u_i;
      tri_v_q <= tri_v_i;
      viewport_width_q <= viewport_width_i;
      viewport_height_q <= viewport_height_i;
      density_log2_q <= density_log2_i;
    end
  end

  // ---------------------------------------------------------------- stage 0
  // Registered results of stage 0.
  logic                empty_d, empty_q;
  logic                x_major_d, x_major_q;
  logic signed [63:0]  g_d, g_q;
  logic signed [31:0]  shift_d, shift_q;
  logic [7:0]          flags_d, flags_q;
  logic [31:0]         box_x_lo_d, box_x_lo_q, box_x_hi_d, box_x_hi_q;
  logic [31:0]         box_y_lo_d, box_y_lo_q, box_y_hi_d, box_y_hi_q;
  logic signed [W-1:0] ref_x_d, ref_x_q, ref_y_d, ref_y_q;
  // Exact planes scaled by det: at the reference centre, per pixel in x and y.
  logic signed [W-1:0] q_ref_d, q_ref_q, q_px_d, q_px_q, q_py_d, q_py_q;
  logic signed [W-1:0] u_ref_d, u_ref_q, u_px_d, u_px_q, u_py_d, u_py_q;
  logic signed [W-1:0] v_ref_d, v_ref_q, v_px_d, v_px_q, v_py_d, v_py_q;
  logic [191:0]        edge_a_d, edge_a_q, edge_b_d, edge_b_q, edge_c_d, edge_c_q;
  logic [2:0]          edge_threshold_d, edge_threshold_q;

  // Stage 0 temporaries.
  logic signed [W-1:0] vx [3];
  logic signed [W-1:0] vy [3];
  logic signed [W-1:0] qn [3];
  logic signed [W-1:0] uq [3];
  logic signed [W-1:0] vq [3];
  logic [7:0]          exponent [3];
  logic [7:0]          max_exponent;
  logic signed [W-1:0] dx1, dy1, dx2, dy2, det, det_sign, det_abs;
  logic signed [W-1:0] edge_dx, edge_dy, edge_a, edge_b;
  logic signed [W-1:0] min_x, max_x, min_y, max_y, x_lo, x_hi, y_lo, y_hi;
  logic signed [W-1:0] q_peak, q_major, q_minor, g_num, g_den;
  logic signed [W-1:0] one_px, half_px;

  always_comb begin
    empty_d = empty_q;
    x_major_d = x_major_q;
    g_d = g_q;
    shift_d = shift_q;
    flags_d = flags_q;
    box_x_lo_d = box_x_lo_q;
    box_x_hi_d = box_x_hi_q;
    box_y_lo_d = box_y_lo_q;
    box_y_hi_d = box_y_hi_q;
    ref_x_d = ref_x_q;
    ref_y_d = ref_y_q;
    q_ref_d = q_ref_q;
    q_px_d = q_px_q;
    q_py_d = q_py_q;
    u_ref_d = u_ref_q;
    u_px_d = u_px_q;
    u_py_d = u_py_q;
    v_ref_d = v_ref_q;
    v_px_d = v_px_q;
    v_py_d = v_py_q;
    edge_a_d = edge_a_q;
    edge_b_d = edge_b_q;
    edge_c_d = edge_c_q;
    edge_threshold_d = edge_threshold_q;
    for (int i = 0; i < 3; i++) begin
      vx[i] = '0;
      vy[i] = '0;
      qn[i] = '0;
      uq[i] = '0;
      vq[i] = '0;
      exponent[i] = '0;
    end
    {max_exponent, dx1, dy1, dx2, dy2, det, det_sign, det_abs} = '0;
    {edge_dx, edge_dy, edge_a, edge_b} = '0;
    {min_x, max_x, min_y, max_y, x_lo, x_hi, y_lo, y_hi} = '0;
    {q_peak, q_major, q_minor, g_num, g_den, one_px, half_px} = '0;

    if (stage0_i) begin
      one_px = 128'sd1 <<< SubpixelBits;
      half_px = 128'sd1 <<< (SubpixelBits - 1);
      for (int i = 0; i < 3; i++) begin
        vx[i] = sext32(tri_x_q[32*i +: 32]);
        vy[i] = sext32(tri_y_q[32*i +: 32]);
      end
      // Edge functions and the top-left rule (model/coverage.cpp make_edges).
      dx1 = vx[1] - vx[0];
      dy1 = vy[1] - vy[0];
      dx2 = vx[2] - vx[0];
      dy2 = vy[2] - vy[0];
      det = dx1 * dy2 - dx2 * dy1;
      det_sign = det < 0 ? -128'sd1 : 128'sd1;
      det_abs = abs_wide(det);
      for (int i = 0; i < 3; i++) begin
        edge_dx = vx[(i + 2) % 3] - vx[(i + 1) % 3];
        edge_dy = vy[(i + 2) % 3] - vy[(i + 1) % 3];
        edge_a = -edge_dy * det_sign;
        edge_b = edge_dx * det_sign;
        edge_a_d[64*i +: 64] = edge_a[63:0];
        edge_b_d[64*i +: 64] = edge_b[63:0];
        edge_c_d[64*i +: 64] =
            64'((edge_dy * vx[(i + 1) % 3] - edge_dx * vy[(i + 1) % 3]) * det_sign);
        edge_threshold_d[i] = !((edge_a == 0 && edge_b > 0) || edge_a > 0);
      end
      // Bounding box of the pixel centres, clipped to the viewport.
      min_x = vx[0];
      max_x = vx[0];
      min_y = vy[0];
      max_y = vy[0];
      for (int i = 1; i < 3; i++) begin
        if (vx[i] < min_x) min_x = vx[i];
        if (vx[i] > max_x) max_x = vx[i];
        if (vy[i] < min_y) min_y = vy[i];
        if (vy[i] > max_y) max_y = vy[i];
      end
      x_lo = -cd_floor_div(half_px - min_x, one_px);
      x_hi = cd_floor_div(max_x - half_px, one_px);
      y_lo = -cd_floor_div(half_px - min_y, one_px);
      y_hi = cd_floor_div(max_y - half_px, one_px);
      if (x_lo < 0) x_lo = '0;
      if (y_lo < 0) y_lo = '0;
      if (x_hi > $signed({112'd0, viewport_width_q}) - 1) x_hi = $signed({112'd0, viewport_width_q}) - 1;
      if (y_hi > $signed({112'd0, viewport_height_q}) - 1) y_hi = $signed({112'd0, viewport_height_q}) - 1;
      box_x_lo_d = x_lo[31:0];
      box_x_hi_d = x_hi[31:0];
      box_y_lo_d = y_lo[31:0];
      box_y_hi_d = y_hi[31:0];
      empty_d = det == 0 || x_lo > x_hi || y_lo > y_hi;

      // Normalise 1/w to the largest exponent; U = u q, V = v q exactly.
      max_exponent = '0;
      for (int i = 0; i < 3; i++) begin
        exponent[i] = tri_q_q[32*i + 23 +: 8];
        if (exponent[i] > max_exponent) max_exponent = exponent[i];
      end
      flags_d = '0;
      for (int i = 0; i < 3; i++) begin
        qn[i] = cd_shift_round($signed({104'd0, 1'b1, tri_q_q[32*i +: 23]}),
                               $signed({24'd0, max_exponent - exponent[i]}) + 32'sd24 - 32'(QBits), 1'b1);
        if (qn[i] == 0 && !empty_d) flags_d = flags_d | FlagDepthRange;
        uq[i] = qn[i] * sext32(tri_u_q[32*i +: 32]);
        vq[i] = qn[i] * sext32(tri_v_q[32*i +: 32]);
      end

      // Plane equations scaled by det, signed so that q |det| > 0.
      ref_x_d = (sext32(box_x_lo_d) <<< SubpixelBits) + half_px - vx[0];
      ref_y_d = (sext32(box_y_lo_d) <<< SubpixelBits) + half_px - vy[0];
      q_px_d = det_sign * ((qn[1] - qn[0]) * dy2 - (qn[2] - qn[0]) * dy1);
      q_py_d = det_sign * ((qn[2] - qn[0]) * dx1 - (qn[1] - qn[0]) * dx2);
      q_ref_d = det_sign * qn[0] * det + q_px_d * ref_x_d + q_py_d * ref_y_d;
      u_px_d = det_sign * ((uq[1] - uq[0]) * dy2 - (uq[2] - uq[0]) * dy1);
      u_py_d = det_sign * ((uq[2] - uq[0]) * dx1 - (uq[1] - uq[0]) * dx2);
      u_ref_d = det_sign * uq[0] * det + u_px_d * ref_x_d + u_py_d * ref_y_d;
      v_px_d = det_sign * ((vq[1] - vq[0]) * dy2 - (vq[2] - vq[0]) * dy1);
      v_py_d = det_sign * ((vq[2] - vq[0]) * dx1 - (vq[1] - vq[0]) * dx2);
      v_ref_d = det_sign * vq[0] * det + v_px_d * ref_x_d + v_py_d * ref_y_d;
      q_px_d = q_px_d <<< SubpixelBits;
      q_py_d = q_py_d <<< SubpixelBits;
      u_px_d = u_px_d <<< SubpixelBits;
      u_py_d = u_py_d <<< SubpixelBits;
      v_px_d = v_px_d <<< SubpixelBits;
      v_py_d = v_py_d <<< SubpixelBits;

      // Orientation: lines run along the axis in which q changes least.
      x_major_d = abs_wide(q_px_d) <= abs_wide(q_py_d);
      q_major = x_major_d ? q_px_d : q_py_d;
      q_minor = x_major_d ? q_py_d : q_px_d;
      // g = round(-q_major 2^g_frac / q_minor), ties toward +inf.
      g_num = -q_major <<< GFrac;
      g_den = q_minor;
      if (g_den < 0) begin
        g_num = -g_num;
        g_den = -g_den;
      end
      g_d = q_minor == 0 ? 64'sd0 : 64'(cd_floor_div(2 * g_num + g_den, 2 * g_den));

      // Shared shift: after it, q |det| fits plane_bits.
      q_peak = '0;
      for (int i = 0; i < 3; i++) begin
        if (qn[i] * det_abs > q_peak) q_peak = qn[i] * det_abs;
      end
      shift_d = $signed({24'd0, cd_bit_length(q_peak)}) - 32'(PlaneBits);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      empty_q <= 1'b1;
      x_major_q <= 1'b1;
      g_q <= '0;
      shift_q <= '0;
      flags_q <= '0;
      box_x_lo_q <= '0;
      box_x_hi_q <= '0;
      box_y_lo_q <= '0;
      box_y_hi_q <= '0;
      ref_x_q <= '0;
      ref_y_q <= '0;
      q_ref_q <= '0;
      q_px_q <= '0;
      q_py_q <= '0;
      u_ref_q <= '0;
      u_px_q <= '0;
      u_py_q <= '0;
      v_ref_q <= '0;
      v_px_q <= '0;
      v_py_q <= '0;
      edge_a_q <= '0;
      edge_b_q <= '0;
      edge_c_q <= '0;
      edge_threshold_q <= '0;
    end else begin
      empty_q <= empty_d;
      x_major_q <= x_major_d;
      g_q <= g_d;
      shift_q <= shift_d;
      flags_q <= flags_d;
      box_x_lo_q <= box_x_lo_d;
      box_x_hi_q <= box_x_hi_d;
      box_y_lo_q <= box_y_lo_d;
      box_y_hi_q <= box_y_hi_d;
      ref_x_q <= ref_x_d;
      ref_y_q <= ref_y_d;
      q_ref_q <= q_ref_d;
      q_px_q <= q_px_d;
      q_py_q <= q_py_d;
      u_ref_q <= u_ref_d;
      u_px_q <= u_px_d;
      u_py_q <= u_py_d;
      v_ref_q <= v_ref_d;
      v_px_q <= v_px_d;
      v_py_q <= v_py_d;
      edge_a_q <= edge_a_d;
      edge_b_q <= edge_b_d;
      edge_c_q <= edge_c_d;
      edge_threshold_q <= edge_threshold_d;
    end
  end

  // ---------------------------------------------------------------- stage 1
  // Normalised planes for the fill, walk geometry and the line range.
  logic signed [W-1:0] q_at_ref_d, q_at_ref_q, q_per_line_d, q_per_line_q;
  logic signed [W-1:0] u_at_ref_d, u_at_ref_q, u_per_line_d, u_per_line_q;
  logic signed [W-1:0] v_at_ref_d, v_at_ref_q, v_per_line_d, v_per_line_q;
  logic signed [W-1:0] step_u_d, step_u_q, step_v_d, step_v_q;
  logic [31:0]         major_lo_d, major_lo_q, major_count_d, major_count_q;
  logic [31:0]         minor_lo_d, minor_lo_q, minor_hi_d, minor_hi_q;
  logic signed [63:0]  line_lo_d, line_lo_q, line_hi_d, line_hi_q;

  logic signed [W-1:0] u_major, u_minor, v_major, v_minor, q_minor1;
  logic signed [W-1:0] ref_major, ref_minor, vertex_major, vertex_minor, kappa;
  logic signed [W-1:0] kappa_lo, kappa_hi, kappa_scale, line_lo, line_hi, round_last;
  logic signed [W-1:0] minor_extent;
  logic signed [31:0]  line_shift;

  always_comb begin
    q_at_ref_d = q_at_ref_q;
    q_per_line_d = q_per_line_q;
    u_at_ref_d = u_at_ref_q;
    u_per_line_d = u_per_line_q;
    v_at_ref_d = v_at_ref_q;
    v_per_line_d = v_per_line_q;
    step_u_d = step_u_q;
    step_v_d = step_v_q;
    major_lo_d = major_lo_q;
    major_count_d = major_count_q;
    minor_lo_d = minor_lo_q;
    minor_hi_d = minor_hi_q;
    line_lo_d = line_lo_q;
    line_hi_d = line_hi_q;
    {u_major, u_minor, v_major, v_minor, q_minor1} = '0;
    {ref_major, ref_minor, vertex_major, vertex_minor, kappa} = '0;
    {kappa_lo, kappa_hi, kappa_scale, line_lo, line_hi, round_last} = '0;
    minor_extent = '0;
    line_shift = '0;

    if (stage1_i) begin
      line_shift = {30'd0, density_log2_q};
      q_minor1 = x_major_q ? q_py_q : q_px_q;
      u_major = x_major_q ? u_px_q : u_py_q;
      u_minor = x_major_q ? u_py_q : u_px_q;
      v_major = x_major_q ? v_px_q : v_py_q;
      v_minor = x_major_q ? v_py_q : v_px_q;
      q_at_ref_d = cd_shift_round(q_ref_q, shift_q, 1'b1);
      u_at_ref_d = cd_shift_round(u_ref_q, shift_q, 1'b1);
      v_at_ref_d = cd_shift_round(v_ref_q, shift_q, 1'b1);
      q_per_line_d = cd_shift_round(q_minor1, shift_q + line_shift, 1'b1);
      u_per_line_d = cd_shift_round(u_minor, shift_q + line_shift, 1'b1);
      v_per_line_d = cd_shift_round(v_minor, shift_q + line_shift, 1'b1);
      step_u_d = cd_shift_round((u_major <<< GFrac) + sext64(g_q) * u_minor,
                                shift_q + 32'(GFrac), 1'b1);
      step_v_d = cd_shift_round((v_major <<< GFrac) + sext64(g_q) * v_minor,
                                shift_q + 32'(GFrac), 1'b1);

      major_lo_d = x_major_q ? box_x_lo_q : box_y_lo_q;
      major_count_d = x_major_q ? box_x_hi_q - box_x_lo_q + 1 : box_y_hi_q - box_y_lo_q + 1;
      minor_lo_d = x_major_q ? box_y_lo_q : box_x_lo_q;
      minor_hi_d = x_major_q ? box_y_hi_q : box_x_hi_q;

      // kappa = density ((minor - minor_ref) - g (major - major_ref)) at each
      // vertex, in 2^-(subpixel_bits + g_frac) units.
      ref_major = x_major_q ? ref_x_q : ref_y_q;
      ref_minor = x_major_q ? ref_y_q : ref_x_q;
      for (int i = 0; i < 3; i++) begin
        vertex_major = (x_major_q ? sext32(tri_x_q[32*i +: 32]) - sext32(tri_x_q[31:0])
                                  : sext32(tri_y_q[32*i +: 32]) - sext32(tri_y_q[31:0])) - ref_major;
        vertex_minor = (x_major_q ? sext32(tri_y_q[32*i +: 32]) - sext32(tri_y_q[31:0])
                                  : sext32(tri_x_q[32*i +: 32]) - sext32(tri_x_q[31:0])) - ref_minor;
        kappa = ((vertex_minor <<< GFrac) - sext64(g_q) * vertex_major) <<< density_log2_q;
        if (i == 0 || kappa < kappa_lo) kappa_lo = kappa;
        if (i == 0 || kappa > kappa_hi) kappa_hi = kappa;
      end
      kappa_scale = 128'sd1 <<< (SubpixelBits + GFrac);
      // ceil(x / 2^n) = -floor(-x / 2^n), an arithmetic shift.
      line_lo = -((kappa_scale - 2 * kappa_lo) >>> (SubpixelBits + GFrac + 1));
      line_hi = -((-2 * kappa_hi - kappa_scale) >>> (SubpixelBits + GFrac + 1)) - 1;
      // The box bounds them too: line = density minor_offset - round(density g o).
      round_last = ((sext64(g_q) * $signed({96'd0, major_count_d - 32'd1}) <<< density_log2_q)
                    + (128'sd1 <<< (GFrac - 1))) >>> GFrac;
      if (round_last > 0) begin
        if (line_lo < -round_last) line_lo = -round_last;
      end else begin
        if (line_lo < 0) line_lo = '0;
      end
      minor_extent = $signed({96'd0, minor_hi_d - minor_lo_d}) <<< density_log2_q;
      if (round_last < 0) begin
        if (line_hi > minor_extent - round_last) line_hi = minor_extent - round_last;
      end else begin
        if (line_hi > minor_extent) line_hi = minor_extent;
      end
      line_lo_d = 64'(line_lo);
      line_hi_d = 64'(line_hi);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_at_ref_q <= '0;
      q_per_line_q <= '0;
      u_at_ref_q <= '0;
      u_per_line_q <= '0;
      v_at_ref_q <= '0;
      v_per_line_q <= '0;
      step_u_q <= '0;
      step_v_q <= '0;
      major_lo_q <= '0;
      major_count_q <= '0;
      minor_lo_q <= '0;
      minor_hi_q <= '0;
      line_lo_q <= '0;
      line_hi_q <= '0;
    end else begin
      q_at_ref_q <= q_at_ref_d;
      q_per_line_q <= q_per_line_d;
      u_at_ref_q <= u_at_ref_d;
      u_per_line_q <= u_per_line_d;
      v_at_ref_q <= v_at_ref_d;
      v_per_line_q <= v_per_line_d;
      step_u_q <= step_u_d;
      step_v_q <= step_v_d;
      major_lo_q <= major_lo_d;
      major_count_q <= major_count_d;
      minor_lo_q <= minor_lo_d;
      minor_hi_q <= minor_hi_d;
      line_lo_q <= line_lo_d;
      line_hi_q <= line_hi_d;
    end
  end

  assign empty_o = empty_q;
  assign x_major_o = x_major_q;
  assign g_o = g_q;
  assign major_lo_o = major_lo_q;
  assign major_count_o = major_count_q;
  assign minor_lo_o = minor_lo_q;
  assign minor_hi_o = minor_hi_q;
  assign pixel_line_lo_o = line_lo_q;
  assign pixel_line_hi_o = line_hi_q;
  assign edge_a_o = edge_a_q;
  assign edge_b_o = edge_b_q;
  assign edge_c_o = edge_c_q;
  assign edge_threshold_o = edge_threshold_q;
  assign flags_o = flags_q;

  // ---------------------------------------------------------------- fill
  // Line k: q_k = q_ref + k q_line (likewise U, V); reciprocal mantissa
  // R = floor(2^(2 rb) / M) of q_k; T = U_k R, S = SU R narrowed to their formats.
  localparam int PipeBits = 1 + AddrBits + WordBits;

  logic [PipeBits-1:0] fill_result;
  logic signed [W-1:0] line_q, line_u, line_v, line_k, mantissa_q, recip;
  logic [7:0]          recip_exponent;
  logic signed [31:0]  product_frac;
  logic                depth_out, saturated;
  logic signed [W-1:0] t_u, t_v, s_u, s_v, narrowed;

  always_comb begin
    fill_result = '0;
    {line_q, line_u, line_v, line_k, mantissa_q, recip} = '0;
    {t_u, t_v, s_u, s_v, narrowed} = '0;
    recip_exponent = '0;
    product_frac = '0;
    depth_out = 1'b0;
    saturated = 1'b0;
    if (fill_valid_i) begin
      line_k = sext64(fill_line_i);
      line_q = q_at_ref_q + line_k * q_per_line_q;
      line_u = u_at_ref_q + line_k * u_per_line_q;
      line_v = v_at_ref_q + line_k * v_per_line_q;
      if (line_q <= 0) begin
        depth_out = 1'b1;
        line_q = 128'sd1;
      end
      recip_exponent = cd_bit_length(line_q) - 8'd1;
      if (32'(recip_exponent) >= RecipBits) mantissa_q = line_q >>> (32'(recip_exponent) - RecipBits);
      else mantissa_q = line_q <<< (RecipBits - 32'(recip_exponent));
      recip = (128'sd1 <<< (2 * RecipBits)) / mantissa_q;
      product_frac = 32'(RecipBits) + 32'(recip_exponent) + 32'(UvInFrac);

      narrowed = cd_shift_round(line_u * recip, product_frac - 32'(TFrac), 1'b1);
      t_u = cd_saturate(narrowed, TBits);
      if (t_u != narrowed) saturated = 1'b1;
      narrowed = cd_shift_round(line_v * recip, product_frac - 32'(TFrac), 1'b1);
      t_v = cd_saturate(narrowed, TBits);
      if (t_v != narrowed) saturated = 1'b1;
      narrowed = cd_shift_round(step_u_q * recip, product_frac - 32'(SFrac), 1'b1);
      s_u = cd_saturate(narrowed, SBits);
      if (s_u != narrowed) saturated = 1'b1;
      narrowed = cd_shift_round(step_v_q * recip, product_frac - 32'(SFrac), 1'b1);
      s_v = cd_saturate(narrowed, SBits);
      if (s_v != narrowed) saturated = 1'b1;
      // Word: {depth_range, table_saturated, S.v, S.u, T.v, T.u}.
      fill_result = {1'b1, fill_addr_i, depth_out, saturated,
                     s_v[SBits-1:0], s_u[SBits-1:0], t_v[TBits-1:0], t_u[TBits-1:0]};
    end
  end

  // The reciprocal pipeline: RecipLatency stages between issue and write.
  logic [RecipLatency*PipeBits-1:0] pipe_q;

  if (RecipLatency == 1) begin : gen_pipe_one
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) pipe_q <= '0;
      else pipe_q <= fill_result;
    end
  end else begin : gen_pipe
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) pipe_q <= '0;
      else pipe_q <= {pipe_q[(RecipLatency-1)*PipeBits-1:0], fill_result};
    end
  end

  assign {write_valid_o, write_addr_o, write_entry_o} =
      pipe_q[(RecipLatency-1)*PipeBits +: PipeBits];

endmodule
