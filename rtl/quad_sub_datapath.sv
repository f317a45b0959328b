// quad-subN's per-span datapath (Hecker's quadratic approximation, with
// subdivision): a span is cut into segments whose length L is a power of two,
// N while N pixels remain to its last pixel, then the remainder's binary
// digits from the highest (11 = 8 + 2 + 1). The exact u, v (rtl/exact_points.sv,
// t_int.s_frac) at each segment's start, middle (L >= 2) and end give the
// quadratic through them, and its forward differences walk the segment's
// pixels (and the span's last pixel itself in the final segment). Twin of
// run_affine's quadratic branch and quadratic_segment (model/scan_unit.cpp,
// model/affine_datapath.cpp).
//
// Exact, with no divider and no rounding before the output: with h = L / 2 =
// 2^j, a at 0, m at h and b at 2h, the quadratic times 2 h^2 has the integer
// first difference D1 = (4m - 3a - b) h + (a - 2m + b) at 0 and second
// difference D2 = 2 (a - 2m + b). All are held times 2^G, G = 2 MaxSegmentLog2
// - 1 (2 h^2 <= 2^G), so a shift aligns each segment; a 1-pixel segment has
// D1 = (b - a) 2^G, D2 = 0. The sum is rounded once to the output format.
//
// Points are issued in order, one per cycle: the span's first in the column
// cycle (span_i), then each segment's middle and end, a segment's no earlier
// than the cycle the segment before it takes its first pixel. A queue of five
// holds the current segment's three and the next one's two; the pipeline's
// result is usable in the cycle it arrives. valid_o is low until the current
// segment's points have arrived (model/timing.cpp, quadratic_span_cycles).
//
// hold_i (a fragment offered and not taken) freezes everything, the exact
// points' pipeline too, so that a stall costs exactly one cycle.
`include "cd_widths.svh"
`default_nettype none

