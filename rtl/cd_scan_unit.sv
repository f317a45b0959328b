// Constant-depth scan unit: setup engine, scanline table, column walker and
// correction adder behind a ready/valid triangle input, a ready/valid fragment
// output and a ready/valid per-triangle record. The design (density m and
// correction on/off) is chosen per triangle by density_log2_i and correction_i.
//
// Cycles of a triangle (docs/rtl.md): one per cycle spent in SETUP, FILL,
// COLUMN, PIXEL or SCAN (an empty walk), from the cycle after the triangle is
// accepted to the cycle before its record is offered. Without back-pressure
// that is the model's count exactly: setup_cycles + per band (lines +
// recip_latency) + per band (columns) + pixels. A PIXEL cycle whose fragment
// is not taken is a stall and is counted too.
`include "cd_widths.svh"

module cd_scan_unit #(
  parameter int SubpixelBits = `CD_SUBPIXEL_BITS,
  parameter int UvInFrac     = `CD_UV_IN_FRAC,
  parameter int QBits        = `CD_Q_BITS,
  parameter int PlaneBits    = `CD_PLANE_BITS,
  parameter int GFrac        = `CD_G_FRAC,
  parameter int RecipBits    = `CD_RECIP_BITS,
  parameter int TInt         = `CD_T_INT,
  parameter int TFrac        = `CD_T_FRAC,
  parameter int SInt         = `CD_S_INT,
  parameter int SFrac        = `CD_S_FRAC,
  parameter int DFrac        = `CD_D_FRAC,
  parameter int OutInt       = `CD_OUT_INT,
  parameter int OutFrac      = `CD_OUT_FRAC,
  parameter int TableDepth   = `CD_TABLE_DEPTH,
  parameter int RecipLatency = `CD_RECIP_LATENCY,
  parameter int SetupCycles  = `CD_SETUP_CYCLES
) (
  input  logic        clk_i,
  input  logic        rst_ni,

  // Triangle: per vertex x, y (signed, SubpixelBits fraction bits), q = 1/w
  // (binary32 bits), u, v (signed texels, UvInFrac fraction bits).
  input  logic        tri_valid_i,
  output logic        tri_ready_o,
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
  input  logic [15:0] viewport_width_i,
  input  logic [15:0] viewport_height_i,
  input  logic [1:0]  density_log2_i,   // m = 1, 2, 4
  input  logic        correction_i,

  // Fragment: pixel x, y; u, v sign-extended from OutInt.OutFrac; flags.
  output logic        frag_valid_o,
  input  logic        frag_ready_i,
  output logic [15:0] frag_x_o,
  output logic [15:0] frag_y_o,
  output logic [63:0] frag_u_o,
  output logic [63:0] frag_v_o,
  output logic [7:0]  frag_flags_o,

  // Per-triangle record, after the triangle's last fragment.
  output logic        rec_valid_o,
  input  logic        rec_ready_i,
  output logic [63:0] rec_cycles_o,
  output logic [31:0] rec_lines_o,
  output logic [31:0] rec_bands_o,
  output logic [31:0] rec_pixels_o,
  output logic [7:0]  rec_flags_o
);

  localparam int TBits    = TInt + TFrac;
  localparam int SBits    = SInt + SFrac;
  localparam int WordBits = 2 * TBits + 2 * SBits + 2;
  // A dense-m design uses m times TableDepth lines (docs/microarchitecture.md):
  // the SRAM is sized for the densest design, m = 4.
  localparam int MaxDensity = 4;
  localparam int SramDepth = TableDepth * MaxDensity;
  localparam int AddrBits = $clog2(SramDepth);
  localparam int OutBits  = OutInt + OutFrac;
  localparam logic [7:0] FlagBanded = 8'h08;

  // The setup engine needs a cycle for each of its two stages before the
  // last setup cycle decides what follows.
  if (SetupCycles < 3) begin : gen_setup_cycles_check
    $error("cd_scan_unit needs SetupCycles >= 3");
  end

  localparam logic [2:0] StIdle   = 3'd0;
  localparam logic [2:0] StSetup  = 3'd1;
  localparam logic [2:0] StFill   = 3'd2;
  localparam logic [2:0] StColumn = 3'd3;
  localparam logic [2:0] StPixel  = 3'd4;
  localparam logic [2:0] StScan   = 3'd5;  // columns walked with no possible line
  localparam logic [2:0] StRecord = 3'd6;

  logic [2:0]  state_d, state_q;
  logic [31:0] count_d, count_q;            // setup / fill / scan cycle within the state
  logic [1:0]  density_log2_d, density_log2_q;
  logic        correction_d, correction_q;
  logic signed [63:0] band_lo_d, band_lo_q, band_hi_d, band_hi_q;
  logic signed [63:0] band_lines_d, band_lines_q;   // filled lines of the band, guards included
  logic [31:0] offset_d, offset_q;          // column offset o
  logic [31:0] major_d, major_q;
  logic [31:0] minor_d, minor_q, last_d, last_q;
  logic signed [63:0] line_shift_d, line_shift_q;
  logic signed [1:0]  direction_d, direction_q;
  logic [31:0] weight_d, weight_q;
  logic [63:0] cycles_d, cycles_q;
  logic [31:0] lines_d, lines_q, bands_d, bands_q, pixels_d, pixels_q;
  logic [7:0]  flags_d, flags_q;

  // ---------------------------------------------------------------- blocks
  logic               setup_empty, setup_x_major;
  logic signed [63:0] setup_g, pixel_line_lo, pixel_line_hi;
  logic [31:0]        major_lo, major_count, minor_lo, minor_hi;
  logic [191:0]       edge_a, edge_b, edge_c;
  logic [2:0]         edge_threshold;
  logic [7:0]         setup_flags;
  logic               fill_valid;
  logic signed [63:0] fill_line;
  logic [AddrBits-1:0] fill_addr;
  logic               write_valid;
  logic [AddrBits-1:0] write_addr;
  logic [WordBits-1:0] write_entry;

  setup_engine #(
    .SubpixelBits(SubpixelBits), .UvInFrac(UvInFrac), .QBits(QBits), .PlaneBits(PlaneBits),
    .GFrac(GFrac), .RecipBits(RecipBits), .TInt(TInt), .TFrac(TFrac), .SInt(SInt),
    .SFrac(SFrac), .TableDepth(SramDepth), .RecipLatency(RecipLatency)
  ) u_setup_engine (
    .clk_i,
    .rst_ni,
    .load_i            (tri_valid_i && tri_ready_o),
    .tri_x_i           ({tri_x2_i, tri_x1_i, tri_x0_i}),
    .tri_y_i           ({tri_y2_i, tri_y1_i, tri_y0_i}),
    .tri_q_i           ({tri_q2_i, tri_q1_i, tri_q0_i}),
    .tri_u_i           ({tri_u2_i, tri_u1_i, tri_u0_i}),
    .tri_v_i           ({tri_v2_i, tri_v1_i, tri_v0_i}),
    .viewport_width_i,
    .viewport_height_i,
    .density_log2_i,
    .stage0_i          (state_q == StSetup && count_q == 32'd0),
    .stage1_i          (state_q == StSetup && count_q == 32'd1),
    .empty_o           (setup_empty),
    .x_major_o         (setup_x_major),
    .g_o               (setup_g),
    .major_lo_o        (major_lo),
    .major_count_o     (major_count),
    .minor_lo_o        (minor_lo),
    .minor_hi_o        (minor_hi),
    .pixel_line_lo_o   (pixel_line_lo),
    .pixel_line_hi_o   (pixel_line_hi),
    .edge_a_o          (edge_a),
    .edge_b_o          (edge_b),
    .edge_c_o          (edge_c),
    .edge_threshold_o  (edge_threshold),
    .flags_o           (setup_flags),
    .fill_valid_i      (fill_valid),
    .fill_line_i       (fill_line),
    .fill_addr_i       (fill_addr),
    .write_valid_o     (write_valid),
    .write_addr_o      (write_addr),
    .write_entry_o     (write_entry)
  );

  logic               column_step;
  logic [31:0]        column_major, column_weight, column_first, column_last;
  logic signed [63:0] column_line_shift;
  logic signed [1:0]  column_direction;
  logic               column_has_pixels;

  column_walker #(
    .SubpixelBits(SubpixelBits), .GFrac(GFrac), .DFrac(DFrac)
  ) u_column_walker (
    .step_i            (column_step),
    .offset_i          (offset_q),
    .x_major_i         (setup_x_major),
    .g_i               (setup_g),
    .density_log2_i    (density_log2_q),
    .major_lo_i        (major_lo),
    .minor_lo_i        (minor_lo),
    .minor_hi_i        (minor_hi),
    .edge_a_i          (edge_a),
    .edge_b_i          (edge_b),
    .edge_c_i          (edge_c),
    .edge_threshold_i  (edge_threshold),
    .band_lo_i         (band_lo_q),
    .band_hi_i         (band_hi_q),
    .major_o           (column_major),
    .line_shift_o      (column_line_shift),
    .direction_o       (column_direction),
    .weight_o          (column_weight),
    .first_o           (column_first),
    .last_o            (column_last),
    .has_pixels_o      (column_has_pixels)
  );

  logic                read;
  logic                neighbour_read;
  logic [AddrBits-1:0] own_addr, neighbour_addr;
  logic [WordBits-1:0] own_entry, neighbour_entry;

  scanline_table #(
    .Depth(SramDepth), .WordBits(WordBits)
  ) u_scanline_table (
    .clk_i,
    .write_i           (write_valid),
    .write_addr_i      (write_addr),
    .write_entry_i     (write_entry),
    .read_i            (read),
    .own_addr_i        (own_addr),
    .neighbour_read_i  (neighbour_read),
    .neighbour_addr_i  (neighbour_addr),
    .own_entry_o       (own_entry),
    .neighbour_entry_o (neighbour_entry)
  );

  logic [OutBits-1:0] frag_u, frag_v;
  logic [7:0]         frag_flags;

  correction_adder #(
    .TInt(TInt), .TFrac(TFrac), .SInt(SInt), .SFrac(SFrac), .DFrac(DFrac),
    .OutInt(OutInt), .OutFrac(OutFrac)
  ) u_correction_adder (
    .valid_i           (state_q == StPixel),
    .own_entry_i       (own_entry),
    .neighbour_entry_i (neighbour_entry),
    .correct_i         (correction_q && direction_q != 2'sd0),
    .offset_i          (offset_q),
    .weight_i          (weight_q),
    .u_o               (frag_u),
    .v_o               (frag_v),
    .flags_o           (frag_flags)
  );

  // ---------------------------------------------------------------- control
  logic signed [63:0] guard, depth, pixel_lines, lines_per_band, next_band_lo, next_band_hi;
  logic signed [63:0] read_minor, read_line, read_addr;
  logic               read_minor_valid;
  logic               band_done, last_column;

  always_comb begin
    state_d = state_q;
    count_d = count_q;
    density_log2_d = density_log2_q;
    correction_d = correction_q;
    band_lo_d = band_lo_q;
    band_hi_d = band_hi_q;
    band_lines_d = band_lines_q;
    offset_d = offset_q;
    major_d = major_q;
    minor_d = minor_q;
    last_d = last_q;
    line_shift_d = line_shift_q;
    direction_d = direction_q;
    weight_d = weight_q;
    cycles_d = cycles_q;
    lines_d = lines_q;
    bands_d = bands_q;
    pixels_d = pixels_q;
    flags_d = flags_q;
    fill_valid = 1'b0;
    fill_line = '0;
    fill_addr = '0;
    column_step = 1'b0;
    read_minor_valid = 1'b0;
    read_minor = '0;
    band_done = 1'b0;

    guard = {63'd0, correction_q};
    pixel_lines = pixel_line_hi - pixel_line_lo + 64'sd1;
    depth = 64'(TableDepth) <<< density_log2_q;
    lines_per_band = pixel_lines + 2 * guard <= depth ? pixel_lines : depth - 2 * guard;
    next_band_lo = band_hi_q + 64'sd1;
    last_column = offset_q == major_count - 32'd1;

    if (state_q != StIdle && state_q != StRecord) cycles_d = cycles_q + 64'd1;

    case (state_q)
      StIdle: begin
        if (tri_valid_i) begin
          state_d = StSetup;
          count_d = '0;
          density_log2_d = density_log2_i;
          correction_d = correction_i;
          cycles_d = '0;
          lines_d = '0;
          bands_d = '0;
          pixels_d = '0;
          flags_d = '0;
        end
      end
      StSetup: begin
        count_d = count_q + 32'd1;
        if (count_q == 32'(SetupCycles - 1)) begin
          count_d = '0;
          offset_d = '0;
          if (setup_empty) begin
            state_d = StRecord;
          end else begin
            flags_d = setup_flags;
            if (pixel_line_lo > pixel_line_hi) begin
              state_d = StScan;
            end else begin
              state_d = StFill;
              band_lo_d = pixel_line_lo;
              band_hi_d = pixel_line_lo + lines_per_band - 64'sd1;
              if (band_hi_d > pixel_line_hi) band_hi_d = pixel_line_hi;
              band_lines_d = band_hi_d - band_lo_d + 64'sd1 + 2 * guard;
              bands_d = 32'd1;
              lines_d = 32'(band_lines_d);
            end
          end
        end
      end
      StFill: begin
        count_d = count_q + 32'd1;
        if ($signed({32'd0, count_q}) < band_lines_q) begin
          fill_valid = 1'b1;
          fill_line = band_lo_q - guard + $signed({32'd0, count_q});
          fill_addr = AddrBits'(count_q);
        end
        if ($signed({32'd0, count_q}) == band_lines_q + 64'(RecipLatency) - 64'sd1) begin
          state_d = StColumn;
          count_d = '0;
          offset_d = '0;
        end
      end
      StColumn: begin
        column_step = 1'b1;
        major_d = column_major;
        line_shift_d = column_line_shift;
        direction_d = column_direction;
        weight_d = column_weight;
        minor_d = column_first;
        last_d = column_last;
        if (column_has_pixels) begin
          state_d = StPixel;
          read_minor_valid = 1'b1;
          read_minor = $signed({32'd0, column_first});
        end else if (last_column) begin
          band_done = 1'b1;
        end else begin
          offset_d = offset_q + 32'd1;
        end
      end
      StPixel: begin
        if (frag_ready_i) begin
          pixels_d = pixels_q + 32'd1;
          flags_d = flags_q | frag_flags;
          if (minor_q == last_q) begin
            if (last_column) begin
              band_done = 1'b1;
            end else begin
              state_d = StColumn;
              offset_d = offset_q + 32'd1;
            end
          end else begin
            minor_d = minor_q + 32'd1;
            read_minor_valid = 1'b1;
            read_minor = $signed({32'd0, minor_q}) + 64'sd1;
          end
        end
      end
      StScan: begin
        count_d = count_q + 32'd1;
        if (count_q == major_count - 32'd1) state_d = StRecord;
      end
      StRecord: begin
        if (rec_ready_i) state_d = StIdle;
      end
      default: state_d = StIdle;
    endcase

    // End of a band: the next band, or the record.
    next_band_hi = next_band_lo + lines_per_band - 64'sd1;
    if (next_band_hi > pixel_line_hi) next_band_hi = pixel_line_hi;
    if (band_done) begin
      if (band_hi_q < pixel_line_hi) begin
        state_d = StFill;
        count_d = '0;
        band_lo_d = next_band_lo;
        band_hi_d = next_band_hi;
        band_lines_d = next_band_hi - next_band_lo + 64'sd1 + 2 * guard;
        bands_d = bands_q + 32'd1;
        lines_d = lines_q + 32'(band_lines_d);
        flags_d = flags_d | FlagBanded;
      end else begin
        state_d = StRecord;
      end
    end

    // Table read for the next pixel: its line, and the neighbour line.
    read_line = (read_minor - $signed({32'd0, minor_lo})) <<< density_log2_q;
    read_line = read_line - (state_q == StColumn ? column_line_shift : line_shift_q);
    read_addr = read_line - (band_lo_q - guard);
  end

  assign read = read_minor_valid;
  assign own_addr = AddrBits'(read_addr);
  assign neighbour_read = read_minor_valid && correction_q &&
                          (state_q == StColumn ? column_direction : direction_q) != 2'sd0;
  assign neighbour_addr = AddrBits'(read_addr + {{62{direction_d[1]}}, direction_d});

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= StIdle;
      count_q <= '0;
      density_log2_q <= '0;
      correction_q <= 1'b0;
      band_lo_q <= '0;
      band_hi_q <= '0;
      band_lines_q <= '0;
      offset_q <= '0;
      major_q <= '0;
      minor_q <= '0;
      last_q <= '0;
      line_shift_q <= '0;
      direction_q <= '0;
      weight_q <= '0;
      cycles_q <= '0;
      lines_q <= '0;
      bands_q <= '0;
      pixels_q <= '0;
      flags_q <= '0;
    end else begin
      state_q <= state_d;
      count_q <= count_d;
      density_log2_q <= density_log2_d;
      correction_q <= correction_d;
      band_lo_q <= band_lo_d;
      band_hi_q <= band_hi_d;
      band_lines_q <= band_lines_d;
      offset_q <= offset_d;
      major_q <= major_d;
      minor_q <= minor_d;
      last_q <= last_d;
      line_shift_q <= line_shift_d;
      direction_q <= direction_d;
      weight_q <= weight_d;
      cycles_q <= cycles_d;
      lines_q <= lines_d;
      bands_q <= bands_d;
      pixels_q <= pixels_d;
      flags_q <= flags_d;
    end
  end

  // ---------------------------------------------------------------- outputs
  assign tri_ready_o = state_q == StIdle;

  assign frag_valid_o = state_q == StPixel;
  assign frag_x_o = 16'(setup_x_major ? major_q : minor_q);
  assign frag_y_o = 16'(setup_x_major ? minor_q : major_q);
  assign frag_u_o = {{(64 - OutBits){frag_u[OutBits-1]}}, frag_u};
  assign frag_v_o = {{(64 - OutBits){frag_v[OutBits-1]}}, frag_v};
  assign frag_flags_o = frag_flags;

  assign rec_valid_o = state_q == StRecord;
  assign rec_cycles_o = cycles_q;
  assign rec_lines_o = lines_q;
  assign rec_bands_o = bands_q;
  assign rec_pixels_o = pixels_q;
  assign rec_flags_o = flags_q;

endmodule
