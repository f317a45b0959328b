// Correction adder: u_line = T_k + o S_k for the pixel's line and, with a
// usable neighbour, the paper's linear correction
// u = u_line(k) + round(weight (u_line(k') - u_line(k)) 2^-d_frac), then
// rounding and saturation to the output format. Twin of
// model/correction_adder.hpp and of line_value in model/column_walker.hpp, at
// the widths of model/derived_widths.cpp. Combinational; evaluated only while
// valid_i.
`include "cd_widths.svh"
`default_nettype none

module correction_adder #(
  parameter bit HasCorrection = 1'b1  // 0: no correction hardware (designs without it)
) (
  input  logic                          valid_i,
  input  logic [`CD_WORD_BITS-1:0]      own_entry_i,
  input  logic [`CD_WORD_BITS-1:0]      neighbour_entry_i,
  // Correction wanted: a design with correction and a pixel off its line.
  input  logic                          correct_i,
  input  logic [`CD_PIXEL_BITS-1:0]     offset_i,
  input  logic [`CD_WEIGHT_BITS-1:0]    weight_i,
  output logic signed [`CD_OUT_BITS-1:0] u_o,
  output logic signed [`CD_OUT_BITS-1:0] v_o,
  output logic [7:0]                    flags_o
);

  localparam int TBits      = `CD_T_BITS;
  localparam int SBits      = `CD_S_BITS;
  localparam int TFrac      = `CD_T_FRAC;
  localparam int SFrac      = `CD_S_FRAC;
  localparam int DFrac      = `CD_D_FRAC;
  localparam int OutFrac    = `CD_OUT_FRAC;
  localparam int OutBits    = `CD_OUT_BITS;
  localparam int PixelBits  = `CD_PIXEL_BITS;
  localparam int WeightBits = `CD_WEIGHT_BITS;
  localparam int Frac       = `CD_LINE_VALUE_FRAC;
  localparam int ValueBits  = `CD_LINE_VALUE_BITS;
  localparam int SumBits    = `CD_CORRECTED_BITS;
  localparam int ProductBits = WeightBits + ValueBits + 2;
  localparam int OutShift   = Frac - OutFrac;
  localparam int OutLeft    = OutShift < 0 ? -OutShift : 0;

  // u_line or v_line of one entry at column offset o, Frac fraction bits.
  function automatic logic signed [ValueBits-1:0] line_value(input logic signed [TBits-1:0] t,
                                                             input logic signed [SBits-1:0] s,
                                                             input logic [PixelBits-1:0] offset);
    line_value = (ValueBits'(t) <<< (Frac - TFrac)) +
                 ValueBits'($signed({1'b0, offset})) * (ValueBits'(s) <<< (Frac - SFrac));
  endfunction

  // own + round(weight (other - own) 2^-d_frac), ties toward +inf.
  function automatic logic signed [SumBits-1:0] corrected(input logic signed [ValueBits-1:0] own,
                                                          input logic signed [ValueBits-1:0] other,
                                                          input logic [WeightBits-1:0] weight);
    logic signed [ProductBits-1:0] product;
    begin
      product = ProductBits'($signed({1'b0, weight})) * (ProductBits'(other) - ProductBits'(own));
      product = (product + ProductBits'(1 <<< (DFrac - 1))) >>> DFrac;
      corrected = SumBits'(own) + SumBits'(product);
    end
  endfunction

  logic signed [ValueBits-1:0] own_u, own_v, other_u, other_v;
  logic signed [SumBits-1:0]   sum_u, sum_v;
  logic                        neighbour_usable;
  logic                        saturated_u, saturated_v;

  always_comb begin
    own_u = '0;
    own_v = '0;
    other_u = '0;
    other_v = '0;
    neighbour_usable = 1'b0;
    sum_u = '0;
    sum_v = '0;
    if (valid_i) begin
      own_u = line_value(own_entry_i[`CD_WORD_TU_LSB +: TBits], own_entry_i[`CD_WORD_SU_LSB +: SBits], offset_i);
      own_v = line_value(own_entry_i[`CD_WORD_TV_LSB +: TBits], own_entry_i[`CD_WORD_SV_LSB +: SBits], offset_i);
      other_u = line_value(neighbour_entry_i[`CD_WORD_TU_LSB +: TBits],
                           neighbour_entry_i[`CD_WORD_SU_LSB +: SBits], offset_i);
      other_v = line_value(neighbour_entry_i[`CD_WORD_TV_LSB +: TBits],
                           neighbour_entry_i[`CD_WORD_SV_LSB +: SBits], offset_i);
      // A flagged neighbour is never used: it would spread a bad value.
      neighbour_usable = HasCorrection && correct_i && !neighbour_entry_i[`CD_WORD_SATURATED_BIT] &&
                         !neighbour_entry_i[`CD_WORD_DEPTH_RANGE_BIT];
      sum_u = SumBits'(own_u);
      sum_v = SumBits'(own_v);
      if (neighbour_usable) begin
        sum_u = corrected(own_u, other_u, weight_i);
        sum_v = corrected(own_v, other_v, weight_i);
      end
    end
  end

  // To the output format: round to nearest (ties up), saturate, flag.
  shift_round #(.InBits(SumBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(OutLeft))
    u_narrow_u (.enable_i(valid_i), .in_i(sum_u), .shift_i(8'(OutShift)), .out_o(u_o), .saturated_o(saturated_u));
  shift_round #(.InBits(SumBits), .OutBits(OutBits), .ShiftBits(8), .MaxLeft(OutLeft))
    u_narrow_v (.enable_i(valid_i), .in_i(sum_v), .shift_i(8'(OutShift)), .out_o(v_o), .saturated_o(saturated_v));

  always_comb begin
    flags_o = '0;
    if (valid_i) begin
      flags_o[`CD_FLAG_TABLE_SATURATED] = own_entry_i[`CD_WORD_SATURATED_BIT];
      flags_o[`CD_FLAG_DEPTH_RANGE] = own_entry_i[`CD_WORD_DEPTH_RANGE_BIT];
      flags_o[`CD_FLAG_NEIGHBOUR_DROPPED] = HasCorrection && correct_i && !neighbour_usable;
      flags_o[`CD_FLAG_OUTPUT_SATURATED] = saturated_u || saturated_v;
    end
  end

endmodule

`default_nettype wire