module quad_sub_datapath #(
  parameter int MaxSegmentLog2 = 4   // the longest segment, N = 16
) (
  input  logic                                     clk_i,
  input  logic                                     rst_ni,
  input  logic                                     hold_i,
  input  logic [2:0]                               segment_log2_i,  // N = 2^segment_log2_i, >= 2
  // The column cycle of a span with pixels (which issues the exact point at
  // its first pixel), and the span's length - 1.
  input  logic                                     span_i,
  input  logic [`CD_PIXEL_BITS-1:0]                span_last_i,
  input  logic                                     take_i,          // the pixel offered is taken
  // The exact points (rtl/exact_points.sv): this datapath issues them.
  output logic                                     issue_o,         // a point after the span's first
  output logic [MaxSegmentLog2:0]                  jump_o,          // pixels after the point before
  input  logic                                     point_valid_i,
  input  logic signed [`CD_AFFINE_REF_BITS-1:0]    point_u_i,
  input  logic signed [`CD_AFFINE_REF_BITS-1:0]    point_v_i,
  input  logic                                     point_saturated_i,
  // The current pixel.
  output logic                                     valid_o,
  output logic signed [`CD_OUT_BITS-1:0]           u_o,
  output logic signed [`CD_OUT_BITS-1:0]           v_o,
  output logic                                     saturated_o
);

  localparam int PixelBits = `CD_PIXEL_BITS;
  localparam int RefBits   = `CD_AFFINE_REF_BITS;   // points, t_int.s_frac
  localparam int OutBits   = `CD_OUT_BITS;
  localparam int SFrac     = `CD_S_FRAC;
  localparam int OutFrac   = `CD_OUT_FRAC;
  localparam int LogBits   = $clog2(MaxSegmentLog2 + 1);  // log2 L, 0 .. MaxSegmentLog2
  localparam int Guard     = 2 * MaxSegmentLog2 - 1;      // G
  // |a|, |m|, |b| < R = 2^(RefBits - 1): |D1| 2^(G - 2j - 1) < 12 R 2^(G - 1),
  // the first difference anywhere in the segment < 28 R 2^(G - 1), the value
  // < 1.25 R 2^G.
  localparam int AccBits   = RefBits + Guard + 4;
  localparam int EntryBits = 2 * RefBits + 1;        // u, v, saturated
  localparam int Depth     = 5;

  if (MaxSegmentLog2 < 1 || MaxSegmentLog2 > 7) begin : gen_bad_segment
    $error("quad_sub_datapath: MaxSegmentLog2 must be 1 .. 7");
  end

  // log2 of the segment that starts `remaining` pixels before the span's last
  // (remaining >= 1): N, or the largest power of two <= remaining.
  function automatic logic [LogBits-1:0] length_log2(input logic [PixelBits-1:0] remaining,
                                                     input logic [2:0] segment_log2);
    length_log2 = '0;
    for (int b = 1; b < MaxSegmentLog2; b++)
      if (remaining[b]) length_log2 = LogBits'(b);
    if (remaining >= (PixelBits'(1) << segment_log2)) length_log2 = LogBits'(segment_log2);
  endfunction

  function automatic logic [PixelBits-1:0] length_of(input logic [LogBits-1:0] log2);
    length_of = PixelBits'(1) << log2;
  endfunction

  // ---------------------------------------------------------------- issue
  // The segment whose points are being issued: its start, length and whether
  // its middle is still to come.
  logic [PixelBits-1:0] span_last_q, issued_q;     // offsets from the span's first pixel
  logic [PixelBits-1:0] iss_first_q, iss_point, iss_next_first;
  logic [LogBits-1:0]   iss_log2_q;
  logic                 iss_middle_q, iss_busy_q, iss_allowed, issue;
  // The segment being walked and its pixel.
  logic [PixelBits-1:0] seg_first_q, seg_end, pixel_q;
  logic [LogBits-1:0]   seg_log2_q;
  logic                 seg_single_q;              // a 1-pixel span: no segment, one point
  logic                 seg_final, first_pixel, segment_done;

  assign seg_end = seg_single_q ? seg_first_q : seg_first_q + length_of(seg_log2_q);
  assign seg_final = seg_end == span_last_q;
  assign first_pixel = pixel_q == seg_first_q;
  // A segment ends at the pixel before its end point; the final one includes it.
  assign segment_done = take_i && !seg_final && pixel_q + PixelBits'(1) == seg_end;

  assign iss_point = iss_middle_q ? iss_first_q + length_of(LogBits'(iss_log2_q - LogBits'(1)))
                                  : iss_first_q + length_of(iss_log2_q);
  assign iss_next_first = iss_first_q + length_of(iss_log2_q);
  // The walked segment's own points, or the next segment's once the walked
  // one has taken its first pixel.
  assign iss_allowed = iss_first_q == seg_first_q ||
                       (iss_first_q == seg_end && (!first_pixel || take_i));
  assign issue = !hold_i && !span_i && iss_busy_q && iss_allowed;
  assign issue_o = issue;
  assign jump_o = (MaxSegmentLog2+1)'(iss_point - issued_q);

  always_ff @(posedge clk_i) begin
    if (!hold_i) begin
      if (span_i) begin
        span_last_q <= span_last_i;
        issued_q <= '0;
        iss_first_q <= '0;
        iss_log2_q <= length_log2(span_last_i, segment_log2_i);
        iss_middle_q <= length_log2(span_last_i, segment_log2_i) != '0;
        iss_busy_q <= span_last_i != '0;
        seg_first_q <= '0;
        seg_log2_q <= length_log2(span_last_i, segment_log2_i);
        seg_single_q <= span_last_i == '0;
        pixel_q <= '0;
      end else begin
        if (issue) begin
          issued_q <= iss_point;
          if (iss_middle_q) begin
            iss_middle_q <= 1'b0;
          end else begin
            iss_first_q <= iss_next_first;
            iss_log2_q <= length_log2(span_last_q - iss_next_first, segment_log2_i);
            iss_middle_q <= length_log2(span_last_q - iss_next_first, segment_log2_i) != '0;
            iss_busy_q <= iss_next_first != span_last_q;
          end
        end
        if (take_i) pixel_q <= pixel_q + PixelBits'(1);
        if (segment_done) begin
          seg_first_q <= seg_end;
          seg_log2_q <= length_log2(span_last_q - seg_end, segment_log2_i);
        end
      end
    end
  end

  // ---------------------------------------------------------------- queue
  // The walked segment's start, middle, end, then the next one's middle, end.
  logic [EntryBits-1:0] queue_q [Depth];
  logic [2:0]           count_q, needed, pop;
  logic [EntryBits-1:0] arriving, entry [3];
  logic                 arrives;

  assign arriving = {point_saturated_i, point_u_i, point_v_i};
  assign arrives = point_valid_i && !hold_i;
  assign needed = seg_single_q ? 3'd1 : seg_log2_q == '0 ? 3'd2 : 3'd3;
  assign pop = !segment_done ? 3'd0 : seg_log2_q == '0 ? 3'd1 : 3'd2;
  for (genvar i = 0; i < 3; i++) begin : gen_entry
    assign entry[i] = count_q > 3'(i) ? queue_q[i] : arriving;
  end
  assign valid_o = count_q >= needed || (count_q + 3'd1 == needed && point_valid_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      count_q <= '0;
    end else if (span_i && !hold_i) begin
      count_q <= '0;
    end else if (!hold_i) begin
      count_q <= count_q + 3'(arrives) - pop;
    end
  end

  always_ff @(posedge clk_i) begin
    if (!hold_i) begin
      for (int i = 0; i < Depth; i++) begin
        if (32'(i) + 32'(pop) < 32'(count_q)) queue_q[i] <= queue_q[i + 32'(pop)];
        else if (32'(i) + 32'(pop) == 32'(count_q) && arrives) queue_q[i] <= arriving;
      end
    end
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (!hold_i && !span_i && arrives && count_q == 3'(Depth) && pop == '0)
      $error("quad_sub_datapath: a point arrived with the queue full");
  end
`endif

  // ---------------------------------------------------------------- values
  // At a segment's first pixel the value is a 2^G and the differences are
  // formed; each taken pixel adds the first difference, which adds the second.
  logic signed [RefBits-1:0] a_u, a_v, m_u, m_v, b_u, b_v;
  logic                      a_saturated, m_saturated, b_saturated;
  logic signed [AccBits-1:0] d1_u, d1_v, d2_u, d2_v;
  logic signed [AccBits-1:0] acc_u_q, acc_v_q, diff_u_q, diff_v_q, diff2_u_q, diff2_v_q;
  logic signed [AccBits-1:0] value_u, value_v;

  assign {a_saturated, a_u, a_v} = entry[0];
  assign {m_saturated, m_u, m_v} = seg_log2_q == '0 ? entry[0] : entry[1];
  assign {b_saturated, b_u, b_v} = seg_log2_q == '0 ? entry[1] : entry[2];

  // D1 and D2 times 2^G for one coordinate: shifts by 2 (MaxJ - j) and one more,
  // MaxJ = MaxSegmentLog2 - 1, j = log2 L - 1.
  function automatic logic signed [2*AccBits-1:0] differences(
      input logic signed [RefBits-1:0] a, input logic signed [RefBits-1:0] m,
      input logic signed [RefBits-1:0] b, input logic [LogBits-1:0] log2);
    logic signed [AccBits-1:0] curve, line, first, second;
    logic [7:0] shift;
    curve = AccBits'(a) - (AccBits'(m) <<< 1) + AccBits'(b);
    line = (AccBits'(m) <<< 2) - AccBits'(a) - (AccBits'(a) <<< 1) - AccBits'(b);
    if (log2 == '0) begin
      first = (AccBits'(b) - AccBits'(a)) <<< Guard;
      second = '0;
    end else begin
      shift = 8'(2 * MaxSegmentLog2) - 8'(2) * 8'(log2);     // 2 (MaxJ - j)
      first = (line <<< (shift + 8'(log2) - 8'(1))) + (curve <<< shift);
      second = curve <<< (shift + 8'(1));
    end
    differences = {first, second};
  endfunction

  always_comb begin
    {d1_u, d2_u} = differences(a_u, m_u, b_u, seg_log2_q);
    {d1_v, d2_v} = differences(a_v, m_v, b_v, seg_log2_q);
  end

  assign value_u = first_pixel ? AccBits'(a_u) <<< Guard : acc_u_q;
  assign value_v = first_pixel ? AccBits'(a_v) <<< Guard : acc_v_q;

  always_ff @(posedge clk_i) begin
    if (!hold_i && take_i) begin
      if (first_pixel) begin
        acc_u_q <= value_u + d1_u;
        acc_v_q <= value_v + d1_v;
        diff_u_q <= d1_u + d2_u;
        diff_v_q <= d1_v + d2_v;
        diff2_u_q <= d2_u;
        diff2_v_q <= d2_v;
      end else begin
        acc_u_q <= acc_u_q + diff_u_q;
        acc_v_q <= acc_v_q + diff_v_q;
        diff_u_q <= diff_u_q + diff2_u_q;
        diff_v_q <= diff_v_q + diff2_v_q;
      end
    end
  end

  // The output format, and the flags of the segment's points.
  logic [1:0] narrow_saturated;
  localparam logic signed [7:0] NarrowShift = 8'(Guard + SFrac - OutFrac);
  localparam int MaxLeft = OutFrac > SFrac + Guard ? OutFrac - SFrac - Guard : 0;
  shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(MaxLeft))
    u_narrow_u (.enable_i(valid_o), .in_i(value_u), .shift_i(NarrowShift), .out_o(u_o),
                .saturated_o(narrow_saturated[0]));
  shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(MaxLeft))
    u_narrow_v (.enable_i(valid_o), .in_i(value_v), .shift_i(NarrowShift), .out_o(v_o),
                .saturated_o(narrow_saturated[1]));
  assign saturated_o = valid_o && (|narrow_saturated || a_saturated ||
                                   (!seg_single_q && (m_saturated || b_saturated)));

endmodule

`default_nettype wire
