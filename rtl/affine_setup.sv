// Affine setup: the planes of u and v themselves (not u q) in screen space,
// for the plain affine design. Twin of affine_setup (model/affine_datapath.cpp):
//   A_x = dA1 dy2 - dA2 dy1, A_y = dA2 dx1 - dA1 dx2,
//   A(ref) = A0 det + A_x ref_x + A_y ref_y,
// each divided by det 2^uv_in_frac with round to nearest (ties up),
//   divide_nearest(n, d) = floor((2 n + d) / (2 d)) after making d > 0,
// and saturated: the reference to t_int.s_frac, the steps per pixel
// (A_x 2^subpixel_bits, A_y 2^subpixel_bits) to s_int.s_frac. One flag,
// saturated_o, says any of the six saturated.
//
// Timing, on the setup engine's stage count: with the setup engine's stage B
// (CD_SETUP_STAGE_B) it forms the coefficients, with its stage C the
// numerators, and starts six serial dividers, which resolve
// CD_AFFINE_DIV_BITS_PER_CYCLE bits a cycle so that they finish with the
// setup engine's (CD_SETUP_DIV_DONE), where the results are rounded,
// saturated and held until the next triangle. Its multiplies are its own
// (not on the setup engine's shared multipliers).
`include "cd_widths.svh"
`default_nettype none

