// The Kim-style datapath (kim-iter, kim-pipe; SPEC §6, docs/designs.md): a
// reconstruction, not the authors' design. Twin of run_kim and kim_pixel
// (model/scan_unit.cpp, model/kim_datapath.cpp).
//
// Along a span (a column, or a row when y-major) u = N / D with N = U and
// D = q 2^uv_in_frac, both stepping by constants dN, dD per pixel. Per
// coordinate (u and v) the integer stage A keeps I (out_int bits, signed),
// R = N - I D exactly and S = dN - I dD; D and dD are shared.
//
// A, span start: the column cycle (span_i) loads R = N, S = dN, and D and dD
// shifted to their first quotient place, 2^(out_int-1) D and 2^(out_int-1) dD,
// from the plane accumulators' start values. Then out_int cycles of restoring
// division on N' = N + 2^(out_int-1) D, one quotient bit per cycle, MSB first,
// with the divisor register shifting right one place per cycle (so it ends as
// D, and dD as dD). The first bit needs no subtraction: N' >= 2^(out_int-1) D
// exactly when N >= 0, and then R stays N, else R = N'. Each later bit k:
// R >= D 2^k gives R -= D 2^k and S -= dD 2^k, so that R = N - I D and
// S = dN - I dD hold with the quotient so far, and no multiplier is needed. I
// is the quotient with its top bit inverted (Q' - 2^(out_int-1)), which is
// clamp(floor(N / D), out_int range): a quotient past the top keeps every bit
// set (R >= D remains), one below the bottom none (R < 0 remains). D <= 0 at
// the span start forces the bits to 1, 0, ..., 0: I = 0, R = N, S = dN.
//
// A, per pixel: the pixel A holds is finished when no unit step applies:
// R >= D with I < max steps up (R -= D, I += 1, S -= dD), R < 0 with I > min
// steps down (R += D, I -= 1, S += dD); a pixel with D <= 0 takes none. Each
// cycle does KimUnroll chained steps. A finished pixel is handed to B in a
// cycle where B accepts it; in that same cycle A moves to the next pixel of
// the span (D += dD, R += S) and does its first steps, so pixel k is finished
// max(1, ceil(steps / KimUnroll)) cycles after pixel k-1's hand-off, and waits
// (holding) while B is busy.
//
// B, the fraction: KimFrac bits of R / D by restoring division (truncating),
// then I 2^KimFrac + fraction rounded to out_int.out_frac (shift_round: to
// nearest, ties up, saturating with a flag). I at max with R >= D saturates to
// the output's max, I at min with R < 0 to its min (flagged); D <= 0 outputs 0
// (depth_out_o). The fragment is offered in B's last cycle, KimFrac cycles
// after the hand-off, its final quotient bit computed in that cycle.
//  - iterative (kim-iter): one subtractor per coordinate; busy KimFrac cycles
//    per pixel, it accepts the next pixel in the cycle its fragment is taken.
//  - pipelined (kim-pipe): KimFrac stages of one subtractor per coordinate,
//    one pixel per cycle.
//
// hold_i (a fragment offered and not taken) freezes A and B.
`include "cd_widths.svh"
`default_nettype none

