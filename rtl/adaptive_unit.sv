// The adaptive design (Kamen & Shirman; docs/designs.md, "adaptive") as one
// unit: the split engine (adaptive_split.sv) in front of an affine-only scan
// unit (cd_scan_unit.sv) at the leaves' widths, with the ports of
// cd_scan_unit, so that the same bench drives it. Twin of
// ScanUnit::run_adaptive (model/scan_unit.cpp):
// - cd_widths.svh is the leaf unit's (adaptive_leaf_widths: subpixel_bits +
//   adapt_depth, uv_in_frac + adapt_uv_extra); the triangle at the input has
//   adapt_depth fewer subpixel bits and adapt_uv_extra fewer u, v bits.
// - Each leaf goes to the unit as a triangle of its own. Its fragments pass
//   through; its record is absorbed here: pixels summed, flags or-ed.
// - A triangle's record comes in the cycle its last leaf's record does, or in
//   the cycle the split engine reports the triangle done (tri_done_o, after
//   dropping empty sub-triangles that followed the last leaf), whichever is
//   later. Its cycles count from the cycle after the last record (the first
//   triangle: from its acceptance), as the unit's own records do.
// - A fragment offered and not taken holds the split engine as it holds the
//   unit: a stall delays everything by one cycle.
// lines and bands are 0 (no table); the observation ports are idle.
`include "cd_widths.svh"
`default_nettype none

