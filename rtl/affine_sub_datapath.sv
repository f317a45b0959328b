// affine-subN's per-span datapath (Quake-style subdivision): the exact u, v
// (rtl/exact_points.sv, into t_int.s_frac) at the span's first pixel, every
// N-th pixel and the last pixel, and between two end points a, b the affine values
// a + p round((b - a) / run), p = 0 .. run - 1 (and the last pixel itself in
// the span's final segment). Twin of run_affine and interpolate_segment
// (model/scan_unit.cpp, model/affine_datapath.cpp).
//
// End points, by rtl/exact_points.sv, which this datapath drives (issue_o,
// jump_o). The first end point is issued in the column cycle (span_i), the
// second in the next cycle; each later one as the segment before its own
// starts (its first pixel taken). A queue of three end points holds a segment's two and the one in flight; the
// pipeline's result is usable in the cycle it arrives. valid_o is low while the
// current segment's end point has not arrived: the span's first recip_latency
// cycles, and max(0, recip_latency - N) cycles before each later segment.
//
// The step round((b - a) / run) = floor((2 (b - a) + run) / (2 run)), run = 1
// .. N, is exact without a divider: floor(n / d) = floor(n m / 2^K) for
// 0 <= n < 2^W with m = ceil(2^K / d), K = W + 5 and d <= 32 (Granlund and
// Montgomery); a negative numerator takes -floor((|n| + d - 1) m / 2^K). The
// sixteen m are elaboration constants (a ROM), one multiply per coordinate.
//
// hold_i (a fragment offered and not taken) freezes everything, the exact
// points' pipeline too, so that a stall costs exactly one cycle.
`include "cd_widths.svh"
`default_nettype none

