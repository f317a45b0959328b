// Plane accumulator: one plane value (q, U or V of divide; u or v of affine)
// at the current pixel, without a multiply per pixel. The column value
// (column offset o, minor offset 0) steps by per_major from column to column;
// a column's first pixel is the column value plus (first - minor_lo) per_minor
// (one multiply per column: start_value_o); each further pixel adds per_minor,
// or jump_i per_minor when JumpBits > 0 (affine-subN's end points, a short
// multiply). Exact: AccBits holds the plane's value anywhere in the box
// (derived_widths.cpp), so the value equals at_ref + o per_major + m per_minor
// (model: Plane::at and affine_pixel).
//
// Timing, in step with the column walker: init_i (the cycle before the first
// column) loads column 0; advance_i moves to the next column; start_i loads
// the column's first pixel; step_i moves to the next pixel of the column (or
// jump_i pixels on).
//
// HasPixel = 0 builds only the column value and start_value_o (Kim-style
// designs, which step their own state from a span's first pixel): no pixel
// register, value_o and next_value_o are 0 and step_i must stay 0.
`include "cd_widths.svh"
`default_nettype none

module plane_accumulator #(
  parameter int RefBits  = 32,
  parameter int StepBits = 32,
  parameter int AccBits  = 40,
  parameter int JumpBits = 0,
  parameter bit HasPixel = 1'b1
) (
  input  logic                       clk_i,
  input  logic                       init_i,
  input  logic                       advance_i,
  input  logic                       start_i,
  input  logic                       step_i,
  input  logic [`CD_PIXEL_BITS-1:0]  first_offset_i,  // first - minor_lo
  input  logic [(JumpBits > 0 ? JumpBits : 1)-1:0] jump_i,
  input  logic signed [RefBits-1:0]  at_ref_i,
  input  logic signed [StepBits-1:0] per_major_i,
  input  logic signed [StepBits-1:0] per_minor_i,
  output logic signed [AccBits-1:0]  start_value_o,   // what start_i loads (0 otherwise)
  output logic signed [AccBits-1:0]  next_value_o,    // what step_i loads
  output logic signed [AccBits-1:0]  value_o
);

  localparam int OffsetBits = `CD_PIXEL_BITS + 1;

  logic signed [AccBits-1:0] column, pixel, next;

  // Operand isolation: each multiply works only in the cycle that loads its result.
  always_comb begin
    start_value_o = '0;
    if (start_i)
      start_value_o = column + AccBits'(OffsetBits'($signed({1'b0, first_offset_i}))) * AccBits'(per_minor_i);
  end

  if (JumpBits > 0) begin : gen_jump
    always_comb begin
      next = '0;
      if (step_i) next = pixel + AccBits'($signed({1'b0, jump_i})) * AccBits'(per_minor_i);
    end
  end else begin : gen_step
    logic unused_jump;
    assign unused_jump = ^jump_i;
    assign next = pixel + AccBits'(per_minor_i);
  end

  always_ff @(posedge clk_i) begin
    if (init_i) column <= AccBits'(at_ref_i);
    else if (advance_i) column <= column + AccBits'(per_major_i);
  end

  if (HasPixel) begin : gen_pixel
    always_ff @(posedge clk_i) begin
      if (start_i) pixel <= start_value_o;
      else if (step_i) pixel <= next;
    end
    assign value_o = pixel;
    assign next_value_o = next;
  end else begin : gen_no_pixel
    logic unused_pixel;
    assign unused_pixel = ^{step_i, next};
    assign pixel = '0;
    assign value_o = '0;
    assign next_value_o = '0;
  end

endmodule

`default_nettype wire