module kim_datapath #(
  parameter bit HasIterative = 1'b1,   // kim-iter's fraction stage
  parameter bit HasPipelined = 1'b1    // kim-pipe's
) (
  input  logic                                     clk_i,
  input  logic                                     rst_ni,
  input  logic                                     hold_i,
  input  logic                                     pipelined_i,   // both present: this triangle's
  // The column cycle of a span with pixels, and the first pixel's q, U, V.
  input  logic                                     span_i,
  input  logic signed [`CD_PIXEL_Q_BITS-1:0]       q_start_i,
  input  logic signed [`CD_PIXEL_UV_BITS-1:0]      u_start_i,
  input  logic signed [`CD_PIXEL_UV_BITS-1:0]      v_start_i,
  input  logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  q_per_minor_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_minor_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] v_per_minor_i,
  // A works on the span; the pixel it holds is the span's last; its {major, minor}.
  input  logic                                     active_i,
  input  logic                                     last_pixel_i,
  input  logic [2*`CD_PIXEL_BITS-1:0]              tag_i,
  output logic                                     handoff_o,     // A hands its pixel to B
  output logic                                     drained_o,     // nothing in B after this cycle
  // B's fragment.
  output logic                                     valid_o,
  output logic signed [`CD_OUT_BITS-1:0]           u_o,
  output logic signed [`CD_OUT_BITS-1:0]           v_o,
  output logic                                     saturated_o,
  output logic                                     depth_out_o,
  output logic [2*`CD_PIXEL_BITS-1:0]              tag_o
);

  localparam int OutInt     = `CD_OUT_INT;
  localparam int OutFrac    = `CD_OUT_FRAC;
  localparam int OutBits    = `CD_OUT_BITS;
  localparam int KimFrac    = `CD_KIM_FRAC;
  localparam int KimUnroll  = `CD_KIM_UNROLL;
  localparam int UvInFrac   = `CD_UV_IN_FRAC;
  localparam int TagBits    = 2 * `CD_PIXEL_BITS;
  localparam int PixelUvBits = `CD_PIXEL_UV_BITS;
  localparam int StepUvBits = `CD_PLANE_STEP_UV_BITS;
  // D = q 2^uv_in_frac at a pixel (signed), and as the divisor's first place.
  localparam int DBits      = `CD_PIXEL_Q_BITS + UvInFrac;
  localparam int DivBits    = DBits + OutInt - 1;
  localparam int DStepBits  = `CD_PLANE_STEP_Q_BITS + UvInFrac + OutInt - 1;  // dD likewise
  localparam int FirstPlace = UvInFrac + OutInt - 1;
  // |R| = |N - I D| <= 2^(PixelUvBits-1) + 2^(OutInt-1) 2^(DBits-1), I in the
  // out_int range (also during the division, whose partial quotient stays in
  // it); S = dN - I dD likewise. A compare R - D needs one bit more.
  localparam int RBits      = (PixelUvBits > DivBits ? PixelUvBits : DivBits) + 1;
  localparam int SBits      = (StepUvBits > DStepBits ? StepUvBits : DStepBits) + 1;
  localparam int CmpBits    = RBits + 1;
  // B: 0 <= R < D < 2^(DBits-1), unsigned.
  localparam int FracBits   = DBits - 1;
  localparam int CountBits  = $clog2(OutInt);
  // B's payload besides the remainders and D: I_u, I_v, the class bits
  // {depth, u high, u low, v high, v low}, the tag.
  localparam int ClassBits  = 5;
  localparam int FixBits    = 2 * OutInt + ClassBits + TagBits;
  localparam logic signed [OutInt-1:0]  IMax   = {1'b0, {(OutInt - 1){1'b1}}};
  localparam logic signed [OutInt-1:0]  IMin   = {1'b1, {(OutInt - 1){1'b0}}};
  localparam logic signed [OutBits-1:0] OutMax = {1'b0, {(OutBits - 1){1'b1}}};
  localparam logic signed [OutBits-1:0] OutMin = {1'b1, {(OutBits - 1){1'b0}}};
  localparam logic signed [7:0]         NarrowShift = 8'(KimFrac - OutFrac);

  if (!HasIterative && !HasPipelined) begin : gen_no_fraction
    $error("kim_datapath needs a fraction stage (HasIterative, HasPipelined)");
  end

  logic pipelined;  // this triangle's fraction stage
  assign pipelined = HasPipelined && (!HasIterative || pipelined_i);

  // ---------------------------------------------------------------- stage A
  logic                        dividing_q, dividing_d;
  logic [CountBits-1:0]        count_q, count_d;
  logic signed [DivBits-1:0]   d_q, d_d, d_step;
  logic signed [DStepBits-1:0] dd_q, dd_d;
  logic                        load, divide, step, first_bit, last_bit, advance;
  logic                        span_depth, pixel_positive, step_positive;
  logic                        b_ready;
  logic [1:0]                  need;                 // per coordinate: a unit step applies
  logic [1:0]                  high, low;            // per coordinate: saturates high / low
  logic [2*OutInt-1:0]         integer_all;
  logic [2*FracBits-1:0]       remainder_all;

  assign load = span_i && !hold_i;
  assign divide = dividing_q && !hold_i;
  assign step = active_i && !dividing_q && !hold_i;
  assign first_bit = count_q == '0;
  assign last_bit = count_q == CountBits'(OutInt - 1);
  assign span_depth = d_q <= 0;       // during the division: D <= 0 at the span start
  assign pixel_positive = d_q > 0;    // after it: the pixel A holds has D > 0
  assign handoff_o = active_i && !dividing_q && need == 2'b00 && b_ready && !hold_i;
  assign advance = handoff_o && !last_pixel_i;
  // The next pixel's D in a hand-off cycle (the division keeps d_step = d_q).
  assign d_step = advance ? d_q + DivBits'(dd_q) : d_q;
  assign step_positive = d_step > 0;

  always_comb begin
    dividing_d = dividing_q;
    count_d = count_q;
    d_d = d_q;
    dd_d = dd_q;
    if (load) begin
      dividing_d = 1'b1;
      count_d = '0;
      d_d = DivBits'(q_start_i) <<< FirstPlace;
      dd_d = DStepBits'(q_per_minor_i) <<< FirstPlace;
    end else if (divide) begin
      count_d = count_q + CountBits'(1);
      if (last_bit) dividing_d = 1'b0;
      else begin
        // Exact: the low bits shifted out are the zeros shifted in at the load.
        d_d = d_q >>> 1;
        dd_d = dd_q >>> 1;
      end
    end else if (step) begin
      d_d = d_step;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) dividing_q <= 1'b0;
    else dividing_q <= dividing_d;
  end
  always_ff @(posedge clk_i) begin
    count_q <= count_d;
    d_q <= d_d;
    dd_q <= dd_d;
  end

  for (genvar c = 0; c < 2; c++) begin : gen_coordinate
    logic signed [PixelUvBits-1:0] n_start;
    logic signed [StepUvBits-1:0]  dn;
    logic signed [RBits-1:0]       r_q, r_d, r, r_divide;
    logic signed [SBits-1:0]       s_q, s_d, s, s_divide;
    logic signed [OutInt-1:0]      i_q, i_d, i, i_divide;
    logic signed [CmpBits-1:0]     below, below_0, held_below;
    logic signed [RBits-1:0]       above, above_0;  // only taken when R < 0: R + D fits
    logic signed [SBits-1:0]       s_down, s_up, s_down_0, s_up_0;
    logic                          up, down, quotient_bit;

    assign n_start = c == 0 ? u_start_i : v_start_i;
    assign dn = c == 0 ? u_per_minor_i : v_per_minor_i;

    // KimUnroll chained unit steps, from the registers or, in a hand-off
    // cycle, from the next pixel (R + S). The first step's adders also serve
    // the division (d_step is then the shifted divisor).
    always_comb begin
      r = advance ? r_q + RBits'(s_q) : r_q;
      s = s_q;
      i = i_q;
      below_0 = '0;
      above_0 = '0;
      s_down_0 = '0;
      s_up_0 = '0;
      for (int k = 0; k < KimUnroll; k++) begin
        below = CmpBits'(r) - CmpBits'(d_step);
        above = r + RBits'(d_step);
        s_down = s - SBits'(dd_q);
        s_up = s + SBits'(dd_q);
        if (k == 0) begin
          below_0 = below;
          above_0 = above;
          s_down_0 = s_down;
          s_up_0 = s_up;
        end
        up = step_positive && !below[CmpBits-1] && i != IMax;
        down = step_positive && r[RBits-1] && i != IMin;
        if (up) begin
          r = RBits'(below);
          s = s_down;
          i = i + OutInt'(1);
        end else if (down) begin
          r = above;
          s = s_up;
          i = i - OutInt'(1);
        end
      end
    end

    // One quotient bit of the span division.
    always_comb begin
      if (first_bit) begin
        quotient_bit = span_depth || !r_q[RBits-1];
        r_divide = quotient_bit ? r_q : above_0;
        s_divide = quotient_bit ? s_q : s_up_0;
        i_divide = {i_q[OutInt-2:0], !quotient_bit};
      end else begin
        quotient_bit = !span_depth && !below_0[CmpBits-1];
        r_divide = quotient_bit ? RBits'(below_0) : r_q;
        s_divide = quotient_bit ? s_down_0 : s_q;
        i_divide = {i_q[OutInt-2:0], quotient_bit};
      end
    end

    always_comb begin
      r_d = r_q;
      s_d = s_q;
      i_d = i_q;
      if (load) begin
        r_d = RBits'(n_start);
        s_d = SBits'(dn);
        i_d = '0;
      end else if (divide) begin
        r_d = r_divide;
        s_d = s_divide;
        i_d = i_divide;
      end else if (step) begin
        r_d = r;
        s_d = s;
        i_d = i;
      end
    end

    always_ff @(posedge clk_i) begin
      r_q <= r_d;
      s_q <= s_d;
      i_q <= i_d;
    end

    // The pixel A holds: finished, or saturating, from the registers.
    assign held_below = CmpBits'(r_q) - CmpBits'(d_q);
    assign need[c] = pixel_positive && ((!held_below[CmpBits-1] && i_q != IMax) ||
                                        (r_q[RBits-1] && i_q != IMin));
    assign high[c] = i_q == IMax && !held_below[CmpBits-1];
    assign low[c] = i_q == IMin && r_q[RBits-1];
    assign integer_all[c*OutInt +: OutInt] = i_q;
    assign remainder_all[c*FracBits +: FracBits] = FracBits'(r_q);  // 0 <= R < D unless saturating

