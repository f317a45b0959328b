// Per-pixel perspective divide: u = U / q and v = V / q at one pixel per
// cycle, by the pipelined reciprocal and two multiplies. Twin of divide_uv
// (model/divide_datapath.cpp, cdsim::quotient): R = reciprocal(q); U and V
// narrowed by e at issue to OutFrac + guard fraction bits and one integer bit
// more than OutBits (round to nearest, saturate); their products with R read
// with RecipBits + OutFrac + guard fraction bits, rounded to nearest and
// saturated to OutBits with OutFrac fraction bits (the output format for
// divide; the affine accumulator's format for the end points of affine-subN).
//
// Latency CD_RECIP_LATENCY advancing cycles; advance_i = 0 (a stall) holds
// every stage and the output. tag_o travels with the pixel.
`include "cd_widths.svh"
`default_nettype none

module pixel_divide #(
  parameter int OutBits = `CD_OUT_BITS,
  parameter int OutFrac = `CD_OUT_FRAC,
  parameter int TagBits = 1
) (
  input  logic                                clk_i,
  input  logic                                rst_ni,
  input  logic                                advance_i,
  input  logic                                valid_i,
  input  logic signed [`CD_PIXEL_Q_BITS-1:0]  q_i,
  input  logic signed [`CD_PIXEL_UV_BITS-1:0] u_i,
  input  logic signed [`CD_PIXEL_UV_BITS-1:0] v_i,
  input  logic [TagBits-1:0]                  tag_i,
  output logic                                valid_o,
  output logic signed [OutBits-1:0]           u_o,
  output logic signed [OutBits-1:0]           v_o,
  output logic                                saturated_o,
  output logic                                depth_out_o,  // q <= 0: replaced by the smallest q
  output logic [TagBits-1:0]                  tag_o
);

  localparam int QBits        = `CD_PIXEL_Q_BITS;
  localparam int UvBits       = `CD_PIXEL_UV_BITS;
  localparam int RecipBits    = `CD_RECIP_BITS;
  localparam int UvInFrac     = `CD_UV_IN_FRAC;
  localparam int ExponentBits = `CD_EXPONENT_BITS;
  localparam int Guard        = `CD_QUOTIENT_GUARD_BITS;
  localparam int OperandBits  = OutBits + 1 + Guard;
  localparam int OperandFrac  = OutFrac + Guard;
  localparam int ProductBits  = OperandBits + RecipBits + 2;
  localparam int ShiftBits    = 10;  // e + uv_in_frac - out_frac - guard lies in (-64, 256)
  localparam int MaxLeft      = OperandFrac > UvInFrac ? OperandFrac - UvInFrac : 0;  // at e = 0
  localparam logic signed [ShiftBits-1:0] QuotientShift = ShiftBits'(RecipBits + Guard);
  localparam int PipeTagBits  = TagBits + 1 + 2 * OperandBits + 1;

  logic                    depth_out;
  logic [ExponentBits-1:0] exponent;
  logic [RecipBits:0]      mantissa, recip;
  logic [PipeTagBits-1:0]  issue_tag, result_tag;
  logic                    result_valid;
  logic signed [ShiftBits-1:0]   issue_shift;
  logic signed [OperandBits-1:0] issue_u, issue_v;
  logic [1:0]                    issue_saturated;

  reciprocal_operand #(
    .QBits(QBits), .RecipBits(RecipBits), .ExponentBits(ExponentBits)
  ) u_operand (
    .enable_i   (valid_i),
    .q_i,
    .depth_out_o(depth_out),
    .exponent_o (exponent),
    .mantissa_o (mantissa)
  );
  assign issue_shift = ShiftBits'($signed({1'b0, exponent})) + ShiftBits'(UvInFrac - OperandFrac);
  shift_round #(.InBits(UvBits), .OutBits(OperandBits), .ShiftBits(ShiftBits), .MaxLeft(MaxLeft))
    u_operand_u (.enable_i(valid_i), .in_i(u_i), .shift_i(issue_shift), .out_o(issue_u), .saturated_o(issue_saturated[0]));
  shift_round #(.InBits(UvBits), .OutBits(OperandBits), .ShiftBits(ShiftBits), .MaxLeft(MaxLeft))
    u_operand_v (.enable_i(valid_i), .in_i(v_i), .shift_i(issue_shift), .out_o(issue_v), .saturated_o(issue_saturated[1]));
  assign issue_tag = valid_i ? {tag_i, depth_out, issue_u, issue_v, |issue_saturated} : '0;

  reciprocal #(
    .RecipBits(RecipBits), .Latency(`CD_RECIP_LATENCY), .TagBits(PipeTagBits)
  ) u_reciprocal (
    .clk_i, .rst_ni,
    .advance_i,
    .valid_i,
    .mantissa_i(mantissa),
    .tag_i     (issue_tag),
    .valid_o   (result_valid),
    .recip_o   (recip),
    .tag_o     (result_tag)
  );

  logic signed [OperandBits-1:0] result_u, result_v;
  logic                          operand_saturated;
  logic signed [ProductBits-1:0] product_u, product_v;
  logic [1:0]                    saturated;

  always_comb begin
    tag_o = '0;
    depth_out_o = 1'b0;
    result_u = '0;
    result_v = '0;
    operand_saturated = 1'b0;
    product_u = '0;
    product_v = '0;
    if (result_valid) begin
      {tag_o, depth_out_o, result_u, result_v, operand_saturated} = result_tag;
      product_u = ProductBits'(result_u) * ProductBits'($signed({1'b0, recip}));
      product_v = ProductBits'(result_v) * ProductBits'($signed({1'b0, recip}));
    end
  end

  shift_round #(.InBits(ProductBits), .OutBits(OutBits), .ShiftBits(ShiftBits))
    u_narrow_u (.enable_i(result_valid), .in_i(product_u), .shift_i(QuotientShift), .out_o(u_o), .saturated_o(saturated[0]));
  shift_round #(.InBits(ProductBits), .OutBits(OutBits), .ShiftBits(ShiftBits))
    u_narrow_v (.enable_i(result_valid), .in_i(product_v), .shift_i(QuotientShift), .out_o(v_o), .saturated_o(saturated[1]));

  assign valid_o = result_valid;
  assign saturated_o = |saturated || operand_saturated;

endmodule

`default_nettype wire