module affine_setup (
  input  logic                               clk_i,
  input  logic                               rst_ni,
  input  logic                               setup_i,
  input  logic [`CD_SETUP_COUNT_BITS-1:0]    stage_count_i,
  // From the setup engine, valid from stage B (the vertices as loaded, and
  // stage A's differences, determinant and reference offsets).
  input  logic [3*`CD_UV_BITS-1:0]           u_vertex_i,
  input  logic [3*`CD_UV_BITS-1:0]           v_vertex_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    dx1_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    dy1_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    dx2_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    dy2_i,
  input  logic signed [`CD_DET_BITS-1:0]     det_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    ref_x_i,
  input  logic signed [`CD_DIFF_BITS-1:0]    ref_y_i,
  input  logic                               x_major_i,  // valid after the setup engine's stage C
  // Results, valid from the cycle after stage D.
  output logic signed [`CD_AFFINE_REF_BITS-1:0] u_ref_o,
  output logic signed [`CD_AFFINE_REF_BITS-1:0] v_ref_o,
  output logic signed [`CD_S_BITS-1:0]       u_major_o,
  output logic signed [`CD_S_BITS-1:0]       u_minor_o,
  output logic signed [`CD_S_BITS-1:0]       v_major_o,
  output logic signed [`CD_S_BITS-1:0]       v_minor_o,
  output logic                               saturated_o
);

  localparam int UvBits       = `CD_UV_BITS;
  localparam int DiffBits     = `CD_DIFF_BITS;
  localparam int DetBits      = `CD_DET_BITS;
  localparam int SubpixelBits = `CD_SUBPIXEL_BITS;
  localparam int UvInFrac     = `CD_UV_IN_FRAC;
  localparam int SFrac        = `CD_S_FRAC;
  localparam int RefBits      = `CD_AFFINE_REF_BITS;
  localparam int SBits        = `CD_S_BITS;
  localparam int CountBits    = `CD_SETUP_COUNT_BITS;
  localparam int BitsPerCycle = `CD_AFFINE_DIV_BITS_PER_CYCLE;
  // |dA| < 2^UvBits, |dy| < 2^(DiffBits - 1): two products and their difference.
  localparam int CoefBits     = UvBits + DiffBits + 1;
  // |A0 det| < 2^(UvBits + DetBits - 2), |A_x ref_x| < 2^(CoefBits + DiffBits - 2).
  localparam int AtRefBits    = UvBits + DetBits + 2;
  // Numerators 2 n 2^s_frac + d and the denominator 2 |det| 2^uv_in_frac, as magnitudes.
  localparam int DenBits      = DetBits + UvInFrac;
  localparam int RefNumBits   = AtRefBits + SFrac + 2;
  localparam int StepNumBits  = CoefBits + SubpixelBits + SFrac + 2;

  logic stage_b, stage_c, stage_d;
  assign stage_b = setup_i && stage_count_i == CountBits'(`CD_SETUP_STAGE_B);
  assign stage_c = setup_i && stage_count_i == CountBits'(`CD_SETUP_STAGE_C);
  assign stage_d = setup_i && stage_count_i == CountBits'(`CD_SETUP_DIV_DONE);

  // ---------------------------------------------------------------- stage B
  logic signed [UvBits-1:0]   u0, u1, u2, v0, v1, v2;
  logic signed [UvBits:0]     du1, du2, dv1, dv2;
  logic signed [CoefBits-1:0] u_x_d, u_y_d, v_x_d, v_y_d, u_x_q, u_y_q, v_x_q, v_y_q;

  assign {u2, u1, u0} = u_vertex_i;
  assign {v2, v1, v0} = v_vertex_i;

  always_comb begin
    du1 = '0;
    du2 = '0;
    dv1 = '0;
    dv2 = '0;
    u_x_d = '0;
    u_y_d = '0;
    v_x_d = '0;
    v_y_d = '0;
    if (stage_b) begin
      du1 = (UvBits+1)'(u1) - (UvBits+1)'(u0);
      du2 = (UvBits+1)'(u2) - (UvBits+1)'(u0);
      dv1 = (UvBits+1)'(v1) - (UvBits+1)'(v0);
      dv2 = (UvBits+1)'(v2) - (UvBits+1)'(v0);
      u_x_d = CoefBits'(du1) * CoefBits'(dy2_i) - CoefBits'(du2) * CoefBits'(dy1_i);
      u_y_d = CoefBits'(du2) * CoefBits'(dx1_i) - CoefBits'(du1) * CoefBits'(dx2_i);
      v_x_d = CoefBits'(dv1) * CoefBits'(dy2_i) - CoefBits'(dv2) * CoefBits'(dy1_i);
      v_y_d = CoefBits'(dv2) * CoefBits'(dx1_i) - CoefBits'(dv1) * CoefBits'(dx2_i);
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_b) begin
      u_x_q <= u_x_d;
      u_y_q <= u_y_d;
      v_x_q <= v_x_d;
      v_y_q <= v_y_d;
    end
  end

  // ---------------------------------------------------------------- stage C
  // Per plane value (u ref, u per x, u per y, then v): the sign of the
  // numerator 2 n' 2^s_frac + d with n' = sign(det) n, d = |det| 2^uv_in_frac,
  // and its magnitude.
  logic signed [AtRefBits-1:0] u_at_ref, v_at_ref;
  logic signed [RefNumBits:0]  ref_num [2];
  logic signed [StepNumBits:0] step_num [4];
  logic [RefNumBits-1:0]       ref_num_abs [2];
  logic [StepNumBits-1:0]      step_num_abs [4];
  logic [DenBits-1:0]          den;
  logic [5:0]                  negative_d, negative_q;
  logic                        det_negative;

  always_comb begin
    u_at_ref = '0;
    v_at_ref = '0;
    den = '0;
    det_negative = 1'b0;
    negative_d = '0;
    for (int i = 0; i < 2; i++) ref_num[i] = '0;
    for (int i = 0; i < 4; i++) step_num[i] = '0;
    for (int i = 0; i < 2; i++) ref_num_abs[i] = '0;
    for (int i = 0; i < 4; i++) step_num_abs[i] = '0;
    if (stage_c) begin
      det_negative = det_i < 0;
      den = (det_negative ? -(DenBits'(det_i)) : DenBits'(det_i)) << (UvInFrac + 1);
      u_at_ref = AtRefBits'(u0) * AtRefBits'(det_i) + AtRefBits'(u_x_q) * AtRefBits'(ref_x_i) +
                 AtRefBits'(u_y_q) * AtRefBits'(ref_y_i);
      v_at_ref = AtRefBits'(v0) * AtRefBits'(det_i) + AtRefBits'(v_x_q) * AtRefBits'(ref_x_i) +
                 AtRefBits'(v_y_q) * AtRefBits'(ref_y_i);
      ref_num[0] = ((det_negative ? -((RefNumBits+1)'(u_at_ref)) : (RefNumBits+1)'(u_at_ref)) <<< (SFrac + 1)) +
                   (RefNumBits+1)'($signed({1'b0, den >> 1}));
      ref_num[1] = ((det_negative ? -((RefNumBits+1)'(v_at_ref)) : (RefNumBits+1)'(v_at_ref)) <<< (SFrac + 1)) +
                   (RefNumBits+1)'($signed({1'b0, den >> 1}));
      step_num[0] = ((det_negative ? -((StepNumBits+1)'(u_x_q)) : (StepNumBits+1)'(u_x_q)) <<< (SubpixelBits + SFrac + 1)) +
                    (StepNumBits+1)'($signed({1'b0, den >> 1}));
      step_num[1] = ((det_negative ? -((StepNumBits+1)'(u_y_q)) : (StepNumBits+1)'(u_y_q)) <<< (SubpixelBits + SFrac + 1)) +
                    (StepNumBits+1)'($signed({1'b0, den >> 1}));
      step_num[2] = ((det_negative ? -((StepNumBits+1)'(v_x_q)) : (StepNumBits+1)'(v_x_q)) <<< (SubpixelBits + SFrac + 1)) +
                    (StepNumBits+1)'($signed({1'b0, den >> 1}));
      step_num[3] = ((det_negative ? -((StepNumBits+1)'(v_y_q)) : (StepNumBits+1)'(v_y_q)) <<< (SubpixelBits + SFrac + 1)) +
                    (StepNumBits+1)'($signed({1'b0, den >> 1}));
      for (int i = 0; i < 2; i++) begin
        negative_d[3*i] = ref_num[i] < 0;
        ref_num_abs[i] = RefNumBits'(ref_num[i] < 0 ? -ref_num[i] : ref_num[i]);
      end
      for (int i = 0; i < 4; i++) begin
        negative_d[3*(i/2) + 1 + i%2] = step_num[i] < 0;
        step_num_abs[i] = StepNumBits'(step_num[i] < 0 ? -step_num[i] : step_num[i]);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_c) negative_q <= negative_d;
  end

  // ---------------------------------------------------------------- dividers
  logic [RefBits-1:0] ref_quotient [2];
  logic [DenBits-1:0] ref_remainder [2];
  logic [1:0]         ref_overflow;
  logic [SBits-1:0]   step_quotient [4];
  logic [DenBits-1:0] step_remainder [4];
  logic [3:0]         step_overflow;

  for (genvar i = 0; i < 2; i++) begin : gen_ref_dividers
    serial_divider #(
      .NumBits(RefNumBits), .DenBits(DenBits), .QuoBits(RefBits), .BitsPerCycle(BitsPerCycle)
    ) u_divider (
      .clk_i, .rst_ni,
      .start_i      (stage_c),
      .numerator_i  (ref_num_abs[i]),
      .denominator_i(den),
      .quotient_o   (ref_quotient[i]),
      .remainder_o  (ref_remainder[i]),
      .overflow_o   (ref_overflow[i])
    );
  end
  for (genvar i = 0; i < 4; i++) begin : gen_step_dividers
    serial_divider #(
      .NumBits(StepNumBits), .DenBits(DenBits), .QuoBits(SBits), .BitsPerCycle(BitsPerCycle)
    ) u_divider (
      .clk_i, .rst_ni,
      .start_i      (stage_c),
      .numerator_i  (step_num_abs[i]),
      .denominator_i(den),
      .quotient_o   (step_quotient[i]),
      .remainder_o  (step_remainder[i]),
      .overflow_o   (step_overflow[i])
    );
  end

  // ---------------------------------------------------------------- stage D
  // floor of a signed quotient from its magnitude: -q - (r != 0) when negative;
  // then saturated to the format (the magnitude divider flags >= 2^Bits).
  localparam logic [RefBits:0] RefLimit = (RefBits+1)'(1) << (RefBits - 1);
  localparam logic [SBits:0]   StepLimit = (SBits+1)'(1) << (SBits - 1);
  localparam logic signed [RefBits-1:0] RefMax = RefBits'(RefLimit - (RefBits+1)'(1));
  localparam logic signed [SBits-1:0]   StepMax = SBits'(StepLimit - (SBits+1)'(1));

  logic signed [RefBits-1:0] ref_d [2];
  logic signed [SBits-1:0]   step_d [4];
  logic [RefBits:0]          ref_magnitude [2];
  logic [SBits:0]            step_magnitude [4];
  logic [5:0]                saturated_d;
  logic                      negative;

  always_comb begin
    for (int i = 0; i < 2; i++) ref_d[i] = '0;
    for (int i = 0; i < 4; i++) step_d[i] = '0;
    for (int i = 0; i < 2; i++) ref_magnitude[i] = '0;
    for (int i = 0; i < 4; i++) step_magnitude[i] = '0;
    saturated_d = '0;
    negative = 1'b0;
    if (stage_d) begin
      for (int i = 0; i < 2; i++) begin
        negative = negative_q[3*i];
        ref_magnitude[i] = (RefBits+1)'(ref_quotient[i]) +
                           (RefBits+1)'(negative && ref_remainder[i] != '0);
        saturated_d[3*i] = ref_overflow[i] || (negative ? ref_magnitude[i] > RefLimit
                                                        : ref_magnitude[i] >= RefLimit);
        if (saturated_d[3*i]) ref_d[i] = negative ? -RefMax - RefBits'(1) : RefMax;
        else ref_d[i] = negative ? -(RefBits'(ref_magnitude[i])) : RefBits'(ref_magnitude[i]);
      end
      for (int i = 0; i < 4; i++) begin
        negative = negative_q[3*(i/2) + 1 + i%2];
        step_magnitude[i] = (SBits+1)'(step_quotient[i]) +
                            (SBits+1)'(negative && step_remainder[i] != '0);
        saturated_d[3*(i/2) + 1 + i%2] = step_overflow[i] ||
            (negative ? step_magnitude[i] > StepLimit : step_magnitude[i] >= StepLimit);
        if (saturated_d[3*(i/2) + 1 + i%2]) step_d[i] = negative ? -StepMax - SBits'(1) : StepMax;
        else step_d[i] = negative ? -(SBits'(step_magnitude[i])) : SBits'(step_magnitude[i]);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_d) begin
      u_ref_o <= ref_d[0];
      v_ref_o <= ref_d[1];
      u_major_o <= x_major_i ? step_d[0] : step_d[1];
      u_minor_o <= x_major_i ? step_d[1] : step_d[0];
      v_major_o <= x_major_i ? step_d[2] : step_d[3];
      v_minor_o <= x_major_i ? step_d[3] : step_d[2];
      saturated_o <= |saturated_d;
    end
  end

endmodule

`default_nettype wire
