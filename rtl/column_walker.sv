// Column walker: for column offset o (a row, when y-major) the rounded line
// shift r(o) = round(density g o), the distance t to the line as a direction
// and a correction weight, and the covered pixels of the column, clipped to the
// box and to the lines of the current band. Twin of model/column_walker.cpp and
// of covered_span in model/coverage.cpp. Combinational; its results are
// evaluated only in the walker's column cycle (step_i).
`include "cd_widths.svh"

module column_walker #(
  parameter int SubpixelBits = `CD_SUBPIXEL_BITS,
  parameter int GFrac        = `CD_G_FRAC,
  parameter int DFrac        = `CD_D_FRAC
) (
  input  logic               step_i,
  input  logic [31:0]        offset_i,
  // From the setup engine.
  input  logic               x_major_i,
  input  logic signed [63:0] g_i,
  input  logic [1:0]         density_log2_i,
  input  logic [31:0]        major_lo_i,
  input  logic [31:0]        minor_lo_i,
  input  logic [31:0]        minor_hi_i,
  input  logic [191:0]       edge_a_i,
  input  logic [191:0]       edge_b_i,
  input  logic [191:0]       edge_c_i,
  input  logic [2:0]         edge_threshold_i,
  // Lines of the current band.
  input  logic signed [63:0] band_lo_i,
  input  logic signed [63:0] band_hi_i,
  // Column results.
  output logic [31:0]        major_o,
  output logic signed [63:0] line_shift_o,
  output logic signed [1:0]  direction_o,
  output logic [31:0]        weight_o,
  output logic [31:0]        first_o,
  output logic [31:0]        last_o,
  output logic               has_pixels_o
);

  `include "cd_arith.svh"

  function automatic logic signed [127:0] sext64(input logic [63:0] x);
    sext64 = $signed({{64{x[63]}}, x});
  endfunction

  logic signed [63:0]  exact, t, fixed_centre, half_px, base, step, need;
  logic signed [63:0]  fixed_coef, free_coef, span_lo, span_hi, band_first, band_last;
  logic signed [63:0]  minor_lo, minor_hi;
  // |t| 2^(d_frac - g_frac) is at most 2^d_frac: the low 32 bits hold it.
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [127:0] weight;
  /* verilator lint_on UNUSEDSIGNAL */
  logic                span_empty;

  always_comb begin
    major_o = '0;
    line_shift_o = '0;
    direction_o = '0;
    weight_o = '0;
    first_o = '0;
    last_o = '0;
    has_pixels_o = 1'b0;
    {exact, t, fixed_centre, half_px, base, step, need} = '0;
    {fixed_coef, free_coef, span_lo, span_hi, band_first, band_last} = '0;
    {minor_lo, minor_hi} = '0;
    weight = '0;
    span_empty = 1'b0;
    if (step_i) begin
      major_o = major_lo_i + offset_i;
      // density g o in g_frac fraction bits; r(o) rounds it, ties toward +inf.
      exact = (g_i * $signed({32'd0, offset_i})) <<< density_log2_i;
      line_shift_o = (exact + (64'sd1 <<< (GFrac - 1))) >>> GFrac;
      t = (line_shift_o <<< GFrac) - exact;
      direction_o = t > 0 ? 2'sd1 : (t < 0 ? -2'sd1 : 2'sd0);
      weight = cd_shift_round(sext64(t < 0 ? -t : t), 32'(GFrac - DFrac), 1'b1);
      weight_o = weight[31:0];

      // Covered span by the three edge functions with the top-left rule.
      half_px = 64'sd1 <<< (SubpixelBits - 1);
      fixed_centre = ($signed({32'd0, major_o}) <<< SubpixelBits) + half_px;
      span_lo = -(64'sd1 <<< 61);
      span_hi = (64'sd1 <<< 61) - 64'sd1;
      for (int i = 0; i < 3; i++) begin
        fixed_coef = x_major_i ? edge_a_i[64*i +: 64] : edge_b_i[64*i +: 64];
        free_coef = x_major_i ? edge_b_i[64*i +: 64] : edge_a_i[64*i +: 64];
        base = fixed_coef * fixed_centre + free_coef * half_px + edge_c_i[64*i +: 64];
        step = free_coef <<< SubpixelBits;
        need = {63'd0, edge_threshold_i[i]} - base;
        if (step > 0) begin
          // ceil(need / step) = -floor(-need / step)
          band_first = 64'(-cd_floor_div(-sext64(need), sext64(step)));
          if (band_first > span_lo) span_lo = band_first;
        end else if (step < 0) begin
          band_last = 64'(cd_floor_div(-sext64(need), -sext64(step)));
          if (band_last < span_hi) span_hi = band_last;
        end else if (need > 0) begin
          span_empty = 1'b1;
        end
      end
      if (span_empty) begin
        span_lo = '0;
        span_hi = -64'sd1;
      end
      minor_lo = $signed({32'd0, minor_lo_i});
      minor_hi = $signed({32'd0, minor_hi_i});
      if (minor_lo > span_lo) span_lo = minor_lo;
      if (minor_hi < span_hi) span_hi = minor_hi;
      // Pixels whose line (density (minor - minor_lo) - r) lies in the band.
      band_first = minor_lo - ((-band_lo_i - line_shift_o) >>> density_log2_i);
      band_last = minor_lo + ((band_hi_i + line_shift_o) >>> density_log2_i);
      if (band_first > span_lo) span_lo = band_first;
      if (band_last < span_hi) span_hi = band_last;
      has_pixels_o = span_lo <= span_hi;
      first_o = span_lo[31:0];
      last_o = span_hi[31:0];
    end
  end

endmodule
