// Setup engine, its serial dividers (rtl/setup_engine.sv): started in stage C
// and read in stage D, div_cycles later (CD_SETUP_DIV_DONE). The slope g (the
// constant-depth designs only), and per edge its span end at the first column
// floor(N0 / |free|) and its step per column floor(|fixed| / |free|), with
// remainders. Twin of cdsim::setup_dividers (model/setup_engine.cpp). Edge i
// in bits i*W +: W.
`include "cd_widths.svh"
`default_nettype none

module setup_dividers #(
  parameter bit HasLines = 1'b1,
  localparam int SubpixelBits = `CD_SUBPIXEL_BITS,
  localparam int GFrac        = `CD_G_FRAC,
  localparam int DiffBits     = `CD_DIFF_BITS,
  localparam int CoefQBits    = `CD_COEF_Q_BITS,
  localparam int EdgeNBits    = `CD_EDGE_N_BITS,
  localparam int GDivQuoBits  = `CD_G_DIV_QUOTIENT_BITS,
  localparam int BoundDivQuoBits = `CD_BOUND_DIV_QUOTIENT_BITS,
  localparam int SlopeDivQuoBits = `CD_SLOPE_DIV_QUOTIENT_BITS,
  localparam int GDivNumBits  = CoefQBits + GFrac + 1,
  localparam int GDivDenBits  = CoefQBits,
  localparam int FreeBits     = DiffBits - 1,
  localparam int BoundNumBits = EdgeNBits - SubpixelBits
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic                         start_i,
  input  logic [GDivNumBits-1:0]       g_num_i,
  input  logic [GDivDenBits-1:0]       g_den_i,
  input  logic [3*BoundNumBits-1:0]    bound_num_i,
  input  logic [3*FreeBits-1:0]        free_i,
  input  logic [3*FreeBits-1:0]        fixed_i,
  output logic [GDivQuoBits-1:0]       g_quotient_o,
  output logic [GDivDenBits-1:0]       g_remainder_o,
  output logic                         g_overflow_o,
  output logic [3*BoundDivQuoBits-1:0] bound_quotient_o,
  output logic [3*FreeBits-1:0]        bound_remainder_o,
  output logic [3*SlopeDivQuoBits-1:0] slope_quotient_o,
  output logic [3*FreeBits-1:0]        slope_remainder_o,
  output logic [2:0]                   bound_overflow_o,
  output logic [2:0]                   slope_overflow_o
);

  localparam int DivBitsPerCycle = `CD_DIV_BITS_PER_CYCLE;

  if (HasLines) begin : gen_g_divider
    serial_divider #(
      .NumBits(GDivNumBits), .DenBits(GDivDenBits), .QuoBits(GDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_g_divider (
      .clk_i, .rst_ni,
      .start_i,
      .numerator_i  (g_num_i),
      .denominator_i(g_den_i),
      .quotient_o   (g_quotient_o),
      .remainder_o  (g_remainder_o),
      .overflow_o   (g_overflow_o)
    );
  end else begin : gen_no_g_divider
    logic unused_g_operands;
    assign unused_g_operands = ^{g_num_i, g_den_i};
    assign g_quotient_o = '0;
    assign g_remainder_o = '0;
    assign g_overflow_o = 1'b0;
  end

  for (genvar i = 0; i < 3; i++) begin : gen_edge_dividers
    serial_divider #(
      .NumBits(BoundNumBits), .DenBits(FreeBits), .QuoBits(BoundDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_bound_divider (
      .clk_i, .rst_ni,
      .start_i,
      .numerator_i  (bound_num_i[BoundNumBits*i +: BoundNumBits]),
      .denominator_i(free_i[FreeBits*i +: FreeBits]),
      .quotient_o   (bound_quotient_o[BoundDivQuoBits*i +: BoundDivQuoBits]),
      .remainder_o  (bound_remainder_o[FreeBits*i +: FreeBits]),
      .overflow_o   (bound_overflow_o[i])
    );
    serial_divider #(
      .NumBits(FreeBits), .DenBits(FreeBits), .QuoBits(SlopeDivQuoBits),
      .BitsPerCycle(DivBitsPerCycle)
    ) u_slope_divider (
      .clk_i, .rst_ni,
      .start_i,
      .numerator_i  (fixed_i[FreeBits*i +: FreeBits]),
      .denominator_i(free_i[FreeBits*i +: FreeBits]),
      .quotient_o   (slope_quotient_o[SlopeDivQuoBits*i +: SlopeDivQuoBits]),
      .remainder_o  (slope_remainder_o[FreeBits*i +: FreeBits]),
      .overflow_o   (slope_overflow_o[i])
    );
  end

endmodule

`default_nettype wire
