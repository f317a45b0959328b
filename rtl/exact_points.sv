// The exact points of the subdivided designs (affine-subN, quad-subN): u, v
// by pixel_divide into t_int.s_frac at pixels of the current span that the
// datapath names one at a time. Three plane accumulators (q, U, V) hold the
// last point issued: span_i issues the span's first pixel (in the column
// cycle), issue_i a later point jump_i pixels after the one before. A point
// arrives recip_latency cycles after its issue (valid_o). hold_i freezes the
// pipeline and the accumulators.
`include "cd_widths.svh"
`default_nettype none

module exact_points #(
  parameter int JumpBits = 5
) (
  input  logic                                     clk_i,
  input  logic                                     rst_ni,
  input  logic                                     hold_i,
  input  logic                                     column_init_i,
  input  logic                                     column_advance_i,
  input  logic                                     span_i,
  input  logic [`CD_PIXEL_BITS-1:0]                first_offset_i,
  input  logic                                     issue_i,   // a point after the first (not with span_i)
  input  logic [JumpBits-1:0]                      jump_i,
  // Planes of q, U, V (setup engine).
  input  logic signed [`CD_PLANE_REF_Q_BITS-1:0]   q_at_ref_i,
  input  logic signed [`CD_PLANE_REF_UV_BITS-1:0]  u_at_ref_i,
  input  logic signed [`CD_PLANE_REF_UV_BITS-1:0]  v_at_ref_i,
  input  logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  q_per_major_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_major_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] v_per_major_i,
  input  logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  q_per_minor_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_minor_i,
  input  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] v_per_minor_i,
  // The point arriving (t_int.s_frac), its saturation and q <= 0.
  output logic                                     valid_o,
  output logic signed [`CD_AFFINE_REF_BITS-1:0]    u_o,
  output logic signed [`CD_AFFINE_REF_BITS-1:0]    v_o,
  output logic                                     saturated_o,
  output logic                                     depth_out_o
);

  logic start, step;
  assign start = span_i && !hold_i;
  assign step = issue_i && !span_i && !hold_i;

  logic signed [`CD_PIXEL_Q_BITS-1:0]  q_first, q_next, q_point;
  logic signed [`CD_PIXEL_UV_BITS-1:0] u_first, v_first, u_next, v_next, u_point, v_point;

  // start_i loads the span's first pixel; step_i jumps to the next point. Only
  // start_value_o and next_value_o are used (the point issued).
  /* verilator lint_off PINCONNECTEMPTY */
  plane_accumulator #(
    .RefBits(`CD_PLANE_REF_Q_BITS), .StepBits(`CD_PLANE_STEP_Q_BITS), .AccBits(`CD_PIXEL_Q_BITS),
    .JumpBits(JumpBits)
  ) u_point_q (
    .clk_i, .init_i(column_init_i), .advance_i(column_advance_i), .start_i(start), .step_i(step),
    .first_offset_i, .jump_i,
    .at_ref_i(q_at_ref_i), .per_major_i(q_per_major_i), .per_minor_i(q_per_minor_i),
    .start_value_o(q_first), .next_value_o(q_next), .value_o()
  );
  plane_accumulator #(
    .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS),
    .JumpBits(JumpBits)
  ) u_point_u (
    .clk_i, .init_i(column_init_i), .advance_i(column_advance_i), .start_i(start), .step_i(step),
    .first_offset_i, .jump_i,
    .at_ref_i(u_at_ref_i), .per_major_i(u_per_major_i), .per_minor_i(u_per_minor_i),
    .start_value_o(u_first), .next_value_o(u_next), .value_o()
  );
  plane_accumulator #(
    .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS),
    .JumpBits(JumpBits)
  ) u_point_v (
    .clk_i, .init_i(column_init_i), .advance_i(column_advance_i), .start_i(start), .step_i(step),
    .first_offset_i, .jump_i,
    .at_ref_i(v_at_ref_i), .per_major_i(v_per_major_i), .per_minor_i(v_per_minor_i),
    .start_value_o(v_first), .next_value_o(v_next), .value_o()
  );

  // The point issued: the span's first pixel in the column cycle, else the
  // accumulator one jump on (the value it is about to load).
  assign q_point = span_i ? q_first : q_next;
  assign u_point = span_i ? u_first : u_next;
  assign v_point = span_i ? v_first : v_next;

  logic point_depth;
  pixel_divide #(
    .OutBits(`CD_AFFINE_REF_BITS), .OutFrac(`CD_S_FRAC), .TagBits(1)
  ) u_pixel_divide (
    .clk_i, .rst_ni,
    .advance_i   (!hold_i),
    .valid_i     (start || step),
    .q_i         (q_point),
    .u_i         (u_point),
    .v_i         (v_point),
    .tag_i       (1'b0),
    .valid_o,
    .u_o,
    .v_o,
    .saturated_o,
    .depth_out_o (point_depth),
    .tag_o       ()
  );
  /* verilator lint_on PINCONNECTEMPTY */
  assign depth_out_o = valid_o && !hold_i && point_depth;

endmodule

`default_nettype wire
