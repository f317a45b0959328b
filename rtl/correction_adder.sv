// Correction adder: u_line = T_k + o S_k for the pixel's line and, with a
// usable neighbour, the paper's linear correction
// u = u_line(k) + round(weight (u_line(k') - u_line(k)) 2^-d_frac), then
// rounding and saturation to the output format. Twin of
// model/correction_adder.cpp and of line_value in model/column_walker.hpp.
// Combinational; evaluated only while valid_i.
`include "cd_widths.svh"

module correction_adder #(
  parameter int TInt     = `CD_T_INT,
  parameter int TFrac    = `CD_T_FRAC,
  parameter int SInt     = `CD_S_INT,
  parameter int SFrac    = `CD_S_FRAC,
  parameter int DFrac    = `CD_D_FRAC,
  parameter int OutInt   = `CD_OUT_INT,
  parameter int OutFrac  = `CD_OUT_FRAC,
  localparam int TBits   = TInt + TFrac,
  localparam int SBits   = SInt + SFrac,
  localparam int WordBits = 2 * TBits + 2 * SBits + 2,
  localparam int OutBits = OutInt + OutFrac
) (
  input  logic                valid_i,
  input  logic [WordBits-1:0] own_entry_i,
  input  logic [WordBits-1:0] neighbour_entry_i,
  // Correction wanted: a design with correction and a pixel off its line.
  input  logic                correct_i,
  input  logic [31:0]         offset_i,
  input  logic [31:0]         weight_i,
  output logic [OutBits-1:0]  u_o,
  output logic [OutBits-1:0]  v_o,
  output logic [7:0]          flags_o
);

  `include "cd_arith.svh"

  localparam int Frac = TFrac > SFrac ? TFrac : SFrac;
  localparam logic [7:0] FlagOutputSaturated  = 8'h02;
  localparam logic [7:0] FlagNeighbourDropped = 8'h10;

  // u_line and v_line of one entry at column offset o, Frac fraction bits. The
  // model's walker accumulator is 64 bits (widths.cpp validate() keeps it within
  // 63), and so is this one.
  function automatic logic signed [63:0] line_u(input logic [WordBits-1:0] entry,
                                                input logic [31:0] offset);
    logic signed [63:0] t;
    logic signed [63:0] s;
    begin
      t = $signed({{(64 - TBits){entry[TBits-1]}}, entry[TBits-1:0]});
      s = $signed({{(64 - SBits){entry[2*TBits+SBits-1]}}, entry[2*TBits +: SBits]});
      line_u = (t <<< (Frac - TFrac)) + $signed({32'd0, offset}) * (s <<< (Frac - SFrac));
    end
  endfunction

  function automatic logic signed [63:0] line_v(input logic [WordBits-1:0] entry,
                                                input logic [31:0] offset);
    logic signed [63:0] t;
    logic signed [63:0] s;
    begin
      t = $signed({{(64 - TBits){entry[2*TBits-1]}}, entry[TBits +: TBits]});
      s = $signed({{(64 - SBits){entry[2*TBits+2*SBits-1]}}, entry[2*TBits+SBits +: SBits]});
      line_v = (t <<< (Frac - TFrac)) + $signed({32'd0, offset}) * (s <<< (Frac - SFrac));
    end
  endfunction

  // own + round(weight (other - own) 2^-d_frac): the product is exact (128 bits),
  // the sum is 64 bits like the model's.
  function automatic logic signed [63:0] corrected(input logic signed [63:0] own,
                                                   input logic signed [63:0] other,
                                                   input logic [31:0] weight);
    logic signed [127:0] product;
    begin
      product = $signed({96'd0, weight}) * ($signed({{64{other[63]}}, other}) -
                                            $signed({{64{own[63]}}, own}));
      corrected = own + 64'(cd_shift_round(product, 32'(DFrac), 1'b1));
    end
  endfunction

  // To the output format: round to nearest (ties up), saturate, flag; in 64
  // bits as the model does (fx::narrow_nearest_saturate).
  function automatic logic signed [63:0] narrow_out(input logic signed [63:0] x);
    logic signed [63:0] y;
    begin
      if (Frac - OutFrac > 0) y = (x + (64'sd1 <<< (Frac - OutFrac - 1))) >>> (Frac - OutFrac);
      else y = x <<< (OutFrac - Frac);
      narrow_out = y;
    end
  endfunction

  localparam logic signed [63:0] OutMax = (64'sd1 <<< (OutBits - 1)) - 64'sd1;
  localparam logic signed [63:0] OutMin = -(64'sd1 <<< (OutBits - 1));

  logic               neighbour_usable;
  logic [1:0]         neighbour_flags;
  logic signed [63:0] own_u, own_v, sum_u, sum_v, narrowed_u, narrowed_v;

  always_comb begin
    u_o = '0;
    v_o = '0;
    flags_o = '0;
    {own_u, own_v, sum_u, sum_v, narrowed_u, narrowed_v} = '0;
    neighbour_usable = 1'b0;
    neighbour_flags = neighbour_entry_i[WordBits-1 -: 2];
    if (valid_i) begin
      // The entry's own flags: bit 0 table_saturated, bit 2 depth_range.
      flags_o = {5'd0, own_entry_i[WordBits-1], 1'b0, own_entry_i[WordBits-2]};
      // A flagged neighbour is never used: it would spread a bad value.
      neighbour_usable = correct_i && neighbour_flags == 2'b00;
      if (correct_i && !neighbour_usable) flags_o = flags_o | FlagNeighbourDropped;
      own_u = line_u(own_entry_i, offset_i);
      own_v = line_v(own_entry_i, offset_i);
      sum_u = own_u;
      sum_v = own_v;
      if (neighbour_usable) begin
        sum_u = corrected(own_u, line_u(neighbour_entry_i, offset_i), weight_i);
        sum_v = corrected(own_v, line_v(neighbour_entry_i, offset_i), weight_i);
      end
      narrowed_u = narrow_out(sum_u);
      narrowed_v = narrow_out(sum_v);
      if (narrowed_u > OutMax || narrowed_u < OutMin) flags_o = flags_o | FlagOutputSaturated;
      if (narrowed_v > OutMax || narrowed_v < OutMin) flags_o = flags_o | FlagOutputSaturated;
      u_o = OutBits'(narrowed_u > OutMax ? OutMax : (narrowed_u < OutMin ? OutMin : narrowed_u));
      v_o = OutBits'(narrowed_v > OutMax ? OutMax : (narrowed_v < OutMin ? OutMin : narrowed_v));
    end
  end

endmodule
