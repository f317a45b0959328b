// Column walker: for the current column (a row, when y-major) the rounded line
// shift r(o) = round(m g o), the distance t to the line as a direction and a
// correction weight, and the covered pixels of the column clipped to the box and
// to the lines of the current band. Twin of model/column_walker.cpp and of
// covered_span in model/pixel_coverage.cpp, without a divider: m g o and each edge's
// span end are accumulated from column to column.
//
// An edge's span end is floor(N / S) for the edge value N at the column's pixel
// 0 and S = |free coefficient| 2^subpixel_bits; N grows by fixed 2^subpixel_bits
// per column, which the setup engine split into floor(. / S) (slope) and a
// remainder (slope_rem), so a column step is two additions and a compare
// (Bresenham). Kind 1 (free > 0) bounds the span below at -floor(N / S), kind 2
// (free < 0) above at floor(N / S); kind 0 (free = 0) keeps floor(N / 2^sp) and
// empties the column while it is negative.
//
// Timing: init_i (the cycle before a band's first column) loads column 0;
// advance_i moves to the next column at the end of the cycle. The outputs
// describe the current column while active_i (operand isolation: 0 otherwise).
`include "cd_widths.svh"
`default_nettype none

module column_walker #(
  // The constant-depth designs' part: m g o, the line shift, the direction and
  // weight of the correction, and the band clip. 0 walks coverage spans only.
  parameter bit HasLines = 1'b1
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic                              active_i,  // a column cycle: outputs wanted
  input  logic                              init_i,
  input  logic                              advance_i,
  input  logic [`CD_PIXEL_BITS-1:0]         offset_i,
  // From the setup engine.
  input  logic signed [`CD_G_BITS-1:0]      g_i,
  // The lines' phase phi (CD_LINE_PHASE_FRAC fraction bits of a gap): m g o starts at it.
  input  logic [(`CD_LINE_PHASE_FRAC > 0 ? `CD_LINE_PHASE_FRAC : 1)-1:0] line_phase_i,
  input  logic [1:0]                        density_log2_i,
  input  logic [`CD_PIXEL_BITS-1:0]         major_lo_i,
  input  logic [`CD_PIXEL_BITS-1:0]         minor_lo_i,
  input  logic [`CD_PIXEL_BITS-1:0]         minor_hi_i,
  input  logic [5:0]                        edge_kind_i,
  input  logic [3*`CD_EDGE_BOUND_BITS-1:0]  edge_bound_i,
  input  logic [3*`CD_EDGE_STEP_BITS-1:0]   edge_rem_i,
  input  logic [3*`CD_EDGE_STEP_BITS-1:0]   edge_step_i,
  input  logic [3*`CD_EDGE_SLOPE_BITS-1:0]  edge_slope_i,
  input  logic [3*`CD_EDGE_STEP_BITS-1:0]   edge_slope_rem_i,
  // Lines of the current band; clip_band_i = 0 (the per-pixel designs) walks
  // the whole covered span.
  input  logic                              clip_band_i,
  input  logic signed [`CD_LINE_BITS-1:0]   band_lo_i,
  input  logic signed [`CD_LINE_BITS-1:0]   band_hi_i,
  // The current column.
  output logic [`CD_PIXEL_BITS-1:0]         major_o,
  output logic signed [`CD_LINE_BITS-1:0]   line_shift_o,
  output logic signed [1:0]                 direction_o,
  output logic [`CD_WEIGHT_BITS-1:0]        weight_o,
  output logic [`CD_PIXEL_BITS-1:0]         first_o,
  output logic [`CD_PIXEL_BITS-1:0]         last_o,
  output logic                              has_pixels_o
);

  localparam int GFrac         = `CD_G_FRAC;
  localparam int PhaseFrac     = `CD_LINE_PHASE_FRAC;
  localparam int DFrac         = `CD_D_FRAC;
  localparam int PixelBits     = `CD_PIXEL_BITS;
  localparam int LineBits      = `CD_LINE_BITS;
  localparam int ExactBits     = `CD_EXACT_SHIFT_BITS;
  localparam int TDistBits     = `CD_T_DIST_BITS;
  localparam int WeightBits    = `CD_WEIGHT_BITS;
  localparam int BoundBits     = `CD_EDGE_BOUND_BITS;
  localparam int StepBits      = `CD_EDGE_STEP_BITS;
  localparam int SlopeBits     = `CD_EDGE_SLOPE_BITS;
  localparam int SpanBits      = BoundBits + 1;
  // weight = round(|t| 2^-(g_frac - d_frac)), a right shift when g_frac > d_frac.
  localparam int WeightRight   = GFrac > DFrac ? GFrac - DFrac : 0;
  localparam int WeightLeft    = DFrac > GFrac ? DFrac - GFrac : 0;
  localparam logic [TDistBits-1:0] WeightHalf =
      GFrac > DFrac ? TDistBits'(1) << (WeightRight > 0 ? WeightRight - 1 : 0) : '0;

  // ---------------------------------------------------------------- state
  logic signed [ExactBits-1:0] exact_d, exact_q;      // m g o + phi, g_frac fraction bits
  logic signed [BoundBits-1:0] bound_d [3];
  logic signed [BoundBits-1:0] bound_q [3];
  logic [StepBits-1:0]         rem_d [3];
  logic [StepBits-1:0]         rem_q [3];
  logic [StepBits:0]           rem_sum;

  always_comb begin
    exact_d = exact_q;
    for (int i = 0; i < 3; i++) bound_d[i] = bound_q[i];
    for (int i = 0; i < 3; i++) rem_d[i] = rem_q[i];
    rem_sum = '0;
    if (init_i) begin
      exact_d = '0;
      if (HasLines && PhaseFrac > 0) exact_d = ExactBits'($unsigned(line_phase_i)) <<< (GFrac - PhaseFrac);
      for (int i = 0; i < 3; i++) begin
        bound_d[i] = edge_bound_i[BoundBits*i +: BoundBits];
        rem_d[i] = edge_rem_i[StepBits*i +: StepBits];
      end
    end else if (advance_i) begin
      if (HasLines) exact_d = exact_q + (ExactBits'(g_i) <<< density_log2_i);
      for (int i = 0; i < 3; i++) begin
        rem_sum = (StepBits+1)'(rem_q[i]) + (StepBits+1)'(edge_slope_rem_i[StepBits*i +: StepBits]);
        bound_d[i] = bound_q[i] + BoundBits'($signed(edge_slope_i[SlopeBits*i +: SlopeBits]));
        if (rem_sum >= (StepBits+1)'(edge_step_i[StepBits*i +: StepBits])) begin
          rem_sum = rem_sum - (StepBits+1)'(edge_step_i[StepBits*i +: StepBits]);
          bound_d[i] = bound_d[i] + BoundBits'(1);
        end
        rem_d[i] = StepBits'(rem_sum);
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      exact_q <= '0;
      for (int i = 0; i < 3; i++) begin
        bound_q[i] <= '0;
        rem_q[i] <= '0;
      end
    end else begin
      exact_q <= exact_d;
      for (int i = 0; i < 3; i++) bound_q[i] <= bound_d[i];
      for (int i = 0; i < 3; i++) rem_q[i] <= rem_d[i];
    end
  end

  // ---------------------------------------------------------------- column
  logic signed [ExactBits-1:0] rounded;
  logic signed [TDistBits-1:0] t;
  logic [TDistBits-1:0]        t_abs;
  logic signed [SpanBits-1:0]  span_lo, span_hi, bound;
  logic signed [LineBits:0]    band_first, band_last;
  logic                        span_empty;
  localparam int WeightWideBits = TDistBits + WeightLeft + 1;
  /* verilator lint_off UNUSEDSIGNAL */  // the weight is at most 2^(d_frac - 1)
  logic [WeightWideBits-1:0]   weight_wide;
  /* verilator lint_on UNUSEDSIGNAL */

  always_comb begin
    major_o = '0;
    rounded = '0;
    line_shift_o = '0;
    t = '0;
    direction_o = '0;
    t_abs = '0;
    weight_wide = '0;
    weight_o = '0;
    span_lo = '0;
    span_hi = '0;
    span_empty = 1'b0;
    bound = '0;
    band_first = '0;
    band_last = '0;
    has_pixels_o = 1'b0;
    first_o = '0;
    last_o = '0;
    if (active_i) begin
      major_o = major_lo_i + offset_i;
      // r(o) rounds m g o, ties toward +inf; the pixel lies t below its line.
      if (HasLines) rounded = (exact_q + ExactBits'(1 <<< (GFrac - 1))) >>> GFrac;
      line_shift_o = LineBits'(rounded);
      if (HasLines) t = TDistBits'((rounded <<< GFrac) - exact_q);
      direction_o = t > 0 ? 2'sd1 : (t < 0 ? -2'sd1 : 2'sd0);
      t_abs = t < 0 ? TDistBits'(-t) : TDistBits'(t);
      weight_wide = ((WeightWideBits'(t_abs) + WeightWideBits'(WeightHalf)) >> WeightRight) << WeightLeft;
      weight_o = WeightBits'(weight_wide);

      // The span: every edge's bound, the box, and the band's lines
      // (line = m (minor - minor_lo) - r lies in [band_lo, band_hi]).
      span_lo = SpanBits'($signed({1'b0, minor_lo_i}));
      span_hi = SpanBits'($signed({1'b0, minor_hi_i}));
      span_empty = 1'b0;
      for (int i = 0; i < 3; i++) begin
        bound = SpanBits'(bound_q[i]);
        unique case (edge_kind_i[2*i +: 2])
          2'd1: if (-bound > span_lo) span_lo = -bound;
          2'd2: if (bound < span_hi) span_hi = bound;
          default: if (bound < 0) span_empty = 1'b1;
        endcase
      end
      band_first = (LineBits+1)'($signed({1'b0, minor_lo_i})) -
                   ((-((LineBits+1)'(band_lo_i)) - (LineBits+1)'(line_shift_o)) >>> density_log2_i);
      band_last = (LineBits+1)'($signed({1'b0, minor_lo_i})) +
                  (((LineBits+1)'(band_hi_i) + (LineBits+1)'(line_shift_o)) >>> density_log2_i);
      if (HasLines && clip_band_i) begin
        if (SpanBits'(band_first) > span_lo) span_lo = SpanBits'(band_first);
        if (SpanBits'(band_last) < span_hi) span_hi = SpanBits'(band_last);
      end
      has_pixels_o = !span_empty && span_lo <= span_hi;
      first_o = PixelBits'(span_lo);
      last_o = PixelBits'(span_hi);
    end
  end

endmodule

`default_nettype wire
