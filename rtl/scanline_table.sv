// Scanline table SRAM: one word (T.u, T.v, S.u, S.v and two flags) per
// constant-depth line of the current band, addressed by line - band base.
// Split into an even and an odd bank by address, so that a pixel's line and
// its correction neighbour (address +- 1) come from different banks in the
// same cycle. Reads are synchronous: data appears the cycle after the address.
// Writes (the fill) and reads (the walk) share a cycle only with early_walk,
// and then never an address: a read goes only to lines written in earlier
// cycles. Each bank is single-port without early_walk, two-port (one read,
// one write port) with it.
`include "cd_widths.svh"
`default_nettype none

module scanline_table #(
  parameter int Depth    = `CD_TABLE_DEPTH,
  parameter int WordBits = 64,
  localparam int AddrBits = $clog2(Depth),
  localparam int BankDepth = (Depth + 1) / 2
) (
  input  logic                clk_i,
  input  logic                write_i,
  input  logic [AddrBits-1:0] write_addr_i,
  input  logic [WordBits-1:0] write_entry_i,
  // Read of a pixel's own line, and of its neighbour (which lies in the other bank).
  input  logic                read_i,
  input  logic [AddrBits-1:0] own_addr_i,
  input  logic                neighbour_read_i,
  input  logic [AddrBits-1:0] neighbour_addr_i,
  output logic [WordBits-1:0] own_entry_o,
  output logic [WordBits-1:0] neighbour_entry_o
);

  localparam int RowBits = AddrBits > 1 ? AddrBits - 1 : 1;

  logic [WordBits-1:0] even_bank [BankDepth];
  logic [WordBits-1:0] odd_bank [BankDepth];
  logic [WordBits-1:0] even_data_q, odd_data_q;
  logic                own_is_odd_q;

  logic                even_read, odd_read;
  logic [RowBits-1:0]  even_row, odd_row, write_row;

  always_comb begin
    write_row = RowBits'(write_addr_i >> 1);
    even_read = 1'b0;
    odd_read = 1'b0;
    even_row = '0;
    odd_row = '0;
    if (read_i) begin
      if (own_addr_i[0]) begin
        odd_read = 1'b1;
        odd_row = RowBits'(own_addr_i >> 1);
      end else begin
        even_read = 1'b1;
        even_row = RowBits'(own_addr_i >> 1);
      end
      if (neighbour_read_i) begin
        if (neighbour_addr_i[0]) begin
          odd_read = 1'b1;
          odd_row = RowBits'(neighbour_addr_i >> 1);
        end else begin
          even_read = 1'b1;
          even_row = RowBits'(neighbour_addr_i >> 1);
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (write_i && !write_addr_i[0]) even_bank[write_row] <= write_entry_i;
    if (even_read) even_data_q <= even_bank[even_row];
  end

  always_ff @(posedge clk_i) begin
    if (write_i && write_addr_i[0]) odd_bank[write_row] <= write_entry_i;
    if (odd_read) odd_data_q <= odd_bank[odd_row];
  end

  always_ff @(posedge clk_i) begin
    if (read_i) own_is_odd_q <= own_addr_i[0];
  end

  assign own_entry_o = own_is_odd_q ? odd_data_q : even_data_q;
  assign neighbour_entry_o = own_is_odd_q ? even_data_q : odd_data_q;

endmodule
`default_nettype wire
