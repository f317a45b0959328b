// The reciprocal unit's operand: q as a normalised mantissa and an exponent.
// q <= 0 raises depth_out_o and is replaced by q = 1; e = bitlen(q) - 1; the
// mantissa keeps RecipBits fraction bits below its leading one, truncated
// (2^RecipBits <= mantissa_o < 2^(RecipBits+1)). Twin of the first half of
// cdsim::reciprocal (model/setup_engine.cpp). Combinational; 0 while enable_i
// is low (operand isolation).
`default_nettype none

module reciprocal_operand #(
  parameter int QBits        = 40,
  parameter int RecipBits    = 24,
  parameter int ExponentBits = 6
) (
  input  logic                    enable_i,
  input  logic signed [QBits-1:0] q_i,
  output logic                    depth_out_o,
  output logic [ExponentBits-1:0] exponent_o,
  output logic [RecipBits:0]      mantissa_o
);

  logic signed [QBits-1:0] q_positive;

  always_comb begin
    depth_out_o = 1'b0;
    q_positive = '0;
    exponent_o = '0;
    mantissa_o = '0;
    if (enable_i) begin
      depth_out_o = q_i <= 0;
      q_positive = depth_out_o ? QBits'(1) : q_i;
      for (int i = 0; i < QBits - 1; i++) if (q_positive[i]) exponent_o = ExponentBits'(i);
      if (32'(exponent_o) >= RecipBits)
        mantissa_o = (RecipBits+1)'(q_positive >> (exponent_o - ExponentBits'(RecipBits)));
      else
        mantissa_o = (RecipBits+1)'(q_positive << (ExponentBits'(RecipBits) - exponent_o));
    end
  end

endmodule

`default_nettype wire
