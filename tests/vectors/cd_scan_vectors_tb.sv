// Replays the vectors of `cdsim vectors` on the scan unit, in SystemVerilog
// alone (no SystemC, no C++ model): the triangles of triangles.hex go in
// through the ready/valid input, and each block's results are compared with
// the model's, as sim/scoreboard.cpp compares them: the setup engine's
// (setups.hex), every table write (table_writes.hex), every fragment
// (fragments.hex) and every record (records.hex), whose cycles must equal the
// model's plus the cycles a fragment was refused.
//
//   build: Verilator --binary -Wall -IVECTORS -Irtl --top-module cd_scan_vectors_tb
//          tests/vectors/cd_scan_vectors_tb.sv rtl/*.sv
//   run:   obj_dir/Vcd_scan_vectors_tb +vectors=VECTORS [+backpressure=PERMILLE] [+seed=N]
//          [+max_mismatches=N]   (stop after N mismatches; default: run to the end)
//
// VECTORS holds cd_widths.svh and vectors.svh, which fix the widths, the
// counts and the unit's parameters, so a bench is built for one vector set;
// +vectors may then name any copy of it. The bench prints each mismatch (the
// first 20) with its triangle, block and field, and ends with $fatal unless
// every triangle's record came and nothing differed (docs/vectors.md).
`include "cd_widths.svh"
`include "vectors.svh"
`default_nettype none

module cd_scan_vectors_tb;

  localparam int Triangles = `CD_VEC_TRIANGLES;
  // Arrays hold at least one word, so that a set without writes still elaborates.
  localparam int WriteSlots = `CD_VEC_TABLE_WRITES > 0 ? `CD_VEC_TABLE_WRITES : 1;
  localparam int FragmentSlots = `CD_VEC_FRAGMENTS > 0 ? `CD_VEC_FRAGMENTS : 1;
  localparam bit HasTable = `CD_VEC_HAS_TABLE;
  localparam int MaxReported = 20;

  // The words of the files are triangle_t, setup_t, table_write_t,
  // fragment_t and record_t, packed structs from vectors.svh (sim/vectors.cpp's
  // layouts); the bits of a setup's `bits` and a table write's `flags` are at
  // CD_OBS_SETUP_* and CD_OBS_WRITE_* (model/encodings.def).
  localparam int Empty = `CD_OBS_SETUP_EMPTY, XMajor = `CD_OBS_SETUP_X_MAJOR;
  localparam int NoLines = `CD_OBS_SETUP_NO_LINES, SetupDepthRange = `CD_OBS_SETUP_DEPTH_RANGE;
  localparam int Saturated = `CD_OBS_WRITE_SATURATED, WriteDepthRange = `CD_OBS_WRITE_DEPTH_RANGE;
  localparam int EpsSaturated = `CD_OBS_WRITE_EPS_SATURATED, EpsChecked = `CD_OBS_WRITE_EPS_CHECKED;

  triangle_t    triangles     [Triangles];
  setup_t       setups        [Triangles];
  record_t      records       [Triangles];
  table_write_t table_writes  [WriteSlots];
  fragment_t    fragments     [FragmentSlots];

  logic clk = 1'b0;
  always #5 clk <= ~clk;

  logic        rst_n;
  logic        tri_valid, tri_ready;
  triangle_t   presented;
  logic        frag_valid, frag_ready;
  logic [15:0] frag_x, frag_y;
  logic [63:0] frag_u, frag_v;
  logic [7:0]  frag_flags;
  logic        rec_valid;
  logic [63:0] rec_cycles;
  logic [31:0] rec_lines, rec_bands, rec_pixels;
  logic [7:0]  rec_flags;
  logic        obs_setup_valid;
  /* verilator lint_off UNUSEDSIGNAL */  // bits 7:4 are always 0
  logic [7:0]  obs_setup_bits;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [31:0] obs_setup_g;
  logic [63:0] obs_setup_box, obs_setup_lines;
  logic        obs_write_valid;
  logic [31:0] obs_write_addr;
  logic [63:0] obs_write_tu, obs_write_tv, obs_write_su, obs_write_sv;
  logic [63:0] obs_write_eps;
  logic [2:0]  obs_write_flags;

  cd_scan_unit #(`CD_VEC_UNIT_PARAMETERS, .HasObservation(1'b1)) dut (
    .clk_i(clk), .rst_ni(rst_n),
    .tri_valid_i(tri_valid), .tri_ready_o(tri_ready),
    .tri_x0_i(presented.x0), .tri_y0_i(presented.y0), .tri_q0_i(presented.q0),
    .tri_u0_i(presented.u0), .tri_v0_i(presented.v0),
    .tri_x1_i(presented.x1), .tri_y1_i(presented.y1), .tri_q1_i(presented.q1),
    .tri_u1_i(presented.u1), .tri_v1_i(presented.v1),
    .tri_x2_i(presented.x2), .tri_y2_i(presented.y2), .tri_q2_i(presented.q2),
    .tri_u2_i(presented.u2), .tri_v2_i(presented.v2),
    .viewport_width_i(presented.viewport_width), .viewport_height_i(presented.viewport_height),
    .kind_i(presented.kind[`CD_KIND_BITS-1:0]), .segment_log2_i(presented.segment_log2[2:0]),
    .quadratic_i(presented.quadratic[0]),
    .kim_pipelined_i(presented.kim_pipelined[0]), .density_log2_i(presented.density_log2[1:0]),
    .correction_i(presented.correction[0]), .persp_i(presented.persp[0]), .fallback_i(presented.fallback[0]),
    .frag_valid_o(frag_valid), .frag_ready_i(frag_ready),
    .frag_x_o(frag_x), .frag_y_o(frag_y), .frag_u_o(frag_u), .frag_v_o(frag_v),
    .frag_flags_o(frag_flags),
    .rec_valid_o(rec_valid), .rec_ready_i(1'b1),
    .rec_cycles_o(rec_cycles), .rec_lines_o(rec_lines), .rec_bands_o(rec_bands),
    .rec_pixels_o(rec_pixels), .rec_flags_o(rec_flags),
    .obs_setup_valid_o(obs_setup_valid), .obs_setup_bits_o(obs_setup_bits),
    .obs_setup_g_o(obs_setup_g), .obs_setup_box_o(obs_setup_box),
    .obs_setup_lines_o(obs_setup_lines),
    .obs_write_valid_o(obs_write_valid), .obs_write_addr_o(obs_write_addr),
    .obs_write_tu_o(obs_write_tu), .obs_write_tv_o(obs_write_tv),
    .obs_write_su_o(obs_write_su), .obs_write_sv_o(obs_write_sv),
    .obs_write_eps_o(obs_write_eps), .obs_write_flags_o(obs_write_flags));

  // ---- checks -------------------------------------------------------------
  int mismatches = 0;
  int current = 0;                       // the triangle in flight
  int write_base = 0, write_seen = 0;    // its first word in table_writes, and the writes seen
  int fragment_base = 0, fragment_seen = 0;
  bit setup_seen = 1'b0;
  longint stalls = 0;

  function automatic void mismatch(string where, string field, logic [63:0] expected,
                                   logic [63:0] actual);
    mismatches++;
    if (mismatches <= MaxReported)
      $display("MISMATCH triangle %0d %s: field %s: expected 0x%0h, actual 0x%0h", current, where,
               field, expected, actual);
    if (mismatches == MaxReported) $display("(further mismatches are counted, not shown)");
  endfunction

  function automatic void check_setup();
    setup_t e = setups[current];
    if (setup_seen) mismatch("setup engine", "results shown twice", 64'd1, 64'd2);
    setup_seen = 1'b1;
    if (obs_setup_bits[Empty] != e.bits[Empty]) begin
      mismatch("setup engine", "empty", 64'(e.bits[Empty]), 64'(obs_setup_bits[Empty]));
      return;
    end
    if (e.bits[Empty]) return;  // nothing else of an empty triangle is used
    if (obs_setup_bits[XMajor] != e.bits[XMajor])
      mismatch("setup engine", "x_major", 64'(e.bits[XMajor]), 64'(obs_setup_bits[XMajor]));
    if (HasTable && obs_setup_g != e.g) mismatch("setup engine", "g", 64'(e.g), 64'(obs_setup_g));
    if (obs_setup_box != e.box) mismatch("setup engine", "box", e.box, obs_setup_box);
    if (obs_setup_bits[SetupDepthRange] != e.bits[SetupDepthRange])
      mismatch("setup engine", "depth_range", 64'(e.bits[SetupDepthRange]), 64'(obs_setup_bits[SetupDepthRange]));
    if (obs_setup_bits[NoLines] != e.bits[NoLines])
      mismatch("setup engine", "no_lines", 64'(e.bits[NoLines]), 64'(obs_setup_bits[NoLines]));
    else if (HasTable && !e.bits[NoLines] && obs_setup_lines != e.lines)
      mismatch("setup engine", "pixel lines", e.lines, obs_setup_lines);
  endfunction

  function automatic void check_write();
    table_write_t e;
    string where;
    if (write_seen >= int'(records[current].table_writes)) begin
      mismatch($sformatf("table write #%0d", write_seen), "count",
               64'(records[current].table_writes), 64'(write_seen) + 64'd1);
      write_seen++;
      return;
    end
    e = table_writes[write_base + write_seen];
    where = $sformatf("table write #%0d", write_seen);
    write_seen++;
    if (obs_write_addr != e.address) mismatch(where, "address", 64'(e.address), 64'(obs_write_addr));
    if (obs_write_tu != e.t_u) mismatch(where, "T.u", e.t_u, obs_write_tu);
    if (obs_write_tv != e.t_v) mismatch(where, "T.v", e.t_v, obs_write_tv);
    if (obs_write_su != e.s_u) mismatch(where, "S.u", e.s_u, obs_write_su);
    if (obs_write_sv != e.s_v) mismatch(where, "S.v", e.s_v, obs_write_sv);
    if (obs_write_flags[Saturated] != e.flags[Saturated] || obs_write_flags[WriteDepthRange] != e.flags[WriteDepthRange])
      mismatch(where, "flags", 64'(e.flags), 64'(obs_write_flags));
    if (e.flags[EpsChecked] && obs_write_eps != e.eps) mismatch(where, "eps", e.eps, obs_write_eps);
    if (e.flags[EpsChecked] && obs_write_flags[EpsSaturated] != e.flags[EpsSaturated])
      mismatch(where, "eps_saturated", 64'(e.flags[EpsSaturated]), 64'(obs_write_flags[EpsSaturated]));
  endfunction

  function automatic void check_fragment();
    fragment_t e;
    string where;
    if (fragment_seen >= int'(records[current].fragments)) begin
      mismatch($sformatf("fragment #%0d pixel (%0d, %0d)", fragment_seen, frag_x, frag_y), "count",
               64'(records[current].fragments), 64'(fragment_seen) + 64'd1);
      fragment_seen++;
      return;
    end
    e = fragments[fragment_base + fragment_seen];
    where = $sformatf("fragment #%0d pixel (%0d, %0d)", fragment_seen, e.x, e.y);
    fragment_seen++;
    if (frag_x != e.x) mismatch(where, "x", 64'(e.x), 64'(frag_x));
    if (frag_y != e.y) mismatch(where, "y", 64'(e.y), 64'(frag_y));
    if (frag_u != e.u) mismatch(where, "u", e.u, frag_u);
    if (frag_v != e.v) mismatch(where, "v", e.v, frag_v);
    if (frag_flags != e.flags) mismatch(where, "flags", 64'(e.flags), 64'(frag_flags));
  endfunction

  function automatic void check_record();
    record_t e = records[current];
    if (!setup_seen) mismatch("record", "setup results shown", 64'd1, 64'd0);
    if (write_seen != int'(e.table_writes))
      mismatch("record", "table writes", 64'(e.table_writes), 64'(write_seen));
    if (fragment_seen != int'(e.fragments))
      mismatch("record", "fragments", 64'(e.fragments), 64'(fragment_seen));
    if (rec_cycles != e.cycles + 64'(stalls))
      mismatch($sformatf("record (%0d stall cycles)", stalls), "cycles", e.cycles + 64'(stalls),
               rec_cycles);
    if (rec_lines != e.lines) mismatch("record", "lines", 64'(e.lines), 64'(rec_lines));
    if (rec_bands != e.bands) mismatch("record", "bands", 64'(e.bands), 64'(rec_bands));
    if (rec_pixels != e.pixels) mismatch("record", "pixels", 64'(e.pixels), 64'(rec_pixels));
    if (rec_flags != e.flags) mismatch("record", "flags", 64'(e.flags), 64'(rec_flags));
  endfunction

  // ---- the run ------------------------------------------------------------
  string dir;
  int unsigned backpressure_permille = 0, seed = 1, max_mismatches = 0;
  logic [31:0] random_state;
  longint permille = 0;
  longint model_cycles = 0, rtl_cycles = 0, busy = 0, limit = 0, taken = 0;
  int next = 0, done = 0;
  bit presenting = 1'b0, in_flight = 1'b0, hung = 1'b0;

  // xorshift32: the sink's back-pressure, repeatable from +seed.
  function automatic logic [31:0] next_random(logic [31:0] x);
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
  endfunction

  initial begin
    if (!$value$plusargs("vectors=%s", dir)) dir = ".";
    void'($value$plusargs("backpressure=%d", backpressure_permille));
    void'($value$plusargs("seed=%d", seed));
    void'($value$plusargs("max_mismatches=%d", max_mismatches));
    if (backpressure_permille > 950) $fatal(1, "+backpressure=%0d: at most 950 (per mille)", backpressure_permille);
    permille = longint'(backpressure_permille);
    random_state = seed == 0 ? 32'h1 : seed;
    $readmemh({dir, "/triangles.hex"}, triangles);
    $readmemh({dir, "/setups.hex"}, setups);
    $readmemh({dir, "/records.hex"}, records);
    if (`CD_VEC_TABLE_WRITES > 0) $readmemh({dir, "/table_writes.hex"}, table_writes);
    if (`CD_VEC_FRAGMENTS > 0) $readmemh({dir, "/fragments.hex"}, fragments);
    $display("vectors: %s: %0d triangles, %0d table writes, %0d fragments; back-pressure %0d/1000, seed %0d",
             dir, Triangles, `CD_VEC_TABLE_WRITES, `CD_VEC_FRAGMENTS, backpressure_permille, seed);

    rst_n = 1'b0;
    tri_valid = 1'b0;
    frag_ready = 1'b1;
    presented = '0;
    repeat (3) @(negedge clk);
    rst_n = 1'b1;
    // Drive on the falling edge and sample 1 time unit later, as sim/bench.hpp
    // does: every value read is the cycle's settled state, every value written
    // is what the unit samples at the next rising edge.
    while (done < Triangles && !hung &&
           (max_mismatches == 0 || mismatches < int'(max_mismatches))) begin
      @(negedge clk);
      random_state = next_random(random_state);
      frag_ready = !(backpressure_permille > 0 && random_state % 1000 < backpressure_permille);
      // Let the unit's outputs settle on the new frag_ready: a refused fragment
      // holds the unit, and the table write or setup result of this cycle with it.
      #1;
      if (frag_valid) begin
        if (!frag_ready) stalls++;
        else begin
          check_fragment();
          taken++;
        end
      end
      if (obs_setup_valid) check_setup();
      if (obs_write_valid) check_write();
      if (presenting || in_flight) busy++;
      if (busy > limit) begin
        $display("HANG triangle %0d: no record after %0d cycles", current, busy);
        hung = 1'b1;
      end
      if (rec_valid) begin
        check_record();
        model_cycles += longint'(records[current].cycles);
        rtl_cycles += longint'(rec_cycles);
        in_flight = 1'b0;
        done++;
        write_base += int'(records[current].table_writes);
        fragment_base += int'(records[current].fragments);
      end
      // Source: offer the next triangle; it is taken at the coming rising edge
      // when the unit is ready, and tri_valid falls at the next falling edge.
      if (!presenting && !in_flight && next < Triangles) begin
        current = next++;
        presented = triangles[current];
        presenting = 1'b1;
        write_seen = 0;
        fragment_seen = 0;
        setup_seen = 1'b0;
        stalls = 0;
        busy = 0;
        // As regress's hang limit: 4 x (model cycles + expected stalls) + 1000.
        limit = 4 * (longint'(records[current].cycles) +
                     (longint'(records[current].pixels) * permille + 999 - permille) /
                     (1000 - permille)) + 1000;
      end
      tri_valid = presenting;
      if (presenting && tri_ready) begin
        presenting = 1'b0;
        in_flight = 1'b1;
      end
    end
    $display("vectors: %0d of %0d triangles, %0d fragments compared, %0d mismatches, RTL cycles %0d, model cycles %0d",
             done, Triangles, taken, mismatches, rtl_cycles, model_cycles);
    if (hung || mismatches > 0 || done != Triangles)
      $fatal(1, "vectors: FAIL");
    $display("vectors: PASS");
    $finish;
  end

endmodule