module affine_sub_datapath #(
  parameter int MaxSegmentLog2 = 4   // the longest segment, N = 16
) (
  input  logic                                     clk_i,
  input  logic                                     rst_ni,
  input  logic                                     hold_i,
  input  logic [2:0]                               segment_log2_i,  // N = 2^segment_log2_i
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
  localparam int RefBits   = `CD_AFFINE_REF_BITS;   // end points, t_int.s_frac
  localparam int OutBits   = `CD_OUT_BITS;
  localparam int SFrac     = `CD_S_FRAC;
  localparam int OutFrac   = `CD_OUT_FRAC;
  localparam int JumpBits  = MaxSegmentLog2 + 1;    // 0 .. N
  localparam int StepBits  = RefBits + 1;           // |round((b - a) / run)| <= 2^(RefBits - 1) + 1
  localparam int AccBits   = RefBits + JumpBits + 2;
  localparam int NumBits   = RefBits + 2;           // |2 (b - a) + run| + 2 run - 1 < 2^(RefBits + 2)
  localparam int MagicBits = NumBits + 5;           // K
  localparam int MaxRun    = 1 << MaxSegmentLog2;
  localparam int EntryBits = 2 * RefBits + 1;       // u, v, saturated

  // ---------------------------------------------------------------- end points
  logic [PixelBits-1:0] span_last_q, issued_q;      // offsets from the span's first pixel
  logic                 second_due_q;               // issue the second end point next cycle
  logic                 issue;
  logic [JumpBits-1:0]  jump;
  logic [PixelBits-1:0] segment, left;
  logic [PixelBits-1:0] seg_first_q, seg_end_q, pixel_q;  // the current segment and pixel

  assign segment = PixelBits'(1) << segment_log2_i;

  always_comb begin
    // The next end point: a segment on, or the span's last pixel.
    left = span_last_q - issued_q;
    jump = JumpBits'(left < segment ? left : segment);
    issue = 1'b0;
    if (!hold_i) begin
      if (span_i) issue = 1'b1;
      else if (second_due_q) issue = 1'b1;
      else if (take_i && pixel_q == seg_first_q && issued_q != span_last_q) issue = 1'b1;
    end
  end
  assign issue_o = issue && !span_i;
  assign jump_o = jump;

  // ---------------------------------------------------------------- queue
  // Entries 0 and 1: the current segment's start and end; 2: the next end.
  logic [EntryBits-1:0] queue_q [3];
  logic [1:0]           count_q;
  logic [EntryBits-1:0] arriving, start_entry, end_entry;
  logic                 arrives, segment_done;

  assign arriving = {point_saturated_i, point_u_i, point_v_i};
  assign arrives = point_valid_i && !hold_i;
  assign start_entry = queue_q[0];
  assign end_entry = count_q >= 2'd2 ? queue_q[1] : arriving;
  assign valid_o = count_q >= 2'd2 || (count_q == 2'd1 && point_valid_i);

  // A segment ends at the pixel before its end point, but the span's final
  // segment includes its last pixel.
  assign segment_done = take_i && seg_end_q != span_last_q && pixel_q + PixelBits'(1) == seg_end_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      count_q <= '0;
    end else if (span_i && !hold_i) begin
      count_q <= '0;
    end else if (!hold_i) begin
      count_q <= count_q + 2'(arrives) - 2'(segment_done);
    end
  end

  always_ff @(posedge clk_i) begin
    if (!hold_i) begin
      if (segment_done) begin
        // Pop the start; an arrival fills the first free slot after it.
        queue_q[0] <= end_entry;
        queue_q[1] <= count_q == 2'd3 ? queue_q[2] : arriving;
        if (arrives && count_q == 2'd3) queue_q[2] <= arriving;
      end else if (arrives) begin
        for (int i = 0; i < 3; i++) if (2'(i) == count_q) queue_q[i] <= arriving;
      end
    end
  end

  // ---------------------------------------------------------------- segments
  logic [PixelBits-1:0] next_end;
  always_comb begin
    next_end = seg_end_q + segment;
    if (next_end > span_last_q || next_end < seg_end_q) next_end = span_last_q;
  end

  always_ff @(posedge clk_i) begin
    if (!hold_i) begin
      if (span_i) begin
        span_last_q <= span_last_i;
        issued_q <= '0;
        second_due_q <= 1'b1;
        seg_first_q <= '0;
        seg_end_q <= span_last_i < segment ? span_last_i : segment;
        pixel_q <= '0;
      end else begin
        second_due_q <= 1'b0;
        if (issue) issued_q <= issued_q + PixelBits'(jump);
        if (take_i) pixel_q <= pixel_q + PixelBits'(1);
        if (segment_done) begin
          seg_first_q <= seg_end_q;
          seg_end_q <= next_end;
        end
      end
    end
  end

  // ---------------------------------------------------------------- values
  // At a segment's first pixel the value is its start; the step is formed
  // there and each taken pixel adds it.
  logic signed [RefBits-1:0]  a_u, a_v, b_u, b_v;
  logic                       a_saturated, b_saturated;
  logic [JumpBits-1:0]        run;
  logic [MagicBits-1:0]       magic;
  logic signed [StepBits-1:0] step_u, step_v, step_u_q, step_v_q;
  logic signed [AccBits-1:0]  acc_u_q, acc_v_q, value_u, value_v;
  logic                       first_pixel;

  assign {a_saturated, a_u, a_v} = start_entry;
  assign {b_saturated, b_u, b_v} = end_entry;
  assign run = JumpBits'(seg_end_q - seg_first_q);
  assign first_pixel = pixel_q == seg_first_q;

  // m(run) = ceil(2^K / (2 run)), run = 1 .. MaxRun: elaboration constants.
  logic [(MaxRun+1)*MagicBits-1:0] magic_rom;
  for (genvar r = 0; r <= MaxRun; r++) begin : gen_magic
    if (r == 0) begin : gen_zero
      assign magic_rom[0 +: MagicBits] = '0;
    end else begin : gen_entry
      localparam logic [MagicBits:0] Power = (MagicBits+1)'(1) << MagicBits;
      localparam logic [MagicBits:0] Divisor = (MagicBits+1)'(2 * r);
      localparam logic [MagicBits:0] Magic = (Power + Divisor - (MagicBits+1)'(1)) / Divisor;
      assign magic_rom[r*MagicBits +: MagicBits] = MagicBits'(Magic);
    end
  end
  assign magic = magic_rom[32'(run)*MagicBits +: MagicBits];

  // floor((2 (b - a) + run) / (2 run)) for each coordinate.
  logic signed [NumBits:0]          num_u, num_v;
  logic [NumBits-1:0]               mag_u, mag_v;
  logic [NumBits+MagicBits-1:0]     product_u, product_v;
  logic [StepBits-1:0]              quotient_u, quotient_v;  // < 2^(NumBits - 1)

  always_comb begin
    num_u = '0;
    num_v = '0;
    mag_u = '0;
    mag_v = '0;
    product_u = '0;
    product_v = '0;
    quotient_u = '0;
    quotient_v = '0;
    step_u = '0;
    step_v = '0;
    if (valid_o && first_pixel && run != '0) begin
      num_u = (((NumBits+1)'(b_u) - (NumBits+1)'(a_u)) <<< 1) + (NumBits+1)'($signed({1'b0, run}));
      num_v = (((NumBits+1)'(b_v) - (NumBits+1)'(a_v)) <<< 1) + (NumBits+1)'($signed({1'b0, run}));
      // |n|, or |n| + 2 run - 1 for a negative n (floor toward -inf).
      mag_u = num_u < 0 ? NumBits'(-num_u) + NumBits'({run, 1'b0}) - NumBits'(1) : NumBits'(num_u);
      mag_v = num_v < 0 ? NumBits'(-num_v) + NumBits'({run, 1'b0}) - NumBits'(1) : NumBits'(num_v);
      product_u = (NumBits+MagicBits)'(mag_u) * (NumBits+MagicBits)'(magic);
      product_v = (NumBits+MagicBits)'(mag_v) * (NumBits+MagicBits)'(magic);
      quotient_u = StepBits'(product_u >> MagicBits);
      quotient_v = StepBits'(product_v >> MagicBits);
      step_u = num_u < 0 ? -quotient_u : quotient_u;
      step_v = num_v < 0 ? -quotient_v : quotient_v;
    end
  end

  assign value_u = first_pixel ? AccBits'(a_u) : acc_u_q;
  assign value_v = first_pixel ? AccBits'(a_v) : acc_v_q;

  always_ff @(posedge clk_i) begin
    if (!hold_i && take_i) begin
      if (first_pixel) begin
        step_u_q <= step_u;
        step_v_q <= step_v;
        acc_u_q <= AccBits'(a_u) + AccBits'(step_u);
        acc_v_q <= AccBits'(a_v) + AccBits'(step_v);
      end else begin
        acc_u_q <= acc_u_q + AccBits'(step_u_q);
        acc_v_q <= acc_v_q + AccBits'(step_v_q);
      end
    end
  end

  // The output format, and the flags of the segment's end points.
  logic [1:0] narrow_saturated;
  localparam logic signed [7:0] NarrowShift = 8'(SFrac - OutFrac);
  shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8),
                .MaxLeft(OutFrac > SFrac ? OutFrac - SFrac : 0))
    u_narrow_u (.enable_i(valid_o), .in_i(value_u), .shift_i(NarrowShift), .out_o(u_o),
                .saturated_o(narrow_saturated[0]));
  shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8),
                .MaxLeft(OutFrac > SFrac ? OutFrac - SFrac : 0))
    u_narrow_v (.enable_i(valid_o), .in_i(value_v), .shift_i(NarrowShift), .out_o(v_o),
                .saturated_o(narrow_saturated[1]));
  assign saturated_o = valid_o && (|narrow_saturated || a_saturated || (run != '0 && b_saturated));

endmodule

`default_nettype wire