`ifndef SYNTHESIS
    // Exact arithmetic: a finished pixel with D > 0 either lies in 0 <= R < D or
    // saturates; its D lies inside the pixel width.
    always_ff @(posedge clk_i) begin
      if (handoff_o && pixel_positive) begin
        assert (high[c] || low[c] || (r_q >= 0 && CmpBits'(r_q) < CmpBits'(d_q)))
          else $error("kim_datapath: coordinate %0d handed off with R outside [0, D)", c);
        assert (d_q < (DivBits'(1) <<< FracBits))
          else $error("kim_datapath: D past %0d bits", DBits);
      end
    end
`endif
  end

  logic [FracBits-1:0]  handoff_d;
  logic [FixBits-1:0]   handoff_fix;
  assign handoff_d = FracBits'(d_q);
  assign handoff_fix = {integer_all, !pixel_positive, high[0], low[0], high[1], low[1], tag_i};

  // ---------------------------------------------------------------- stage B
  // One restoring step per coordinate: t = 2 r - D, bit = t >= 0, r = t or 2 r.
  // 2 r < 2 D, so t fits FracBits + 2 bits; when bit = 0, 2 r < D fits FracBits.
  logic                  iter_valid, iter_rest, iter_ready;
  logic [2*KimFrac-1:0]  iter_quotient;
  logic [FixBits-1:0]    iter_fix;
  logic                  pipe_valid, pipe_rest;
  logic [2*KimFrac-1:0]  pipe_quotient;
  logic [FixBits-1:0]    pipe_fix;

  if (HasIterative) begin : gen_iterative
    localparam int FracCountBits = $clog2(KimFrac + 1);
    logic                     busy_q;
    logic [FracCountBits-1:0] frac_count_q;
    logic [2*FracBits-1:0]    rem_q, rem_next;
    logic [FracBits-1:0]      d_frac_q;
    logic [2*KimFrac-1:0]     quo_q, quo_next;
    logic [FixBits-1:0]       fix_q;
    logic                     take;

    for (genvar c = 0; c < 2; c++) begin : gen_step
      logic [FracBits+1:0] trial;
      assign trial = (FracBits+2)'({rem_q[c*FracBits +: FracBits], 1'b0}) - (FracBits+2)'(d_frac_q);
      assign rem_next[c*FracBits +: FracBits] =
          trial[FracBits+1] ? {rem_q[c*FracBits +: FracBits-1], 1'b0} : trial[FracBits-1:0];
      assign quo_next[c*KimFrac +: KimFrac] = KimFrac'({quo_q[c*KimFrac +: KimFrac], !trial[FracBits+1]});
    end

    assign take = handoff_o && !pipelined;
    assign iter_valid = busy_q && frac_count_q == FracCountBits'(KimFrac - 1);
    assign iter_rest = busy_q && !iter_valid;
    assign iter_ready = !busy_q || iter_valid;
    assign iter_quotient = quo_next;
    assign iter_fix = fix_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) busy_q <= 1'b0;
      else if (!hold_i) busy_q <= take || iter_rest;
    end
    always_ff @(posedge clk_i) begin
      if (take) begin
        frac_count_q <= '0;
        rem_q <= remainder_all;
        d_frac_q <= handoff_d;
        quo_q <= '0;
        fix_q <= handoff_fix;
      end else if (iter_rest && !hold_i) begin
        frac_count_q <= frac_count_q + FracCountBits'(1);
        rem_q <= rem_next;
        quo_q <= quo_next;
      end
    end
  end else begin : gen_no_iterative
    assign iter_valid = 1'b0;
    assign iter_rest = 1'b0;
    assign iter_ready = 1'b0;
    assign iter_quotient = '0;
    assign iter_fix = '0;
  end

  if (HasPipelined) begin : gen_pipelined
    // Slot s of each chain feeds stage s's registers (slot 0: the hand-off);
    // stage s resolves quotient bit KimFrac-1-s and fills slot s+1; the last
    // stage's result is the fragment.
    logic [KimFrac:0]               valid_chain;
    logic [(KimFrac+1)*2*FracBits-1:0] rem_chain;
    logic [(KimFrac+1)*FracBits-1:0]   d_chain;
    logic [(KimFrac+1)*2*KimFrac-1:0]  quo_chain;
    logic [(KimFrac+1)*FixBits-1:0]    fix_chain;

    assign valid_chain[0] = handoff_o && pipelined;
    assign rem_chain[0 +: 2*FracBits] = remainder_all;
    assign d_chain[0 +: FracBits] = handoff_d;
    assign quo_chain[0 +: 2*KimFrac] = '0;
    assign fix_chain[0 +: FixBits] = handoff_fix;

    for (genvar s = 0; s < KimFrac; s++) begin : gen_stage
      logic                  valid_q;
      logic [2*FracBits-1:0] rem_q;
      logic [FracBits-1:0]   d_frac_q;
      logic [2*KimFrac-1:0]  quo_q, quo_next;
      logic [FixBits-1:0]    fix_q;

      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) valid_q <= 1'b0;
        else if (!hold_i) valid_q <= valid_chain[s];
      end
      // Operand isolation: a stage loads only behind a valid pixel.
      always_ff @(posedge clk_i) begin
        if (!hold_i && valid_chain[s]) begin
          rem_q <= rem_chain[s*2*FracBits +: 2*FracBits];
          d_frac_q <= d_chain[s*FracBits +: FracBits];
          quo_q <= quo_chain[s*2*KimFrac +: 2*KimFrac];
          fix_q <= fix_chain[s*FixBits +: FixBits];
        end
      end

      logic [2*FracBits-1:0] rem_next;
      for (genvar c = 0; c < 2; c++) begin : gen_step
        logic [FracBits+1:0] trial;
        assign trial = (FracBits+2)'({rem_q[c*FracBits +: FracBits], 1'b0}) - (FracBits+2)'(d_frac_q);
        assign rem_next[c*FracBits +: FracBits] =
            trial[FracBits+1] ? {rem_q[c*FracBits +: FracBits-1], 1'b0} : trial[FracBits-1:0];
        assign quo_next[c*KimFrac +: KimFrac] = KimFrac'({quo_q[c*KimFrac +: KimFrac], !trial[FracBits+1]});
      end

      assign valid_chain[s+1] = valid_q;
      assign quo_chain[(s+1)*2*KimFrac +: 2*KimFrac] = quo_next;
      assign fix_chain[(s+1)*FixBits +: FixBits] = fix_q;
      // The last stage's remainder and D go nowhere.
      assign rem_chain[(s+1)*2*FracBits +: 2*FracBits] = s + 1 < KimFrac ? rem_next : '0;
      assign d_chain[(s+1)*FracBits +: FracBits] = s + 1 < KimFrac ? d_frac_q : '0;
    end

    logic unused_last;
    assign unused_last = ^{rem_chain[KimFrac*2*FracBits +: 2*FracBits], d_chain[KimFrac*FracBits +: FracBits]};
    assign pipe_valid = valid_chain[KimFrac];
    if (KimFrac > 1) begin : gen_rest
      assign pipe_rest = |valid_chain[KimFrac-1:1];  // stages before the last
    end else begin : gen_no_rest
      assign pipe_rest = 1'b0;
    end
    assign pipe_quotient = quo_chain[KimFrac*2*KimFrac +: 2*KimFrac];
    assign pipe_fix = fix_chain[KimFrac*FixBits +: FixBits];
  end else begin : gen_no_pipelined
    assign pipe_valid = 1'b0;
    assign pipe_rest = 1'b0;
    assign pipe_quotient = '0;
    assign pipe_fix = '0;
  end

  assign b_ready = pipelined || iter_ready;
  // After this cycle B holds nothing: no hand-off, and nothing but the fragment
  // being offered now (a held cycle repeats, so hold_i need not enter).
  assign drained_o = !handoff_o && !iter_rest && !pipe_rest;

  // ---------------------------------------------------------------- output
  logic [2*KimFrac-1:0]      quotient;
  logic [FixBits-1:0]        fix;
  logic signed [OutInt-1:0]  out_i_u, out_i_v;
  logic                      depth, high_u, low_u, high_v, low_v;
  logic [TagBits-1:0]        tag;
  logic signed [OutBits-1:0] rounded_u, rounded_v;
  logic [1:0]                rounded_saturated;

  assign valid_o = pipelined ? pipe_valid : iter_valid;
  assign quotient = pipelined ? pipe_quotient : iter_quotient;
  assign fix = valid_o ? (pipelined ? pipe_fix : iter_fix) : '0;
  assign {out_i_v, out_i_u, depth, high_u, low_u, high_v, low_v, tag} = fix;

  shift_round #(.InBits(OutInt + KimFrac), .OutBits(OutBits), .ShiftBits(8),
                .MaxLeft(OutFrac > KimFrac ? OutFrac - KimFrac : 0))
    u_round_u (.enable_i(valid_o), .in_i({out_i_u, quotient[0 +: KimFrac]}), .shift_i(NarrowShift),
               .out_o(rounded_u), .saturated_o(rounded_saturated[0]));
  shift_round #(.InBits(OutInt + KimFrac), .OutBits(OutBits), .ShiftBits(8),
                .MaxLeft(OutFrac > KimFrac ? OutFrac - KimFrac : 0))
    u_round_v (.enable_i(valid_o), .in_i({out_i_v, quotient[KimFrac +: KimFrac]}), .shift_i(NarrowShift),
               .out_o(rounded_v), .saturated_o(rounded_saturated[1]));

  assign u_o = depth ? '0 : high_u ? OutMax : low_u ? OutMin : rounded_u;
  assign v_o = depth ? '0 : high_v ? OutMax : low_v ? OutMin : rounded_v;
  assign saturated_o = valid_o && !depth && (high_u || low_u || high_v || low_v || |rounded_saturated);
  assign depth_out_o = valid_o && depth;
  assign tag_o = tag;

`ifndef SYNTHESIS
  // A hand-off only into a free fraction stage; a fragment only from one stage.
  always_ff @(posedge clk_i) begin
    if (handoff_o && !pipelined)
      assert (iter_ready) else $error("kim_datapath: hand-off into a busy iterative fraction stage");
    assert (!(iter_valid && pipe_valid)) else $error("kim_datapath: both fraction stages offer a fragment");
    // The divisor and dD are back at their own place (D, dD) after the division.
    if (divide && last_bit)
      assert (d_q == DivBits'($signed(d_q[DBits-1:0])) &&
              dd_q == DStepBits'($signed(dd_q[DStepBits-OutInt:0])))
        else $error("kim_datapath: D or dD outside their widths after the span division");
  end
`endif

endmodule

`default_nettype wire
