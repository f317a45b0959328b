// One stage of a triangle's context on its way from the setup engine to the
// walker (cd_scan_unit.sv, "Front and back"): a register loaded as the
// triangle moves on when Present, a wire when the stage does not exist
// (setup_fifo_depth below its level), so that the consumer reads the stage
// before it.
`default_nettype none

module context_register #(
  parameter int Bits = 1,
  parameter bit Present = 1'b1
) (
  input  logic            clk_i,
  input  logic            load_i,
  input  logic [Bits-1:0] d_i,
  output logic [Bits-1:0] q_o
);

  if (Present) begin : gen_register
    logic [Bits-1:0] q;
    always_ff @(posedge clk_i) begin
      if (load_i) q <= d_i;
    end
    assign q_o = q;
  end else begin : gen_wire
    logic unused_clock_load;
    assign unused_clock_load = ^{clk_i, load_i};
    assign q_o = d_i;
  end

endmodule

`default_nettype wire
