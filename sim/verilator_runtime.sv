// One flip-flop, verilated only so that Verilator's CMake package compiles
// its runtime (verilated.cpp, the FST writer, threads) into cdsim with the
// flags it needs. Every unit cdsim simulates is verilated on first use into
// the RTL cache (sim/rtl_cache.cpp) and takes this runtime from cdsim.
`default_nettype none

module verilator_runtime (
  input  logic clk_i,
  input  logic d_i,
  output logic q_o
);
  always_ff @(posedge clk_i) q_o <= d_i;
endmodule

`default_nettype wire