module adaptive_unit #(
  parameter bit HasObservation = 1'b1  // the unit's; nothing is observed here
) (
  input  logic        clk_i,
  input  logic        rst_ni,

  input  logic        tri_valid_i,
  output logic        tri_ready_o,
  /* verilator lint_off UNUSEDSIGNAL */  // the bits above the input formats (sign extension)
  input  logic [31:0] tri_x0_i,
  input  logic [31:0] tri_y0_i,
  input  logic [31:0] tri_q0_i,
  input  logic [31:0] tri_u0_i,
  input  logic [31:0] tri_v0_i,
  input  logic [31:0] tri_x1_i,
  input  logic [31:0] tri_y1_i,
  input  logic [31:0] tri_q1_i,
  input  logic [31:0] tri_u1_i,
  input  logic [31:0] tri_v1_i,
  input  logic [31:0] tri_x2_i,
  input  logic [31:0] tri_y2_i,
  input  logic [31:0] tri_q2_i,
  input  logic [31:0] tri_u2_i,
  input  logic [31:0] tri_v2_i,
  // 1 .. 8192: bits 15:14 are always 0
  input  logic [15:0] viewport_width_i,
  input  logic [15:0] viewport_height_i,
  // The design select of cd_scan_unit: this unit has one design.
  input  logic [`CD_KIND_BITS-1:0] kind_i,
  input  logic [2:0]  segment_log2_i,
  input  logic        kim_pipelined_i,
  input  logic [1:0]  density_log2_i,
  input  logic        correction_i,
  input  logic        persp_i,
  input  logic        quadratic_i,
  input  logic        fallback_i,
  /* verilator lint_on UNUSEDSIGNAL */

  output logic        frag_valid_o,
  input  logic        frag_ready_i,
  output logic [15:0] frag_x_o,
  output logic [15:0] frag_y_o,
  output logic [63:0] frag_u_o,
  output logic [63:0] frag_v_o,
  output logic [7:0]  frag_flags_o,

  output logic        rec_valid_o,
  input  logic        rec_ready_i,
  output logic [63:0] rec_cycles_o,
  output logic [31:0] rec_lines_o,
  output logic [31:0] rec_bands_o,
  output logic [31:0] rec_pixels_o,
  output logic [7:0]  rec_flags_o,

  output logic        obs_setup_valid_o,
  output logic [7:0]  obs_setup_bits_o,
  output logic [31:0] obs_setup_g_o,
  output logic [63:0] obs_setup_box_o,
  output logic [63:0] obs_setup_lines_o,
  output logic        obs_write_valid_o,
  output logic [31:0] obs_write_addr_o,
  output logic [63:0] obs_write_tu_o,
  output logic [63:0] obs_write_tv_o,
  output logic [63:0] obs_write_su_o,
  output logic [63:0] obs_write_sv_o,
  output logic [63:0] obs_write_eps_o,
  output logic [2:0]  obs_write_flags_o
);

  localparam int Depth         = `CD_ADAPT_DEPTH;
  localparam int UvExtra       = `CD_ADAPT_UV_EXTRA;
  localparam int SubpixelBits  = `CD_SUBPIXEL_BITS - Depth;   // the input's
  localparam int UvInFrac      = `CD_UV_IN_FRAC - UvExtra;    // the input's
  localparam int CoordBits     = 16 + SubpixelBits;
  localparam int UvBits        = 16 + UvInFrac;
  localparam int LeafCoordBits = CoordBits + Depth;
  localparam int LeafUvBits    = UvBits + UvExtra;
  localparam int CountBits     = `CD_CYCLE_COUNT_BITS;
  localparam int LeafCountBits = 2 * Depth + 2;               // at most 4^Depth leaves
  // Triangles done by the split engine and not yet recorded: each but the
  // oldest has a leaf in the unit, which holds at most three (setup, fill
  // stage, back end) and one whose record is being delivered.
  localparam int DoneDepth     = 8;
  localparam int DoneBits      = $clog2(DoneDepth);

  // ------------------------------------------------------------ split engine
  logic                       hold;
  logic                       leaf_valid, leaf_ready;
  logic [3*LeafCoordBits-1:0] leaf_x, leaf_y;
  logic [95:0]                leaf_q;
  logic [3*LeafUvBits-1:0]    leaf_u, leaf_v;
  logic                       split_done;
  logic [1:0]                 split_flags;

  // The viewport of the triangle the split engine holds: the source may
  // already offer the next one, with its own.
  logic [15:0] viewport_width_q, viewport_height_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      viewport_width_q <= '0;
      viewport_height_q <= '0;
    end else if (tri_valid_i && tri_ready_o) begin
      viewport_width_q <= viewport_width_i;
      viewport_height_q <= viewport_height_i;
    end
  end

  adaptive_split #(
    .SubpixelBits (SubpixelBits),
    .UvInFrac     (UvInFrac),
    .QBits        (`CD_Q_BITS),
    .RecipBits    (`CD_RECIP_BITS),
    .RecipLatency (`CD_RECIP_LATENCY),
    .Depth        (Depth),
    .BoundFrac    (`CD_ADAPT_BOUND_FRAC),
    .UvExtra      (UvExtra),
    .GuardBits    (`CD_QUOTIENT_GUARD_BITS)
  ) u_split (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .hold_i            (hold),
    .viewport_width_i  (viewport_width_q[13:0]),
    .viewport_height_i (viewport_height_q[13:0]),
    .tri_valid_i       (tri_valid_i),
    .tri_ready_o       (tri_ready_o),
    .tri_x_i           ({tri_x2_i[CoordBits-1:0], tri_x1_i[CoordBits-1:0], tri_x0_i[CoordBits-1:0]}),
    .tri_y_i           ({tri_y2_i[CoordBits-1:0], tri_y1_i[CoordBits-1:0], tri_y0_i[CoordBits-1:0]}),
    .tri_q_i           ({tri_q2_i, tri_q1_i, tri_q0_i}),
    .tri_u_i           ({tri_u2_i[UvBits-1:0], tri_u1_i[UvBits-1:0], tri_u0_i[UvBits-1:0]}),
    .tri_v_i           ({tri_v2_i[UvBits-1:0], tri_v1_i[UvBits-1:0], tri_v0_i[UvBits-1:0]}),
    .leaf_valid_o      (leaf_valid),
    .leaf_ready_i      (leaf_ready),
    .leaf_x_o          (leaf_x),
    .leaf_y_o          (leaf_y),
    .leaf_q_o          (leaf_q),
    .leaf_u_o          (leaf_u),
    .leaf_v_o          (leaf_v),
    /* verilator lint_off PINCONNECTEMPTY */
    .leaf_depth_o      (),
    /* verilator lint_on PINCONNECTEMPTY */
    .tri_done_o        (split_done),
    .tri_flags_o       (split_flags)
  );

  // -------------------------------------------------------------- leaf unit
  // Vertex k of a leaf field, sign-extended to the unit's 32-bit input.
  function automatic logic [31:0] coord(input logic [3*LeafCoordBits-1:0] field, input int k);
    coord = 32'($signed(field[k*LeafCoordBits +: LeafCoordBits]));
  endfunction
  function automatic logic [31:0] texel(input logic [3*LeafUvBits-1:0] field, input int k);
    texel = 32'($signed(field[k*LeafUvBits +: LeafUvBits]));
  endfunction

  logic        unit_rec_valid, unit_rec_ready;
  logic [31:0] unit_rec_pixels;
  logic [7:0]  unit_rec_flags;
  /* verilator lint_off UNUSEDSIGNAL */  // the unit's own cycle counts and its idle table counts
  logic [63:0] unit_rec_cycles;
  logic [31:0] unit_rec_lines, unit_rec_bands;
  /* verilator lint_on UNUSEDSIGNAL */

  cd_scan_unit #(
    .MaxDensityLog2 (0),
    .HasCorrection  (1'b0),
    .HasPersp       (1'b0),
    .HasTable       (1'b0),
    .HasDivide      (1'b0),
    .HasAffine      (1'b1),
    .HasAffineSub   (1'b0),
    .HasQuadSub     (1'b0),
    .HasKimIter     (1'b0),
    .HasKimPipe     (1'b0),
    .HasObservation (1'b0)
  ) u_unit (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .tri_valid_i       (leaf_valid),
    .tri_ready_o       (leaf_ready),
    .tri_x0_i          (coord(leaf_x, 0)),
    .tri_y0_i          (coord(leaf_y, 0)),
    .tri_q0_i          (leaf_q[31:0]),
    .tri_u0_i          (texel(leaf_u, 0)),
    .tri_v0_i          (texel(leaf_v, 0)),
    .tri_x1_i          (coord(leaf_x, 1)),
    .tri_y1_i          (coord(leaf_y, 1)),
    .tri_q1_i          (leaf_q[63:32]),
    .tri_u1_i          (texel(leaf_u, 1)),
    .tri_v1_i          (texel(leaf_v, 1)),
    .tri_x2_i          (coord(leaf_x, 2)),
    .tri_y2_i          (coord(leaf_y, 2)),
    .tri_q2_i          (leaf_q[95:64]),
    .tri_u2_i          (texel(leaf_u, 2)),
    .tri_v2_i          (texel(leaf_v, 2)),
    .viewport_width_i  (viewport_width_q),
    .viewport_height_i (viewport_height_q),
    .kind_i            (`CD_KIND_BITS'(`CD_KIND_AFFINE)),
    .segment_log2_i    (3'd0),
    .kim_pipelined_i   (1'b0),
    .density_log2_i    (2'd0),
    .correction_i      (1'b0),
    .persp_i           (1'b0),
    .quadratic_i       (1'b0),
    .fallback_i        (1'b0),
    .frag_valid_o      (frag_valid_o),
    .frag_ready_i      (frag_ready_i),
    .frag_x_o          (frag_x_o),
    .frag_y_o          (frag_y_o),
    .frag_u_o          (frag_u_o),
    .frag_v_o          (frag_v_o),
    .frag_flags_o      (frag_flags_o),
    .rec_valid_o       (unit_rec_valid),
    .rec_ready_i       (unit_rec_ready),
    .rec_cycles_o      (unit_rec_cycles),
    .rec_lines_o       (unit_rec_lines),
    .rec_bands_o       (unit_rec_bands),
    .rec_pixels_o      (unit_rec_pixels),
    .rec_flags_o       (unit_rec_flags),
    /* verilator lint_off PINCONNECTEMPTY */
    .obs_setup_valid_o (),
    .obs_setup_bits_o  (),
    .obs_setup_g_o     (),
    .obs_setup_box_o   (),
    .obs_setup_lines_o (),
    .obs_write_valid_o (),
    .obs_write_addr_o  (),
    .obs_write_tu_o    (),
    .obs_write_tv_o    (),
    .obs_write_su_o    (),
    .obs_write_sv_o    (),
    .obs_write_eps_o   (),
    .obs_write_flags_o ()
    /* verilator lint_on PINCONNECTEMPTY */
  );

  // The unit holds while a fragment waits; so does the split engine.
  assign hold = frag_valid_o && !frag_ready_i;

  // ------------------------------------------------------------- records
  // Leaves sent per triangle; the triangles the split engine has finished,
  // oldest first, with their leaf counts and flags.
  logic [LeafCountBits-1:0] sent_q;
  logic [LeafCountBits-1:0] done_count [DoneDepth];
  logic [1:0]               done_flags [DoneDepth];
  logic [DoneBits-1:0]      done_rd_q, done_wr_q;
  logic [DoneBits:0]        done_used_q;
  logic                     done_now;      // the split engine reports a triangle done this cycle
  logic                     head_known;    // the oldest unrecorded triangle's leaf count is known
  logic [LeafCountBits-1:0] head_count;
  logic [1:0]               head_flags;
  // Leaf records absorbed for the oldest triangle, and what they carry.
  logic [LeafCountBits-1:0] got_q, got;
  logic [CountBits-1:0]     pixels_q, pixels;
  logic [7:0]               flags_q, flags;
  logic                     unit_rec;      // a leaf's record is taken this cycle
  logic                     deliver;       // a triangle's record is taken this cycle
  logic                     started_q;     // a triangle has been accepted
  logic [CountBits-1:0]     cycles_q;      // since the last record (the first: since the first acceptance)

  assign done_now = split_done && !hold;  // tri_done_o stays up while held
  assign head_known = done_used_q != '0 || done_now;
  assign head_count = done_used_q != '0 ? done_count[done_rd_q] : sent_q;
  assign head_flags = done_used_q != '0 ? done_flags[done_rd_q] : split_flags;
  assign unit_rec_ready = rec_ready_i;
  assign unit_rec = unit_rec_valid && unit_rec_ready;
  assign got = got_q + (unit_rec ? LeafCountBits'(1) : '0);
  assign pixels = pixels_q + (unit_rec ? CountBits'(unit_rec_pixels) : '0);
  assign flags = flags_q | (unit_rec ? unit_rec_flags : '0);

  assign rec_valid_o = head_known && got == head_count;
  assign deliver = rec_valid_o && rec_ready_i;
  assign rec_cycles_o = 64'(cycles_q) + 64'd1;
  assign rec_lines_o = '0;
  assign rec_bands_o = '0;
  assign rec_pixels_o = 32'(pixels);
  // The split engine's flags are its {output saturated, depth range}.
  assign rec_flags_o = flags | (8'(head_flags[1]) << `CD_FLAG_OUTPUT_SATURATED)
                             | (8'(head_flags[0]) << `CD_FLAG_DEPTH_RANGE);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sent_q <= '0;
      done_rd_q <= '0;
      done_wr_q <= '0;
      done_used_q <= '0;
      got_q <= '0;
      pixels_q <= '0;
      flags_q <= '0;
      started_q <= 1'b0;
      cycles_q <= '0;
    end else begin
      if (tri_valid_i && tri_ready_o) started_q <= 1'b1;
      if (deliver) cycles_q <= '0;
      else if (started_q || (tri_valid_i && tri_ready_o)) cycles_q <= cycles_q + CountBits'(1);
      // Leaves sent: a triangle's count is taken when it is done (no leaf
      // is sent in that cycle: the split engine is idle in it).
      if (done_now) sent_q <= '0;
      else if (leaf_valid && leaf_ready) sent_q <= sent_q + LeafCountBits'(1);
      // A finished triangle waits here unless its record goes in the same cycle.
      if (done_now && !(deliver && done_used_q == '0)) begin
        done_count[done_wr_q] <= sent_q;
        done_flags[done_wr_q] <= split_flags;
        done_wr_q <= done_wr_q + DoneBits'(1);
      end
      if (deliver && done_used_q != '0) done_rd_q <= done_rd_q + DoneBits'(1);
      done_used_q <= done_used_q + (done_now && !(deliver && done_used_q == '0) ? (DoneBits+1)'(1) : '0)
                                 - (deliver && done_used_q != '0 ? (DoneBits+1)'(1) : '0);
      if (deliver) begin
        got_q <= '0;
        pixels_q <= '0;
        flags_q <= '0;
      end else if (unit_rec) begin
        got_q <= got;
        pixels_q <= pixels;
        flags_q <= flags;
      end
    end
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (done_used_q == (DoneBits+1)'(DoneDepth) && done_now)  // 0 in reset
      $error("adaptive_unit: more than %0d triangles done and not recorded", DoneDepth);
  end
`endif

  // Nothing is observed inside: the split engine has its own testbench
  // (tests/rtl_units/adaptive_split_tb.cpp), and the leaves' setups are the
  // affine unit's.
  assign obs_setup_valid_o = 1'b0;
  assign obs_setup_bits_o  = '0;
  assign obs_setup_g_o     = '0;
  assign obs_setup_box_o   = '0;
  assign obs_setup_lines_o = '0;
  assign obs_write_valid_o = 1'b0;
  assign obs_write_addr_o  = '0;
  assign obs_write_tu_o    = '0;
  assign obs_write_tv_o    = '0;
  assign obs_write_su_o    = '0;
  assign obs_write_sv_o    = '0;
  assign obs_write_eps_o   = '0;
  assign obs_write_flags_o = '0;
  logic unused;
  assign unused = HasObservation;

endmodule

`default_nettype wire
