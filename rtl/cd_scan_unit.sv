// Scan unit: setup engine, column walker and a per-pixel datapath behind a
// ready/valid triangle input, a ready/valid fragment output and a ready/valid
// per-triangle record. The datapaths are the constant-depth designs
// (scanline table and correction adder; density m and correction on/off) and
// the per-pixel designs (docs/designs.md), each present by parameter, so that
// a unit synthesised for one design holds only that design's hardware. The
// design is chosen per triangle by kind_i (when more than one is present),
// density_log2_i, correction_i, persp_i and fallback_i (a constant-depth
// design whose triangles near their horizon go to the divide datapath).
//
// Front, fill and back (docs/rtl.md, "Front and back"): the front accepts a
// triangle and runs the setup engine (SetupCycles); the fill fills the table
// band by band for the constant-depth designs; the back walks the columns and
// runs the datapath, then offers the record. The back takes a set-up triangle
// when it is idle or in its record cycle. CD_SETUP_FIFO_DEPTH chooses how far
// they overlap: with 2 a fill stage between front and back holds a triangle
// and a copy of everything it needs (contexts, the fill's operands), so the
// front sets up triangle N+2 while N+1 is filled and N walked; with 1 the back
// walks from its own copy of the setup results (the context) and the front
// sets up the next triangle during the walk, but the fill reads the setup
// engine's registers; with 0 they take turns: setup, fill and walk one after
// another. CD_TABLE_BANKS = 2 doubles the table so that a band is filled
// while the walker reads the band before; with 1 a fill waits for the walk.
//
// Cycles (docs/microarchitecture.md, model/timing.cpp): a walk takes one cycle
// per column of every band and one per pixel (COLUMN, PIXEL); a fill lines +
// fill_latency; divide DRAINs its reciprocal pipeline, Kim its fraction stage
// (rtl/kim_datapath.sv); a per-pixel design at depth 1 or 2 spends an INIT
// cycle loading the walker from the back's context. A fragment offered and not taken holds
// the whole unit for the cycle. The record counts the clocks from the cycle
// after the previous record was delivered (the first triangle: from its accept)
// to its own delivery, held cycles included: the model's schedule, plus the
// back-pressure stalls. (With early_walk the back also starves for lines not
// yet written; the model's schedule counts those.)
`include "cd_widths.svh"
`default_nettype none

module cd_scan_unit #(
  // The table holds TableDepth << MaxDensityLog2 lines: the densest design the
  // unit serves (2 for cd-dense4; 0 when only m = 1 designs run on it).
  parameter int MaxDensityLog2 = 2,
  // 0 builds the unit without the linear correction (cd-none, cd-dense2,
  // cd-dense4): no neighbour read, no correction multiplies, no guard lines.
  parameter bit HasCorrection = 1'b1,
  // cd-persp's perspective-correct weight (needs HasCorrection): eps in the
  // table word, its product in the fill, the weight's ROM and multiplies.
  parameter bit HasPersp = 1'b1,
  // The datapaths present: the constant-depth designs (table, fill,
  // correction adder) and divide (plane walker, pixel reciprocal pipeline).
  parameter bit HasTable = 1'b1,
  parameter bit HasDivide = 1'b1,
  // affine: its setup (planes of u and v by six serial dividers) and two
  // plane accumulators.
  parameter bit HasAffine = 1'b1,
  // affine-subN: exact end points every N pixels (rtl/affine_sub_datapath.sv),
  // N up to 2^MaxSegmentLog2.
  parameter bit HasAffineSub = 1'b1,
  // quad-subN: exact points at each segment's start, middle and end, the
  // quadratic between (rtl/quad_sub_datapath.sv). It shares the exact points
  // (rtl/exact_points.sv) with affine-subN.
  parameter bit HasQuadSub = 1'b1,
  parameter int MaxSegmentLog2 = 5,
  // kim-iter and kim-pipe (rtl/kim_datapath.sv): the span division and unit
  // steps with three plane accumulators, and an iterative or a pipelined
  // fraction stage (either present alone is one design; both share the rest).
  parameter bit HasKimIter = 1'b1,
  parameter bit HasKimPipe = 1'b1,
  // The obs_* ports, for the scoreboard; synthesis turns them off.
  parameter bit HasObservation = 1'b1
) (
  input  logic        clk_i,
  input  logic        rst_ni,

  // Triangle: per vertex x, y (signed, SubpixelBits fraction bits), q = 1/w
  // (binary32 bits), u, v (signed texels, UvInFrac fraction bits), each
  // sign-extended to 32 bits.
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
  /* verilator lint_off UNUSEDSIGNAL */  // 1 .. 8192: bits 15:14 are always 0
  input  logic [15:0] viewport_width_i,
  input  logic [15:0] viewport_height_i,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic [`CD_KIND_BITS-1:0] kind_i,  // CD_KIND_* (model/encodings.def)
  input  logic [2:0]  segment_log2_i,     // affine: 0 plain, else subdivided every 2^segment_log2_i pixels
  input  logic        kim_pipelined_i,    // Kim: 1 kim-pipe, 0 kim-iter
  input  logic [1:0]  density_log2_i,     // m = 1, 2, 4
  input  logic        correction_i,
  input  logic        persp_i,            // cd-persp: the perspective-correct weight
  input  logic        quadratic_i,        // subdivided affine kind: quad-subN (else affine-subN)
  input  logic        fallback_i,         // constant depth: near-horizon triangles by divide (cd-*-div)

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
  output logic [7:0]  rec_flags_o,

  // Observation for the scoreboard (sim/scoreboard.cpp), wires only: the setup
  // engine's results in the last setup cycle, and every table write. With
  // them a mismatch is traced to the block where it starts.
  output logic        obs_setup_valid_o,
  // Bit and field positions: CD_OBS_SETUP_*, CD_OBS_BOX_*, CD_OBS_LINES_* and
  // CD_OBS_WRITE_* (model/encodings.def), which the bench and vectors read.
  output logic [7:0]  obs_setup_bits_o,   // empty, x_major, no_lines, depth_range
  output logic [31:0] obs_setup_g_o,      // sign-extended
  output logic [63:0] obs_setup_box_o,    // major_lo, major_count, minor_lo, minor_hi, 16 bits each
  output logic [63:0] obs_setup_lines_o,  // pixel_line_lo, pixel_line_hi, 32 bits each, signed
  output logic        obs_write_valid_o,
  output logic [31:0] obs_write_addr_o,
  output logic [63:0] obs_write_tu_o,     // T.u, T.v, S.u, S.v, sign-extended
  output logic [63:0] obs_write_tv_o,
  output logic [63:0] obs_write_su_o,
  output logic [63:0] obs_write_sv_o,
  output logic [63:0] obs_write_eps_o,    // cd-persp's eps, sign-extended (0 without HasPersp)
  output logic [2:0]  obs_write_flags_o   // table_saturated, depth_range, eps_saturated
);

  localparam int TableDepth   = `CD_TABLE_DEPTH;
  localparam int RecipLatency = `CD_RECIP_LATENCY;
  // A line issued into the fill's reciprocal is written FillLatency cycles
  // later: RecipLatency, and one more with fill_product_register.
  localparam int FillLatency  = `CD_FILL_LATENCY;
  localparam int SetupCycles  = `CD_SETUP_CYCLES;
  localparam int PixelBits    = `CD_PIXEL_BITS;
  localparam int LineBits     = `CD_LINE_BITS;
  localparam int GBits        = `CD_G_BITS;
  localparam int PhaseBits    = `CD_LINE_PHASE_FRAC > 0 ? `CD_LINE_PHASE_FRAC : 1;
  localparam int WeightBits   = `CD_WEIGHT_BITS;
  localparam bit Persp        = HasPersp && HasCorrection && HasTable;
  localparam int WordBits     = Persp ? `CD_PERSP_WORD_BITS : `CD_WORD_BITS;
  localparam int OutBits      = `CD_OUT_BITS;
  localparam int CountBits    = `CD_CYCLE_COUNT_BITS;
  localparam int BoundBits    = `CD_EDGE_BOUND_BITS;
  localparam int StepBits     = `CD_EDGE_STEP_BITS;
  localparam int SlopeBits    = `CD_EDGE_SLOPE_BITS;
  localparam int SramDepth    = TableDepth << MaxDensityLog2;
  localparam int AddrBits     = $clog2(SramDepth);
  // Lines of a band, and fill cycles: at most SramDepth + FillLatency (a
  // drain at most RecipLatency).
  localparam int BandBits     = LineBits + 2;
  localparam int StepCountBits = $clog2(SramDepth + FillLatency + 1) + 1 > PixelBits + 1
                                 ? $clog2(SramDepth + FillLatency + 1) + 1 : PixelBits + 1;
  localparam int FlagBanded   = `CD_FLAG_BANDED;
  localparam int FifoDepth    = `CD_SETUP_FIFO_DEPTH;

  // The back's states, the design kinds, the front's and the fill's states:
  // encodings the cover points, the bench and the model share
  // (model/encodings.def, CD_STATE_*, CD_KIND_*, CD_FRONT_*, CD_FILL_*).
  typedef enum logic [`CD_STATE_BITS-1:0] {
    StIdle     = `CD_STATE_IDLE,
    StFillWait = `CD_STATE_FILL_WAIT,  // the walker waits for its band to be in the table
    StInit     = `CD_STATE_INIT,       // the walker loads from the context
    StColumn   = `CD_STATE_COLUMN,
    StPixel    = `CD_STATE_PIXEL,
    StScan     = `CD_STATE_SCAN,       // columns walked with no possible line
    StRecord   = `CD_STATE_RECORD,
    StDrain    = `CD_STATE_DRAIN       // a pipeline empties (per-pixel designs; the table with correction_stages)
  } state_e;

  localparam logic [`CD_KIND_BITS-1:0] KindDivide = `CD_KIND_BITS'(`CD_KIND_DIVIDE);  // kind_i
  localparam logic [`CD_KIND_BITS-1:0] KindKim    = `CD_KIND_BITS'(`CD_KIND_KIM);
  localparam logic [`CD_KIND_BITS-1:0] KindAffine = `CD_KIND_BITS'(`CD_KIND_AFFINE);
  localparam bit HasKim = HasKimIter || HasKimPipe;
  localparam bit HasSub = HasAffineSub || HasQuadSub;  // the subdivided designs
  localparam int Datapaths = (HasTable ? 1 : 0) + (HasDivide ? 1 : 0) + (HasAffine ? 1 : 0) +
                             (HasSub ? 1 : 0) + (HasKim ? 1 : 0);
  if (Datapaths == 0) begin : gen_no_datapath
    $error("cd_scan_unit needs at least one datapath (HasTable, HasDivide, HasAffine, HasAffineSub, HasQuadSub, HasKimIter, HasKimPipe)");
  end

  localparam int TableBanks   = `CD_TABLE_BANKS;
  localparam bit FillStage    = FifoDepth > 1;
  // The walker starts a band as soon as its fill starts, and stalls the back
  // in any cycle whose table read needs a line not yet written (the table is
  // then read and written in the same cycle: a two-port SRAM).
  localparam bit EarlyWalk    = `CD_EARLY_WALK != 0;
  // correction_stages: pipeline registers in the correction adder. A table
  // pixel then leaves correction_adder's register, behind the walker, as a
  // per-pixel design's leaves its pipeline: the walker issues a pixel each
  // cycle, the fragment is offered CorrStages cycles later, its pixel and
  // flags counted when it is taken, and the last band ends in StDrain.
  localparam int CorrStages   = `CD_CORRECTION_STAGES;
  localparam bit TablePipe    = HasTable && CorrStages > 0;

  // Front: accepts a triangle and runs the setup engine. Fill: fills the table
  // band by band, into the next of TableBanks banks once the walker is done
  // with the band it held. Back: walks the columns and runs the datapath
  // (docs/rtl.md, "Front and back"). FifoDepth = 2 puts a fill
  // stage between front and back that holds a triangle with a copy of
  // everything (contexts, the fill's operands), so the front sets up the
  // next triangle while this one is filled and the one before walked. With 1
  // the back holds its own copy, so the front sets up the next triangle during
  // the walk, but the fill reads the setup engine's registers; with 0 they
  // take turns.
  typedef enum logic [`CD_FRONT_BITS-1:0] {
    FrIdle     = `CD_FRONT_IDLE,
    FrSetup    = `CD_FRONT_SETUP,
    FrOffer    = `CD_FRONT_OFFER,     // set up, waiting to move on
    FrFillHeld = `CD_FRONT_FILL_HELD  // FifoDepth < 2: the fill reads the setup engine's registers
  } front_e;
  typedef enum logic [`CD_FILL_BITS-1:0] {
    FlIdle     = `CD_FILL_IDLE,
    FlFill     = `CD_FILL_FILLING,
    FlBandWait = `CD_FILL_BAND_WAIT   // the next band's bank is still walked
  } fill_e;

  front_e     front_d, front_q;
  logic [StepCountBits-1:0] fcount_d, fcount_q;  // setup cycle
  logic [`CD_KIND_BITS-1:0] f_kind_d, f_kind_q;
  logic [2:0]  f_segment_log2_d, f_segment_log2_q;
  logic        f_kim_pipelined_d, f_kim_pipelined_q;
  logic [1:0]  f_density_log2_d, f_density_log2_q;
  logic        f_correction_d, f_correction_q;
  logic        f_persp_d, f_persp_q;
  logic        f_quadratic_d, f_quadratic_q;
  logic        f_per_pixel;                      // the front's triangle: a per-pixel design
  logic        f_mode_affine;                    // the front's triangle: affine (its own setup)

  fill_e      fill_d, fill_q;
  logic [StepCountBits-1:0] fl_count_d, fl_count_q;  // fill cycle of the band
  logic signed [LineBits-1:0] fl_band_lo_d, fl_band_lo_q, fl_band_hi_d, fl_band_hi_q;
  logic signed [LineBits-1:0] fl_line_hi_d, fl_line_hi_q;      // the triangle's last pixel line
  logic signed [BandBits-1:0] fl_band_lines_d, fl_band_lines_q;  // the band being filled, guards included
  logic signed [BandBits-1:0] fl_per_band_d, fl_per_band_q;      // pixel lines per band
  logic        fl_guard_d, fl_guard_q;
  logic        fill_start;   // the fill takes a triangle with bands (its first band from the setup engine's results)
  logic        fill_done;    // the fill's last cycle of its triangle's last band
  logic        more_fill;    // the fill's triangle has a band after this one

  // Banks: the one filled next, the one walked next, and which hold a band
  // filled and not yet walked (with its lines, for the walker).
  localparam int DescBits = 2 * LineBits + BandBits;
  logic        fill_bank_d, fill_bank_q, walk_bank_d, walk_bank_q, next_fill_bank;
  logic [1:0]  full_d, full_q, bank_free;
  logic [DescBits-1:0] walk_desc, held_desc;
  logic        band_avail;   // the band the walker waits for is in the table (or its fill ends now; EarlyWalk: starts)
  logic        starve;       // EarlyWalk: the back stalls, its next read's line not yet written
  logic        table_band_done;

  // The fill stage (FifoDepth = 2): the triangle there (p_*), handed on to
  // the back.
  logic        to_stage;     // the fill stage takes the front's triangle at the end of this cycle
  logic        p_valid;      // a triangle waits for the back (in the fill stage, or the front's)
  logic        stage_busy;
  logic [`CD_KIND_BITS-1:0] p_kind;
  logic [2:0]  p_segment_log2;
  logic        p_kim_pipelined, p_correction, p_persp, p_quadratic, p_empty, p_bands,
               p_per_pixel;
  logic [1:0]  p_density_log2;
  logic [7:0]  p_flags;

  state_e     state_d, state_q;                 // the back's
  logic [StepCountBits-1:0] count_d, count_q;    // scan / drain cycle
  logic [`CD_KIND_BITS-1:0] b_kind_d, b_kind_q, kind_q;
  logic        mode_divide, mode_affine, mode_sub, mode_kim;  // this triangle's datapath, when not the table
  logic [2:0]  b_segment_log2_d, b_segment_log2_q, segment_log2_q;
  logic        b_kim_pipelined_d, b_kim_pipelined_q, kim_pipelined_q;
  logic        per_pixel;                        // a per-pixel design: no fill, no band clip
  logic        hold;                             // a fragment offered and not taken: the unit holds
  logic [1:0]  b_density_log2_d, b_density_log2_q, density_log2_q;
  logic        b_correction_d, b_correction_q, correction_q;
  logic        b_persp_d, b_persp_q, persp_q;
  logic        b_quadratic_d, b_quadratic_q, quadratic_q;
  logic signed [LineBits-1:0] band_lo_d, band_lo_q, band_hi_d, band_hi_q;
  logic signed [BandBits-1:0] band_lines_d, band_lines_q;  // the band walked, guards included
  logic [PixelBits-1:0] offset_d, offset_q;                 // the walker's column offset o
  // The span being walked: its column's offset, and whether that column is
  // the band's last. The walker moves on as a span is loaded, so that in the
  // span's last pixel cycle it already shows the next column.
  logic [PixelBits-1:0] span_offset_d, span_offset_q;
  logic        span_last_d, span_last_q;
  logic        span_load;                         // a span is loaded this cycle
  logic        pixel_moves;                       // the pixel being walked moves on this cycle
  logic        span_ahead;                        // the walker loads spans ahead (not Kim, affine-subN)
  logic [PixelBits-1:0] major_d, major_q;
  logic [PixelBits-1:0] minor_d, minor_q, last_d, last_q;
  logic signed [LineBits-1:0] line_shift_d, line_shift_q;
  logic signed [1:0]  direction_d, direction_q;
  logic [WeightBits-1:0] weight_d, weight_q;
  logic [CountBits-1:0] cycles_d, cycles_q, lines_d, lines_q, bands_d, bands_q, pixels_d, pixels_q;
  logic [7:0]  flags_d, flags_q;
  logic        take;        // the back takes a triangle at the end of this cycle
  logic        band_ready;  // the last fill cycle of a band

  // ---------------------------------------------------------------- blocks
  // The setup engine's results (s_*), and the context the back walks from
  // (the same names without s_): the back's copy, taken with the triangle when
  // FifoDepth >= 1 (at 2 from the fill stage's copy, p_*), the setup engine's
  // registers themselves when 0.
  logic               setup_empty, setup_no_lines;
  logic               setup_fallback;  // the divide fallback takes the front's triangle
  logic signed [LineBits-1:0] s_pixel_line_lo, s_pixel_line_hi;
  logic [7:0]         setup_flags;
  logic               s_x_major, setup_x_major;
  logic signed [GBits-1:0] s_g, setup_g;
  logic [PhaseBits-1:0]    s_line_phase, line_phase;  // the lines' phase (setup_stage_d.sv)
  logic                    tri_lines;  // the offered triangle's design walks constant-depth lines
  logic signed [LineBits-1:0] pixel_line_hi;
  logic [PixelBits-1:0] s_major_lo, s_minor_lo, s_minor_hi, major_lo, minor_lo, minor_hi;
  logic [PixelBits:0]   s_major_count, major_count;
  logic [5:0]           s_edge_kind, edge_kind;
  logic [3*BoundBits-1:0] s_edge_bound, edge_bound;
  logic [3*StepBits-1:0]  s_edge_rem, s_edge_step, s_edge_slope_rem, edge_rem, edge_step, edge_slope_rem;
  logic [3*SlopeBits-1:0] s_edge_slope, edge_slope;
  logic               fill_valid, fill_last;
  logic [AddrBits-1:0] fill_addr;
  logic               write_valid;
  logic [AddrBits-1:0] write_addr;
  logic [WordBits-1:0] write_entry;
  logic signed [`CD_PLANE_REF_Q_BITS-1:0]   s_q_at_ref, q_at_ref;
  logic signed [`CD_PLANE_REF_UV_BITS-1:0]  s_u_at_ref, s_v_at_ref, u_at_ref, v_at_ref;
  logic signed [`CD_PLANE_STEP_Q_BITS-1:0]  s_q_per_major, s_q_per_minor, q_per_major, q_per_minor;
  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] s_u_per_major, s_v_per_major, s_u_per_minor, s_v_per_minor;
  logic signed [`CD_PLANE_STEP_UV_BITS-1:0] u_per_major, v_per_major, u_per_minor, v_per_minor;

  // The contexts: what the walker and datapath read of a triangle, in two
  // stages after the setup engine's registers. The fill stage's copy (p_*,
  // FifoDepth = 2) is loaded as the triangle enters it, the back's as the back
  // takes it (FifoDepth >= 1); a stage that is not there is a wire.
  localparam int WalkBits = 1 + 3 * PixelBits + (PixelBits + 1) + 6 + 3 * BoundBits + 9 * StepBits +
                            3 * SlopeBits;
  logic [WalkBits-1:0] s_walk, p_walk;
  assign s_walk = {s_x_major, s_major_lo, s_minor_lo, s_minor_hi, s_major_count, s_edge_kind, s_edge_bound,
                   s_edge_rem, s_edge_step, s_edge_slope_rem, s_edge_slope};
  context_register #(.Bits(WalkBits), .Present(FifoDepth > 1))
    u_walk_stage (.clk_i, .load_i(to_stage), .d_i(s_walk), .q_o(p_walk));
  context_register #(.Bits(WalkBits), .Present(FifoDepth > 0))
    u_walk_context (.clk_i, .load_i(take), .d_i(p_walk),
                    .q_o({setup_x_major, major_lo, minor_lo, minor_hi, major_count, edge_kind, edge_bound,
                          edge_rem, edge_step, edge_slope_rem, edge_slope}));

  if (HasTable) begin : gen_line_context
    logic [GBits+PhaseBits+LineBits-1:0] p_line;
    context_register #(.Bits(GBits + PhaseBits + LineBits), .Present(FifoDepth > 1))
      u_line_stage (.clk_i, .load_i(to_stage), .d_i({s_g, s_line_phase, s_pixel_line_hi}), .q_o(p_line));
    context_register #(.Bits(GBits + PhaseBits + LineBits), .Present(FifoDepth > 0))
      u_line_context (.clk_i, .load_i(take), .d_i(p_line), .q_o({setup_g, line_phase, pixel_line_hi}));
  end else begin : gen_line_shared
    assign setup_g = s_g;
    assign line_phase = s_line_phase;
    assign pixel_line_hi = s_pixel_line_hi;
  end

  if (HasDivide || HasSub || HasKim) begin : gen_plane_context
    localparam int Bits = `CD_PLANE_REF_Q_BITS + 2 * `CD_PLANE_REF_UV_BITS + 2 * `CD_PLANE_STEP_Q_BITS +
                          4 * `CD_PLANE_STEP_UV_BITS;
    logic [Bits-1:0] p_planes;
    context_register #(.Bits(Bits), .Present(FifoDepth > 1))
      u_plane_stage (.clk_i, .load_i(to_stage),
                     .d_i({s_q_at_ref, s_u_at_ref, s_v_at_ref, s_q_per_major, s_q_per_minor, s_u_per_major,
                           s_v_per_major, s_u_per_minor, s_v_per_minor}),
                     .q_o(p_planes));
    context_register #(.Bits(Bits), .Present(FifoDepth > 0))
      u_plane_context (.clk_i, .load_i(take), .d_i(p_planes),
                       .q_o({q_at_ref, u_at_ref, v_at_ref, q_per_major, q_per_minor, u_per_major, v_per_major,
                             u_per_minor, v_per_minor}));
  end else begin : gen_plane_shared
    assign {q_at_ref, u_at_ref, v_at_ref, q_per_major, q_per_minor, u_per_major, v_per_major, u_per_minor,
            v_per_minor} = {s_q_at_ref, s_u_at_ref, s_v_at_ref, s_q_per_major, s_q_per_minor, s_u_per_major,
                            s_v_per_major, s_u_per_minor, s_v_per_minor};
  end

  setup_engine #(
    .HasLines(HasTable), .HasPixelPlanes(HasDivide || HasSub || HasKim),
    .HasPlanes(HasTable || HasDivide || HasSub || HasKim), .SramDepth(SramDepth),
    .FillContext(FifoDepth > 1), .HasPersp(Persp)
  ) u_setup_engine (
    .clk_i,
    .rst_ni,
    .load_i            (tri_valid_i && tri_ready_o),
    .tri_x_i           ({tri_x2_i, tri_x1_i, tri_x0_i}),
    .tri_y_i           ({tri_y2_i, tri_y1_i, tri_y0_i}),
    .tri_q_i           ({tri_q2_i, tri_q1_i, tri_q0_i}),
    .tri_u_i           ({tri_u2_i, tri_u1_i, tri_u0_i}),
    .tri_v_i           ({tri_v2_i, tri_v1_i, tri_v0_i}),
    .viewport_width_i  (viewport_width_i[13:0]),
    .viewport_height_i (viewport_height_i[13:0]),
    .density_log2_i,
    .correction_i      (correction_i && HasCorrection),
    .lines_i           (tri_lines),
    .fallback_i        (tri_lines && fallback_i && HasDivide),
    .hold_i            (hold),
    .setup_i           (front_q == FrSetup),
    .stage_count_i     (`CD_SETUP_COUNT_BITS'(fcount_q)),
    .empty_o           (setup_empty),
    .x_major_o         (s_x_major),
    .g_o               (s_g),
    .major_lo_o        (s_major_lo),
    .major_count_o     (s_major_count),
    .minor_lo_o        (s_minor_lo),
    .minor_hi_o        (s_minor_hi),
    .no_lines_o        (setup_no_lines),
    .fallback_o        (setup_fallback),
    .pixel_line_lo_o   (s_pixel_line_lo),
    .pixel_line_hi_o   (s_pixel_line_hi),
    .line_phase_o      (s_line_phase),
    .flags_o           (setup_flags),
    .q_at_ref_o        (s_q_at_ref),
    .u_at_ref_o        (s_u_at_ref),
    .v_at_ref_o        (s_v_at_ref),
    .q_per_major_o     (s_q_per_major),
    .u_per_major_o     (s_u_per_major),
    .v_per_major_o     (s_v_per_major),
    .q_per_minor_o     (s_q_per_minor),
    .u_per_minor_o     (s_u_per_minor),
    .v_per_minor_o     (s_v_per_minor),
    .u_vertex_o        (u_vertex),
    .v_vertex_o        (v_vertex),
    .dx1_o             (geometry_dx1),
    .dy1_o             (geometry_dy1),
    .dx2_o             (geometry_dx2),
    .dy2_o             (geometry_dy2),
    .det_o             (geometry_det),
    .ref_x_o           (geometry_ref_x),
    .ref_y_o           (geometry_ref_y),
    .edge_kind_o       (s_edge_kind),
    .edge_bound_o      (s_edge_bound),
    .edge_rem_o        (s_edge_rem),
    .edge_step_o       (s_edge_step),
    .edge_slope_o      (s_edge_slope),
    .edge_slope_rem_o  (s_edge_slope_rem),
    .fill_load_i       (fill_start),
    .fill_valid_i      (fill_valid),
    .fill_last_i       (fill_last),
    .fill_addr_i       (fill_addr),
    .write_valid_o     (write_valid),
    .write_addr_o      (write_addr),
    .write_entry_o     (write_entry)
  );

  logic               column_init, column_advance;
  logic [PixelBits-1:0] column_major, column_first, column_last;
  logic [WeightBits-1:0] column_weight;
  logic signed [LineBits-1:0] column_line_shift;
  logic signed [1:0]  column_direction;
  logic               column_has_pixels;

  column_walker #(
    .HasLines(HasTable)
  ) u_column_walker (
    .clk_i,
    .rst_ni,
    .active_i          (state_q == StColumn || state_q == StPixel),
    .init_i            (column_init),
    .advance_i         (column_advance),
    .offset_i          (offset_q),
    .g_i               (setup_g),
    .line_phase_i      (line_phase),
    .density_log2_i    (density_log2_q),
    .major_lo_i        (major_lo),
    .minor_lo_i        (minor_lo),
    .minor_hi_i        (minor_hi),
    .edge_kind_i       (edge_kind),
    .edge_bound_i      (edge_bound),
    .edge_rem_i        (edge_rem),
    .edge_step_i       (edge_step),
    .edge_slope_i      (edge_slope),
    .edge_slope_rem_i  (edge_slope_rem),
    .clip_band_i       (!per_pixel),
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
  logic signed [OutBits-1:0] table_u, table_v;
  logic [7:0]          table_flags;
  logic                table_valid;                 // the correction adder's output holds a pixel
  logic [2*PixelBits-1:0] table_tag;               // its major and minor index

  if (HasTable) begin : gen_table
    // One scanline_table per bank: the fill writes one while the walker reads
    // the other (with EarlyWalk also the one being written, behind the fill).
    // Read data comes the cycle after the address, from the bank read then.
    logic [WordBits-1:0] own_entry, neighbour_entry;
    logic [TableBanks*WordBits-1:0] own_bank, neighbour_bank;

    for (genvar b = 0; b < TableBanks; b++) begin : gen_bank
      scanline_table #(
        .Depth(SramDepth), .WordBits(WordBits)
      ) u_scanline_table (
        .clk_i,
        .write_i           (write_valid && fill_bank_q == 1'(b)),
        .write_addr_i      (write_addr),
        .write_entry_i     (write_entry),
        .read_i            (read && walk_bank_q == 1'(b)),
        .own_addr_i        (own_addr),
        .neighbour_read_i  (neighbour_read),
        .neighbour_addr_i  (neighbour_addr),
        .own_entry_o       (own_bank[b*WordBits +: WordBits]),
        .neighbour_entry_o (neighbour_bank[b*WordBits +: WordBits])
      );
    end
    if (TableBanks > 1) begin : gen_read_bank
      logic read_bank_q;
      always_ff @(posedge clk_i) begin
        if (read) read_bank_q <= walk_bank_q;
      end
      assign own_entry = read_bank_q ? own_bank[WordBits +: WordBits] : own_bank[0 +: WordBits];
      assign neighbour_entry = read_bank_q ? neighbour_bank[WordBits +: WordBits] : neighbour_bank[0 +: WordBits];
    end else begin : gen_one_bank
      assign own_entry = own_bank;
      assign neighbour_entry = neighbour_bank;
    end

    // With CorrStages > 0 the adder's register moves with the back (not while
    // held or starved) and the pixel's indices move beside it.
    logic table_issue, table_advance;
    assign table_issue = state_q == StPixel && !per_pixel && (!TablePipe || !starve);
    assign table_advance = !hold && !starve;
    correction_adder #(
      .HasCorrection(HasCorrection), .HasPersp(Persp), .Stages(CorrStages)
    ) u_correction_adder (
      .clk_i,
      .rst_ni,
      .advance_i         (table_advance),
      .valid_i           (table_issue),
      .valid_o           (table_valid),
      .own_entry_i       (own_entry),
      .neighbour_entry_i (neighbour_entry),
      .correct_i         (correction_q && direction_q != 2'sd0),
      .offset_i          (span_offset_q),
      .weight_i          (weight_q),
      .persp_i           (persp_q),
      .direction_i       (direction_q),
      .u_o               (table_u),
      .v_o               (table_v),
      .flags_o           (table_flags)
    );
    if (TablePipe) begin : gen_table_tag
      // Beside each of the adder's registers, loaded with its pixel.
      logic [2*PixelBits-1:0] tag_q [CorrStages];
      logic [CorrStages-1:0]  tag_valid_q;
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) tag_valid_q <= '0;
        else if (table_advance) begin
          tag_valid_q[0] <= table_issue;
          for (int k = 1; k < CorrStages; k++) tag_valid_q[k] <= tag_valid_q[k-1];
        end
      end
      always_ff @(posedge clk_i) begin
        if (table_advance && table_issue) tag_q[0] <= {major_q, minor_q};
        for (int k = 1; k < CorrStages; k++)
          if (table_advance && tag_valid_q[k-1]) tag_q[k] <= tag_q[k-1];
      end
      assign table_tag = tag_q[CorrStages-1];
    end else begin : gen_no_table_tag
      assign table_tag = {major_q, minor_q};
    end
  end else begin : gen_no_table
    logic unused_table_addr;
    assign unused_table_addr = ^{own_addr, neighbour_addr, persp_q};
    assign table_u = '0;
    assign table_v = '0;
    assign table_flags = '0;
    assign table_valid = 1'b0;
    assign table_tag = '0;
  end

  // Per-pixel designs: the plane walker feeds the pixel pipeline, which a
  // hold (a fragment offered and not taken) freezes with the rest of the unit.
  logic               plane_start, plane_step, pixel_issue;
  logic               pipe_valid, pipe_saturated, pipe_depth_out;
  logic signed [OutBits-1:0] pipe_u, pipe_v;
  logic [2*PixelBits-1:0] pipe_tag;

  // start_value_o is only affine-subN's (its end points start there).
  /* verilator lint_off PINCONNECTEMPTY */
  if (HasDivide) begin : gen_divide
    logic signed [`CD_PIXEL_Q_BITS-1:0]  pixel_q;
    logic signed [`CD_PIXEL_UV_BITS-1:0] pixel_u, pixel_v;

    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_Q_BITS), .StepBits(`CD_PLANE_STEP_Q_BITS), .AccBits(`CD_PIXEL_Q_BITS)
    ) u_plane_q (
      .clk_i, .init_i(column_init && mode_divide), .advance_i(column_advance && mode_divide),
      .start_i(plane_start && mode_divide), .step_i(plane_step && mode_divide),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(), .next_value_o(),
      .at_ref_i(q_at_ref), .per_major_i(q_per_major), .per_minor_i(q_per_minor), .value_o(pixel_q)
    );
    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS)
    ) u_plane_u (
      .clk_i, .init_i(column_init && mode_divide), .advance_i(column_advance && mode_divide),
      .start_i(plane_start && mode_divide), .step_i(plane_step && mode_divide),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(), .next_value_o(),
      .at_ref_i(u_at_ref), .per_major_i(u_per_major), .per_minor_i(u_per_minor), .value_o(pixel_u)
    );
    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS)
    ) u_plane_v (
      .clk_i, .init_i(column_init && mode_divide), .advance_i(column_advance && mode_divide),
      .start_i(plane_start && mode_divide), .step_i(plane_step && mode_divide),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(), .next_value_o(),
      .at_ref_i(v_at_ref), .per_major_i(v_per_major), .per_minor_i(v_per_minor), .value_o(pixel_v)
    );

    pixel_divide #(
      .TagBits(2 * PixelBits)
    ) u_pixel_divide (
      .clk_i,
      .rst_ni,
      .advance_i   (!hold),
      .valid_i     (pixel_issue),
      .q_i         (pixel_q),
      .u_i         (pixel_u),
      .v_i         (pixel_v),
      .tag_i       ({major_q, minor_q}),
      .valid_o     (pipe_valid),
      .u_o         (pipe_u),
      .v_o         (pipe_v),
      .saturated_o (pipe_saturated),
      .depth_out_o (pipe_depth_out),
      .tag_o       (pipe_tag)
    );
  end else begin : gen_no_divide
    logic unused_planes;
    assign unused_planes = ^{q_at_ref, u_at_ref, v_at_ref, q_per_major, u_per_major, v_per_major,
                             q_per_minor, u_per_minor, v_per_minor, plane_start, plane_step,
                             pixel_issue};
    assign pipe_valid = 1'b0;
    assign pipe_u = '0;
    assign pipe_v = '0;
    assign pipe_saturated = 1'b0;
    assign pipe_depth_out = 1'b0;
    assign pipe_tag = '0;
  end
  /* verilator lint_on PINCONNECTEMPTY */

  // affine: u and v from their own planes, set up by six serial dividers,
  // accumulated per pixel and rounded to the output format.
  logic signed [OutBits-1:0] affine_u, affine_v;
  logic                      affine_saturated;
  logic [3*`CD_UV_BITS-1:0]  u_vertex, v_vertex;
  logic signed [`CD_DIFF_BITS-1:0] geometry_dx1, geometry_dy1, geometry_dx2, geometry_dy2;
  logic signed [`CD_DIFF_BITS-1:0] geometry_ref_x, geometry_ref_y;
  logic signed [`CD_DET_BITS-1:0]  geometry_det;

  /* verilator lint_off PINCONNECTEMPTY */
  if (HasAffine) begin : gen_affine
    localparam int RefBits = `CD_AFFINE_REF_BITS;
    localparam int AccBits = `CD_AFFINE_ACC_BITS;
    localparam int SFrac   = `CD_S_FRAC;
    localparam int OutFrac = `CD_OUT_FRAC;
    logic signed [RefBits-1:0]      s_u_ref, s_v_ref, u_ref, v_ref;
    logic signed [`CD_S_BITS-1:0]   s_u_major, s_u_minor, s_v_major, s_v_minor;
    logic signed [`CD_S_BITS-1:0]   u_major, u_minor, v_major, v_minor;
    logic                           s_saturated, setup_saturated;
    logic signed [AccBits-1:0]      acc_u, acc_v;
    logic [1:0]                     narrow_saturated;
    localparam logic signed [7:0]   NarrowShift = 8'(SFrac - OutFrac);

    affine_setup u_affine_setup (
      .clk_i, .rst_ni,
      .setup_i      (front_q == FrSetup && f_mode_affine),
      .stage_count_i(`CD_SETUP_COUNT_BITS'(fcount_q)),
      .u_vertex_i   (u_vertex),
      .v_vertex_i   (v_vertex),
      .dx1_i        (geometry_dx1),
      .dy1_i        (geometry_dy1),
      .dx2_i        (geometry_dx2),
      .dy2_i        (geometry_dy2),
      .det_i        (geometry_det),
      .ref_x_i      (geometry_ref_x),
      .ref_y_i      (geometry_ref_y),
      .x_major_i    (s_x_major),
      .u_ref_o      (s_u_ref),
      .v_ref_o      (s_v_ref),
      .u_major_o    (s_u_major),
      .u_minor_o    (s_u_minor),
      .v_major_o    (s_v_major),
      .v_minor_o    (s_v_minor),
      .saturated_o  (s_saturated)
    );

    // The planes' stages, as for the others.
    localparam int Bits = 2 * RefBits + 4 * `CD_S_BITS + 1;
    logic [Bits-1:0] p_affine;
    context_register #(.Bits(Bits), .Present(FifoDepth > 1))
      u_affine_stage (.clk_i, .load_i(to_stage),
                      .d_i({s_u_ref, s_v_ref, s_u_major, s_u_minor, s_v_major, s_v_minor, s_saturated}),
                      .q_o(p_affine));
    context_register #(.Bits(Bits), .Present(FifoDepth > 0))
      u_affine_context (.clk_i, .load_i(take), .d_i(p_affine),
                        .q_o({u_ref, v_ref, u_major, u_minor, v_major, v_minor, setup_saturated}));

    plane_accumulator #(
      .RefBits(RefBits), .StepBits(`CD_S_BITS), .AccBits(AccBits)
    ) u_plane_u (
      .clk_i, .init_i(column_init && mode_affine), .advance_i(column_advance && mode_affine),
      .start_i(plane_start && mode_affine), .step_i(plane_step && mode_affine),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(), .next_value_o(),
      .at_ref_i(u_ref), .per_major_i(u_major), .per_minor_i(u_minor), .value_o(acc_u)
    );
    plane_accumulator #(
      .RefBits(RefBits), .StepBits(`CD_S_BITS), .AccBits(AccBits)
    ) u_plane_v (
      .clk_i, .init_i(column_init && mode_affine), .advance_i(column_advance && mode_affine),
      .start_i(plane_start && mode_affine), .step_i(plane_step && mode_affine),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(), .next_value_o(),
      .at_ref_i(v_ref), .per_major_i(v_major), .per_minor_i(v_minor), .value_o(acc_v)
    );

    shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8),
                  .MaxLeft(OutFrac > SFrac ? OutFrac - SFrac : 0))
      u_narrow_u (.enable_i(state_q == StPixel && mode_affine), .in_i(acc_u), .shift_i(NarrowShift),
                  .out_o(affine_u), .saturated_o(narrow_saturated[0]));
    shift_round #(.InBits(AccBits), .OutBits(OutBits), .ShiftBits(8),
                  .MaxLeft(OutFrac > SFrac ? OutFrac - SFrac : 0))
      u_narrow_v (.enable_i(state_q == StPixel && mode_affine), .in_i(acc_v), .shift_i(NarrowShift),
                  .out_o(affine_v), .saturated_o(narrow_saturated[1]));
    assign affine_saturated = |narrow_saturated || setup_saturated;
  end else begin : gen_no_affine
    logic unused_geometry;
    assign unused_geometry = ^{f_mode_affine, u_vertex, v_vertex, geometry_dx1, geometry_dy1, geometry_dx2,
                               geometry_dy2, geometry_ref_x, geometry_ref_y, geometry_det};
    assign affine_u = '0;
    assign affine_v = '0;
    assign affine_saturated = 1'b0;
  end
  /* verilator lint_on PINCONNECTEMPTY */

  // affine-subN and quad-subN: exact points (one shared exact_points) every
  // 2^segment_log2 pixels, affine or quadratic between.
  logic                      sub_valid, sub_saturated, sub_depth_out, sub_hold;
  logic signed [OutBits-1:0] sub_u, sub_v;
  assign sub_hold = hold;

  if (HasSub) begin : gen_sub
    localparam int JumpBits = MaxSegmentLog2 + 1;
    logic                      quad, span, take_sub;
    logic                      point_valid, point_saturated;
    logic signed [`CD_AFFINE_REF_BITS-1:0] point_u, point_v;
    logic                      lin_issue, quad_issue, lin_valid, quad_valid, lin_saturated, quad_saturated;
    logic [JumpBits-1:0]       lin_jump, quad_jump;
    logic signed [OutBits-1:0] lin_u, lin_v, quad_u, quad_v;

    assign quad = HasQuadSub && (!HasAffineSub || quadratic_q);
    assign span = plane_start && mode_sub;
    assign take_sub = mode_sub && state_q == StPixel && sub_valid && frag_ready_i;

    exact_points #(.JumpBits(JumpBits)) u_exact_points (
      .clk_i, .rst_ni,
      .hold_i           (sub_hold),
      .column_init_i    (column_init && mode_sub),
      .column_advance_i (column_advance && mode_sub),
      .span_i           (span),
      .first_offset_i   (column_first - minor_lo),
      .issue_i          (quad ? quad_issue : lin_issue),
      .jump_i           (quad ? quad_jump : lin_jump),
      .q_at_ref_i       (q_at_ref),
      .u_at_ref_i       (u_at_ref),
      .v_at_ref_i       (v_at_ref),
      .q_per_major_i    (q_per_major),
      .u_per_major_i    (u_per_major),
      .v_per_major_i    (v_per_major),
      .q_per_minor_i    (q_per_minor),
      .u_per_minor_i    (u_per_minor),
      .v_per_minor_i    (v_per_minor),
      .valid_o          (point_valid),
      .u_o              (point_u),
      .v_o              (point_v),
      .saturated_o      (point_saturated),
      .depth_out_o      (sub_depth_out)
    );

    if (HasAffineSub) begin : gen_affine_sub
      affine_sub_datapath #(
        .MaxSegmentLog2(MaxSegmentLog2)
      ) u_affine_sub (
        .clk_i, .rst_ni,
        .hold_i            (sub_hold),
        .segment_log2_i    (segment_log2_q),
        .span_i            (span && !quad),
        .span_last_i       (column_last - column_first),
        .take_i            (take_sub && !quad),
        .issue_o           (lin_issue),
        .jump_o            (lin_jump),
        .point_valid_i     (point_valid && !quad),
        .point_u_i         (point_u),
        .point_v_i         (point_v),
        .point_saturated_i (point_saturated),
        .valid_o           (lin_valid),
        .u_o               (lin_u),
        .v_o               (lin_v),
        .saturated_o       (lin_saturated)
      );
    end else begin : gen_no_affine_sub
      assign {lin_issue, lin_jump, lin_valid, lin_u, lin_v, lin_saturated} = '0;
    end

    if (HasQuadSub) begin : gen_quad_sub
      quad_sub_datapath #(
        .MaxSegmentLog2(MaxSegmentLog2)
      ) u_quad_sub (
        .clk_i, .rst_ni,
        .hold_i            (sub_hold),
        .segment_log2_i    (segment_log2_q),
        .span_i            (span && quad),
        .span_last_i       (column_last - column_first),
        .take_i            (take_sub && quad),
        .issue_o           (quad_issue),
        .jump_o            (quad_jump),
        .point_valid_i     (point_valid && quad),
        .point_u_i         (point_u),
        .point_v_i         (point_v),
        .point_saturated_i (point_saturated),
        .valid_o           (quad_valid),
        .u_o               (quad_u),
        .v_o               (quad_v),
        .saturated_o       (quad_saturated)
      );
    end else begin : gen_no_quad_sub
      assign {quad_issue, quad_jump, quad_valid, quad_u, quad_v, quad_saturated} = '0;
    end

    assign sub_valid = quad ? quad_valid : lin_valid;
    assign sub_u = quad ? quad_u : lin_u;
    assign sub_v = quad ? quad_v : lin_v;
    assign sub_saturated = quad ? quad_saturated : lin_saturated;
  end else begin : gen_no_sub
    logic unused_sub;
    assign unused_sub = ^{sub_hold, quadratic_q};
    assign sub_valid = 1'b0;
    assign sub_u = '0;
    assign sub_v = '0;
    assign sub_saturated = 1'b0;
    assign sub_depth_out = 1'b0;
  end

  // kim-iter, kim-pipe: the plane accumulators give a span's first q, U, V
  // (start values, one multiply per column); the datapath steps its own D,
  // R and S from there.
  logic                      kim_handoff, kim_drained, kim_valid, kim_saturated, kim_depth_out;
  logic signed [OutBits-1:0] kim_u, kim_v;
  logic [2*PixelBits-1:0]    kim_tag;

  /* verilator lint_off PINCONNECTEMPTY */
  if (HasKim) begin : gen_kim
    logic signed [`CD_PIXEL_Q_BITS-1:0]  q_start;
    logic signed [`CD_PIXEL_UV_BITS-1:0] u_start, v_start;

    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_Q_BITS), .StepBits(`CD_PLANE_STEP_Q_BITS), .AccBits(`CD_PIXEL_Q_BITS),
      .HasPixel(1'b0)
    ) u_plane_q (
      .clk_i, .init_i(column_init && mode_kim), .advance_i(column_advance && mode_kim),
      .start_i(plane_start && mode_kim), .step_i(1'b0),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(q_start), .next_value_o(),
      .at_ref_i(q_at_ref), .per_major_i(q_per_major), .per_minor_i(q_per_minor), .value_o()
    );
    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS),
      .HasPixel(1'b0)
    ) u_plane_u (
      .clk_i, .init_i(column_init && mode_kim), .advance_i(column_advance && mode_kim),
      .start_i(plane_start && mode_kim), .step_i(1'b0),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(u_start), .next_value_o(),
      .at_ref_i(u_at_ref), .per_major_i(u_per_major), .per_minor_i(u_per_minor), .value_o()
    );
    plane_accumulator #(
      .RefBits(`CD_PLANE_REF_UV_BITS), .StepBits(`CD_PLANE_STEP_UV_BITS), .AccBits(`CD_PIXEL_UV_BITS),
      .HasPixel(1'b0)
    ) u_plane_v (
      .clk_i, .init_i(column_init && mode_kim), .advance_i(column_advance && mode_kim),
      .start_i(plane_start && mode_kim), .step_i(1'b0),
      .first_offset_i(column_first - minor_lo), .jump_i(1'b0), .start_value_o(v_start), .next_value_o(),
      .at_ref_i(v_at_ref), .per_major_i(v_per_major), .per_minor_i(v_per_minor), .value_o()
    );

    kim_datapath #(
      .HasIterative(HasKimIter), .HasPipelined(HasKimPipe)
    ) u_kim_datapath (
      .clk_i, .rst_ni,
      .hold_i        (hold),
      .pipelined_i   (kim_pipelined_q),
      .span_i        (plane_start && mode_kim),
      .q_start_i     (q_start),
      .u_start_i     (u_start),
      .v_start_i     (v_start),
      .q_per_minor_i (q_per_minor),
      .u_per_minor_i (u_per_minor),
      .v_per_minor_i (v_per_minor),
      .active_i      (state_q == StPixel && mode_kim),
      .last_pixel_i  (minor_q == last_q),
      .tag_i         ({major_q, minor_q}),
      .handoff_o     (kim_handoff),
      .drained_o     (kim_drained),
      .valid_o       (kim_valid),
      .u_o           (kim_u),
      .v_o           (kim_v),
      .saturated_o   (kim_saturated),
      .depth_out_o   (kim_depth_out),
      .tag_o         (kim_tag)
    );
  end else begin : gen_no_kim
    logic unused_kim;
    assign unused_kim = kim_pipelined_q;
    assign kim_handoff = 1'b0;
    assign kim_drained = 1'b1;
    assign kim_valid = 1'b0;
    assign kim_u = '0;
    assign kim_v = '0;
    assign kim_saturated = 1'b0;
    assign kim_depth_out = 1'b0;
    assign kim_tag = '0;
  end
  /* verilator lint_on PINCONNECTEMPTY */

  logic signed [OutBits-1:0] frag_u, frag_v;
  logic [7:0]         frag_flags;
  always_comb begin
    frag_u = table_u;
    frag_v = table_v;
    frag_flags = table_flags;
    if (mode_divide) begin
      frag_u = pipe_u;
      frag_v = pipe_v;
      frag_flags = '0;
      frag_flags[`CD_FLAG_OUTPUT_SATURATED] = pipe_saturated;
    end else if (mode_affine) begin
      frag_u = affine_u;
      frag_v = affine_v;
      frag_flags = '0;
      frag_flags[`CD_FLAG_OUTPUT_SATURATED] = affine_saturated;
    end else if (mode_sub) begin
      frag_u = sub_u;
      frag_v = sub_v;
      frag_flags = '0;
      frag_flags[`CD_FLAG_OUTPUT_SATURATED] = sub_saturated;
    end else if (mode_kim) begin
      frag_u = kim_u;
      frag_v = kim_v;
      frag_flags = '0;
      frag_flags[`CD_FLAG_OUTPUT_SATURATED] = kim_saturated;
    end
  end

  // ---------------------------------------------------------------- control
  logic signed [BandBits-1:0] guard, depth, pixel_lines, lines_per_band, first_band_hi;  // the front's triangle
  logic signed [BandBits-1:0] next_band_lo, next_band_hi;                                 // the fill's
  logic signed [BandBits-1:0] read_addr;
  logic [PixelBits-1:0] read_minor;
  logic               read_minor_valid;
  logic               band_done, last_column;
  logic               job_valid, s_job_bands, back_free, accept, front_leaves, unit_busy;

  // The designs by kind and segment: {divide, affine, affine-subN, Kim}, none
  // for the table. With one datapath the mode is a constant, and synthesis
  // keeps only it.
  function automatic logic [3:0] modes_of(input logic [`CD_KIND_BITS-1:0] kind, input logic [2:0] segment_log2);
    modes_of = {HasDivide && (Datapaths == 1 || kind == KindDivide),
                HasAffine && (Datapaths == 1 || (kind == KindAffine && segment_log2 == '0)),
                HasSub && (Datapaths == 1 || (kind == KindAffine && segment_log2 != '0)),
                HasKim && (Datapaths == 1 || kind == KindKim)};
  endfunction
  logic [3:0] f_modes;
  // The front's triangle walks as divide when the fallback takes it (a
  // constant-depth design with a divide fallback, near its horizon).
  logic [`CD_KIND_BITS-1:0] f_kind;
  assign f_kind = HasDivide && HasTable && !setup_empty && setup_fallback ? KindDivide : f_kind_q;
  assign f_modes = modes_of(f_kind, f_segment_log2_q);
  assign tri_lines = HasTable && !(|modes_of(kind_i, segment_log2_i));
  assign f_mode_affine = f_modes[2];
  assign f_per_pixel = |f_modes;
  // A constant-depth triangle with pixel lines: its table is filled band by band.
  assign s_job_bands = !setup_empty && !f_per_pixel && !setup_no_lines;

  // What the back needs to know of a triangle as it takes it: through the fill
  // stage with FifoDepth = 2, else straight from the front.
  localparam int JobBits = `CD_KIND_BITS + 3 + 1 + 2 + 1 + 1 + 1 + 3 + 8;
  logic [JobBits-1:0] p_job;
  context_register #(.Bits(JobBits), .Present(FillStage)) u_job_stage (
    .clk_i, .load_i(to_stage),
    .d_i({f_kind, f_segment_log2_q, f_kim_pipelined_q, f_density_log2_q, f_correction_q, f_persp_q, f_quadratic_q, setup_empty,
          s_job_bands, f_per_pixel, setup_empty ? 8'd0 : setup_flags}),
    .q_o(p_job));
  assign {p_kind, p_segment_log2, p_kim_pipelined, p_density_log2, p_correction, p_persp, p_quadratic, p_empty, p_bands, p_per_pixel,
          p_flags} = p_job;

  // The back's triangle: its own copy with FifoDepth >= 1, else the front's.
  assign kind_q = FifoDepth > 0 ? b_kind_q : f_kind;
  assign segment_log2_q = FifoDepth > 0 ? b_segment_log2_q : f_segment_log2_q;
  assign kim_pipelined_q = FifoDepth > 0 ? b_kim_pipelined_q : f_kim_pipelined_q;
  assign density_log2_q = FifoDepth > 0 ? b_density_log2_q : f_density_log2_q;
  assign correction_q = FifoDepth > 0 ? b_correction_q : f_correction_q;
  assign persp_q = FifoDepth > 0 ? b_persp_q : f_persp_q;
  assign quadratic_q = FifoDepth > 0 ? b_quadratic_q : f_quadratic_q;
  assign {mode_divide, mode_affine, mode_sub, mode_kim} = modes_of(kind_q, segment_log2_q);
  assign per_pixel = mode_divide || mode_affine || mode_sub || mode_kim;

  // A fragment offered and not taken holds the whole unit, front and back, for
  // the cycle: every register but the record's clock count keeps its value
  // and no block is strobed, so the unit's clocks are the model's plus the
  // cycles held (docs/rtl.md).
  assign hold = frag_valid_o && !frag_ready_i;

  // Hand-offs. The front offers its set-up triangle from the last setup cycle
  // on. With FifoDepth = 2 the fill stage takes it when free, and the back
  // takes it from there; else the back takes it from the front. The back
  // takes a triangle when idle or as it delivers its record. A triangle with
  // bands is filled from the cycle after the fill takes it.
  assign job_valid = (front_q == FrSetup && fcount_q == StepCountBits'(SetupCycles - 1)) || front_q == FrOffer;
  assign back_free = state_q == StIdle || (state_q == StRecord && rec_ready_i);
  assign take = p_valid && back_free && !hold;
  assign band_ready = fill_q == FlFill &&
                      BandBits'($signed({1'b0, fl_count_q})) == fl_band_lines_q + BandBits'(FillLatency - 1);
  assign more_fill = fl_band_hi_q < fl_line_hi_q;
  assign fill_done = band_ready && !more_fill;

  if (FillStage) begin : gen_fill_stage
    // Free once the back has taken its triangle and the last band is filled.
    logic stage_q, stage_taken_q, stage_free;
    assign stage_free = !stage_q || ((stage_taken_q || take) && (fill_q == FlIdle || fill_done));
    assign to_stage = job_valid && stage_free && !hold;
    assign p_valid = stage_q && !stage_taken_q;
    assign stage_busy = stage_q;
    assign fill_start = to_stage && s_job_bands;
    assign front_leaves = to_stage;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        stage_q <= 1'b0;
        stage_taken_q <= 1'b0;
      end else if (!hold) begin
        if (to_stage) begin
          stage_q <= 1'b1;
          stage_taken_q <= 1'b0;
        end else if (stage_q && stage_free) begin
          stage_q <= 1'b0;
        end else if (take) begin
          stage_taken_q <= 1'b1;
        end
      end
    end
  end else begin : gen_no_fill_stage
    // The fill reads the setup engine's registers: the front is free when the
    // back takes a triangle without bands, or at the last band's last fill cycle.
    assign to_stage = 1'b0;
    assign p_valid = job_valid;
    assign stage_busy = 1'b0;
    assign fill_start = take && s_job_bands;
    assign front_leaves = (take && !s_job_bands) || fill_done;
  end
  // With FifoDepth >= 1 the front accepts the next triangle in the cycle the
  // last one leaves it; with 0 only once the back is idle too.
  assign tri_ready_o = !hold && (FifoDepth > 0 ? front_q == FrIdle || front_leaves
                                               : front_q == FrIdle && state_q == StIdle);
  assign accept = tri_valid_i && tri_ready_o;

  // Banks. A bank may be filled from the next cycle when it holds no band
  // waiting or walked (the band whose fill ends now counts), or when the walk
  // of its band ends now. Bands go to the banks in turn, and are walked in
  // the same turn.
  assign table_band_done = band_done && !per_pixel;
  for (genvar b = 0; b < 2; b++) begin : gen_bank_state
    assign bank_free[b] = !(full_q[b] || (band_ready && fill_bank_q == 1'(b))) ||
                          (table_band_done && walk_bank_q == 1'(b));
    assign full_d[b] = (full_q[b] || (band_ready && fill_bank_q == 1'(b))) &&
                       !(table_band_done && walk_bank_q == 1'(b));
  end
  assign next_fill_bank = TableBanks > 1 ? fill_bank_q ^ band_ready : 1'b0;
  assign fill_bank_d = next_fill_bank;
  assign walk_bank_d = TableBanks > 1 ? walk_bank_q ^ table_band_done : 1'b0;
  assign band_avail = full_q[walk_bank_q] ||
                      ((EarlyWalk ? fill_q == FlFill : band_ready) && fill_bank_q == walk_bank_q);
  assign walk_desc = full_q[walk_bank_q] ? held_desc : {fl_band_lo_q, fl_band_hi_q, fl_band_lines_q};
  if (TableBanks > 1) begin : gen_two_descs
    logic [DescBits-1:0] desc0_q, desc1_q;
    always_ff @(posedge clk_i) begin
      if (band_ready && !hold) begin
        if (fill_bank_q) desc1_q <= {fl_band_lo_q, fl_band_hi_q, fl_band_lines_q};
        else desc0_q <= {fl_band_lo_q, fl_band_hi_q, fl_band_lines_q};
      end
    end
    assign held_desc = walk_bank_q ? desc1_q : desc0_q;
  end else begin : gen_one_desc
    logic [DescBits-1:0] desc_q;
    always_ff @(posedge clk_i) begin
      if (band_ready && !hold) desc_q <= {fl_band_lo_q, fl_band_hi_q, fl_band_lines_q};
    end
    assign held_desc = desc_q;
  end

  // ---- front
  always_comb begin
    front_d = front_q;
    fcount_d = fcount_q;
    f_kind_d = f_kind_q;
    f_segment_log2_d = f_segment_log2_q;
    f_kim_pipelined_d = f_kim_pipelined_q;
    f_density_log2_d = f_density_log2_q;
    f_correction_d = f_correction_q;
    f_persp_d = f_persp_q;
    f_quadratic_d = f_quadratic_q;

    unique case (front_q)
      FrIdle, FrOffer: ;
      FrSetup: begin
        fcount_d = fcount_q + StepCountBits'(1);
        if (fcount_q == StepCountBits'(SetupCycles - 1)) begin
          fcount_d = '0;
          front_d = FrOffer;
        end
      end
      FrFillHeld: if (fill_done) front_d = FrIdle;
      default: front_d = FrIdle;
    endcase

    if (FillStage ? to_stage : take) front_d = !FillStage && s_job_bands ? FrFillHeld : FrIdle;
    if (accept) begin
      front_d = FrSetup;
      fcount_d = '0;
      f_kind_d = kind_i;
      f_segment_log2_d = segment_log2_i;
      f_kim_pipelined_d = kim_pipelined_i;
      f_density_log2_d = density_log2_i;
      f_correction_d = correction_i && HasCorrection;
      f_persp_d = persp_i && Persp;
      f_quadratic_d = quadratic_i && HasQuadSub;
    end
  end

  // ---- fill
  always_comb begin
    fill_d = fill_q;
    fl_count_d = fl_count_q;
    fl_band_lo_d = fl_band_lo_q;
    fl_band_hi_d = fl_band_hi_q;
    fl_band_lines_d = fl_band_lines_q;
    fl_line_hi_d = fl_line_hi_q;
    fl_per_band_d = fl_per_band_q;
    fl_guard_d = fl_guard_q;
    fill_valid = 1'b0;
    fill_last = 1'b0;
    fill_addr = '0;

    // The front's triangle: its lines per band, and its first band.
    guard = BandBits'($signed({1'b0, f_correction_q}));
    pixel_lines = BandBits'(s_pixel_line_hi) - BandBits'(s_pixel_line_lo) + BandBits'(1);
    depth = BandBits'(TableDepth) <<< f_density_log2_q;
    lines_per_band = pixel_lines + 2 * guard <= depth ? pixel_lines : depth - 2 * guard;
    first_band_hi = BandBits'(s_pixel_line_lo) + lines_per_band - BandBits'(1);
    if (first_band_hi > BandBits'(s_pixel_line_hi)) first_band_hi = BandBits'(s_pixel_line_hi);
    // The fill's triangle: its next band.
    next_band_lo = BandBits'(fl_band_hi_q) + BandBits'(1);
    next_band_hi = next_band_lo + fl_per_band_q - BandBits'(1);
    if (next_band_hi > BandBits'(fl_line_hi_q)) next_band_hi = BandBits'(fl_line_hi_q);

    unique case (fill_q)
      FlIdle: ;
      FlFill: begin
        fl_count_d = fl_count_q + StepCountBits'(1);
        if (BandBits'($signed({1'b0, fl_count_q})) < fl_band_lines_q) begin
          fill_valid = !hold;
          fill_last = BandBits'($signed({1'b0, fl_count_q})) == fl_band_lines_q - BandBits'(1);
          fill_addr = AddrBits'(fl_count_q);
        end
        if (band_ready) begin
          fl_count_d = '0;
          fill_d = FlIdle;
          if (more_fill) begin
            fl_band_lo_d = LineBits'(next_band_lo);
            fl_band_hi_d = LineBits'(next_band_hi);
            fl_band_lines_d = next_band_hi - next_band_lo + BandBits'(1) + 2 * BandBits'($signed({1'b0, fl_guard_q}));
            fill_d = bank_free[next_fill_bank] ? FlFill : FlBandWait;
          end
        end
      end
      FlBandWait: if (bank_free[fill_bank_q]) fill_d = FlFill;
      default: fill_d = FlIdle;
    endcase

    if (fill_start) begin
      fl_count_d = '0;
      fl_band_lo_d = s_pixel_line_lo;
      fl_band_hi_d = LineBits'(first_band_hi);
      fl_band_lines_d = first_band_hi - BandBits'(s_pixel_line_lo) + BandBits'(1) + 2 * guard;
      fl_line_hi_d = s_pixel_line_hi;
      fl_per_band_d = lines_per_band;
      fl_guard_d = f_correction_q;
      fill_d = bank_free[next_fill_bank] ? FlFill : FlBandWait;
    end
  end

  // ---- back
  always_comb begin
    state_d = state_q;
    count_d = count_q;
    b_kind_d = b_kind_q;
    b_segment_log2_d = b_segment_log2_q;
    b_kim_pipelined_d = b_kim_pipelined_q;
    b_density_log2_d = b_density_log2_q;
    b_correction_d = b_correction_q;
    b_persp_d = b_persp_q;
    b_quadratic_d = b_quadratic_q;
    band_lo_d = band_lo_q;
    band_hi_d = band_hi_q;
    band_lines_d = band_lines_q;
    offset_d = offset_q;
    span_offset_d = span_offset_q;
    span_last_d = span_last_q;
    span_load = 1'b0;
    major_d = major_q;
    minor_d = minor_q;
    last_d = last_q;
    line_shift_d = line_shift_q;
    direction_d = direction_q;
    weight_d = weight_q;
    lines_d = lines_q;
    bands_d = bands_q;
    pixels_d = pixels_q;
    flags_d = flags_q;
    column_init = 1'b0;
    column_advance = 1'b0;
    read_minor_valid = 1'b0;
    read_minor = '0;
    band_done = 1'b0;
    plane_start = 1'b0;
    plane_step = 1'b0;
    pixel_issue = 1'b0;

    last_column = (PixelBits+1)'(offset_q) == major_count - (PixelBits+1)'(1);
    span_ahead = !mode_kim && !mode_sub;
    pixel_moves = mode_divide || (TablePipe && !per_pixel) || (mode_kim && kim_handoff) ||
                  (!mode_kim && frag_ready_i && (!mode_sub || sub_valid));

    unique case (state_q)
      StIdle: ;
      StFillWait: if (band_avail) begin
        // The band's lines are in the table (or their fill ends this cycle;
        // EarlyWalk: starts, the reads waiting for their lines).
        state_d = StColumn;
        offset_d = '0;
        column_init = 1'b1;
        {band_lo_d, band_hi_d, band_lines_d} = walk_desc;
        bands_d = bands_q + CountBits'(1);
        lines_d = lines_q + CountBits'(band_lines_d);
      end
      StInit: begin
        // FifoDepth >= 1: the walker loads from the context taken last cycle.
        state_d = StColumn;
        column_init = 1'b1;
      end
      StColumn: begin
        if (column_has_pixels) begin
          state_d = StPixel;
          span_load = 1'b1;
        end else if (last_column) begin
          band_done = 1'b1;
        end else begin
          offset_d = offset_q + PixelBits'(1);
          column_advance = 1'b1;
        end
      end
      StPixel: begin
        // A pixel moves on (divide issues it into its pipeline, Kim hands it to
        // the fraction stage, the others emit it). Meanwhile the walker, a
        // column ahead, passes over columns without pixels, one a cycle. At
        // the span's last pixel the band ends, or the walker's column is
        // loaded in the same cycle when it has pixels, or the band ends when
        // the walker stands on the last column and it has none; otherwise the
        // walker evaluates its column in COLUMN. Kim and affine-subN always go
        // to COLUMN: their span start takes the walker's column cycle.
        if (pixel_moves) begin
          pixel_issue = mode_divide;
          if (!mode_divide && !mode_kim && !(TablePipe && !per_pixel)) begin
            pixels_d = pixels_q + CountBits'(1);
            flags_d = flags_q | frag_flags;
          end
          if (minor_q == last_q) begin
            if (span_last_q) begin
              band_done = 1'b1;
            end else if (column_has_pixels && span_ahead) begin
              span_load = 1'b1;
            end else if (last_column && span_ahead) begin
              band_done = 1'b1;
            end else begin
              state_d = StColumn;
            end
          end else begin
            minor_d = minor_q + PixelBits'(1);
            read_minor_valid = !per_pixel;
            read_minor = minor_q + PixelBits'(1);
            plane_step = mode_divide || mode_affine;
            if (span_ahead && !column_has_pixels && !last_column) begin
              offset_d = offset_q + PixelBits'(1);
              column_advance = 1'b1;
            end
          end
        end
      end
      StScan: begin
        count_d = count_q + StepCountBits'(1);
        if ((PixelBits+1)'(count_q) == major_count - (PixelBits+1)'(1)) state_d = StRecord;
      end
      StDrain: begin
        count_d = count_q + StepCountBits'(1);
        if (mode_kim) begin
          if (kim_drained) state_d = StRecord;
        end else if (count_q == StepCountBits'((TablePipe && !per_pixel ? CorrStages : RecipLatency) - 1)) begin
          state_d = StRecord;
        end
      end
      StRecord: if (rec_ready_i) state_d = StIdle;
      default: state_d = StIdle;
    endcase

    // A span loaded: the column's values, the first pixel's table read or
    // plane start, and the walker moves on to the next column.
    if (span_load) begin
      major_d = column_major;
      line_shift_d = column_line_shift;
      direction_d = column_direction;
      weight_d = column_weight;
      minor_d = column_first;
      last_d = column_last;
      span_offset_d = offset_q;
      span_last_d = last_column;
      read_minor_valid = !per_pixel;
      read_minor = column_first;
      plane_start = per_pixel;
      if (!last_column) begin
        offset_d = offset_q + PixelBits'(1);
        column_advance = 1'b1;
      end
    end

    // End of a band: the next band, or the record.
    if (band_done && mode_divide) begin
      state_d = StDrain;
      count_d = '0;
    end else if (band_done && mode_kim) begin
      // The fraction stage may still hold pixels (always, after a last pixel's hand-off).
      state_d = kim_drained ? StRecord : StDrain;
      count_d = '0;
    end else if (band_done && (mode_affine || mode_sub)) begin
      state_d = StRecord;
    end else if (band_done) begin
      if (band_hi_q < pixel_line_hi) begin
        state_d = StFillWait;
        flags_d[FlagBanded] = 1'b1;
      end else begin
        // The correction adder's register empties first.
        state_d = TablePipe ? StDrain : StRecord;
        count_d = '0;
      end
    end

    // A table fragment taken from the correction adder's register (flags_d:
    // the band's end may have set banded in this cycle).
    if (TablePipe && !per_pixel && table_valid && !starve && frag_ready_i) begin
      pixels_d = pixels_q + CountBits'(1);
      flags_d = flags_d | frag_flags;
    end
    // A per-pixel fragment taken.
    if (mode_divide && pipe_valid && frag_ready_i) begin
      pixels_d = pixels_q + CountBits'(1);
      flags_d = flags_q | frag_flags;
      if (pipe_depth_out) flags_d[`CD_FLAG_DEPTH_RANGE] = 1'b1;
    end
    if (mode_kim && kim_valid && frag_ready_i) begin
      pixels_d = pixels_q + CountBits'(1);
      flags_d = flags_q | frag_flags;
      if (kim_depth_out) flags_d[`CD_FLAG_DEPTH_RANGE] = 1'b1;
    end
    // An affine-subN end point with q <= 0.
    if (mode_sub && sub_depth_out) flags_d[`CD_FLAG_DEPTH_RANGE] = 1'b1;

    // The back takes a triangle (in its record cycle, after the record's own
    // values were offered).
    if (take) begin
      b_kind_d = p_kind;
      b_segment_log2_d = p_segment_log2;
      b_kim_pipelined_d = p_kim_pipelined;
      b_density_log2_d = p_density_log2;
      b_correction_d = p_correction;
      b_persp_d = p_persp;
      b_quadratic_d = p_quadratic;
      lines_d = '0;
      bands_d = '0;
      pixels_d = '0;
      flags_d = p_flags;
      offset_d = '0;
      count_d = '0;
      if (p_empty) begin
        state_d = StRecord;
      end else if (p_bands) begin
        state_d = StFillWait;
      end else if (!p_per_pixel) begin
        state_d = StScan;  // columns walked with no possible line
      end else if (FifoDepth > 0) begin
        state_d = StInit;
      end else begin
        state_d = StColumn;
        column_init = 1'b1;  // from the setup engine's registers
      end
    end

    // Held, or starved: no block is strobed (the registers keep their values).
    if (hold || starve) begin
      band_done = 1'b0;
      column_init = 1'b0;
      column_advance = 1'b0;
      read_minor_valid = 1'b0;
      plane_start = 1'b0;
      plane_step = 1'b0;
      pixel_issue = 1'b0;
    end

    // Table read for the next pixel: its line, and the neighbour line.
    read_addr = table_addr(read_minor, span_load ? column_line_shift : line_shift_q);
  end

  // A table address: line - band base, for minor index `minor` in a column
  // whose lines are shifted by `shift`.
  function automatic logic signed [BandBits-1:0] table_addr(input logic [PixelBits-1:0] minor,
                                                             input logic signed [LineBits-1:0] shift);
    logic signed [BandBits-1:0] line;
    line = (BandBits'($signed({1'b0, minor})) - BandBits'($signed({1'b0, minor_lo}))) <<< density_log2_q;
    line = line - BandBits'(shift);
    table_addr = line - (BandBits'(band_lo_q) - BandBits'($signed({1'b0, correction_q})));
  endfunction

  // EarlyWalk: the back's next table read and the highest address it touches
  // (its own line, or the correction neighbour above), known before the pixel
  // moves, so that a starved cycle offers no fragment and a fragment offered
  // is never withdrawn. Line A of a band is written in its fill cycle
  // FillLatency + A, so a read of top address A may go once fl_count_q, the
  // band's fill cycle, is past it; once the band is full, always. The band's
  // last walk cycle, which frees its bank, waits for the band to be full.
  if (EarlyWalk && HasTable) begin : gen_early_walk
    localparam int CmpBits = (BandBits > StepCountBits ? BandBits : StepCountBits) + 2;
    logic                       next_read, next_end, at_last_column;
    logic [PixelBits-1:0]       next_minor;
    logic signed [LineBits-1:0] next_shift;
    logic signed [1:0]          next_direction;
    logic signed [BandBits-1:0] next_top;
    always_comb begin
      next_read = 1'b0;
      next_minor = minor_q + PixelBits'(1);
      next_shift = line_shift_q;
      next_direction = direction_q;
      if (state_q == StColumn || (state_q == StPixel && minor_q == last_q)) begin
        // A span load: in its column's cycle, or at the last pixel of the span before.
        next_read = column_has_pixels && (state_q == StColumn || !span_last_q);
        next_minor = column_first;
        next_shift = column_line_shift;
        next_direction = column_direction;
      end else if (state_q == StPixel) begin
        next_read = 1'b1;
      end
      next_top = table_addr(next_minor, next_shift) +
                 BandBits'($signed({1'b0, correction_q && next_direction == 2'sd1}));
      at_last_column = (PixelBits+1)'(offset_q) == major_count - (PixelBits+1)'(1);
      next_end = (state_q == StColumn && !column_has_pixels && at_last_column) ||
                 (state_q == StPixel && minor_q == last_q && (span_last_q || (!column_has_pixels && at_last_column)));
    end
    assign starve = !per_pixel && !full_q[walk_bank_q] &&
                    (next_end || (next_read && CmpBits'(next_top) + CmpBits'(FillLatency) >=
                                                  CmpBits'($signed({1'b0, fl_count_q}))));
  end else begin : gen_no_early_walk
    assign starve = 1'b0;
  end

  // The record's clocks: every cycle from the one after the last record was
  // delivered (from the accept, for the first triangle) to its own delivery,
  // held cycles included. Overlapping triangles are thus attributed in order.
  assign unit_busy = front_q != FrIdle || stage_busy || state_q != StIdle || accept;
  always_comb begin
    cycles_d = cycles_q;
    if (state_q == StRecord && rec_ready_i) cycles_d = '0;
    else if (unit_busy) cycles_d = cycles_q + CountBits'(1);
  end

  assign read = read_minor_valid;
  assign own_addr = AddrBits'(read_addr);
  assign neighbour_read = read_minor_valid && correction_q &&
                          (span_load ? column_direction : direction_q) != 2'sd0;
  assign neighbour_addr = AddrBits'(read_addr + BandBits'(direction_d));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cycles_q <= '0;
    end else begin
      cycles_q <= cycles_d;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      front_q <= FrIdle;
      fcount_q <= '0;
      f_kind_q <= '0;
      f_segment_log2_q <= '0;
      f_kim_pipelined_q <= 1'b0;
      f_density_log2_q <= '0;
      f_correction_q <= 1'b0;
      f_persp_q <= 1'b0;
      f_quadratic_q <= 1'b0;
      fill_q <= FlIdle;
      fl_count_q <= '0;
      fl_band_lo_q <= '0;
      fl_band_hi_q <= '0;
      fl_band_lines_q <= '0;
      fl_line_hi_q <= '0;
      fl_per_band_q <= '0;
      fl_guard_q <= 1'b0;
      fill_bank_q <= 1'b0;
      walk_bank_q <= 1'b0;
      full_q <= '0;
    end else if (!hold) begin
      front_q <= front_d;
      fcount_q <= fcount_d;
      f_kind_q <= f_kind_d;
      f_segment_log2_q <= f_segment_log2_d;
      f_kim_pipelined_q <= f_kim_pipelined_d;
      f_density_log2_q <= f_density_log2_d;
      f_correction_q <= f_correction_d;
      f_persp_q <= f_persp_d;
      f_quadratic_q <= f_quadratic_d;
      fill_q <= fill_d;
      fl_count_q <= fl_count_d;
      fl_band_lo_q <= fl_band_lo_d;
      fl_band_hi_q <= fl_band_hi_d;
      fl_band_lines_q <= fl_band_lines_d;
      fl_line_hi_q <= fl_line_hi_d;
      fl_per_band_q <= fl_per_band_d;
      fl_guard_q <= fl_guard_d;
      fill_bank_q <= fill_bank_d;
      walk_bank_q <= walk_bank_d;
      full_q <= full_d;
    end
  end

  // The back's registers also keep their values while it starves.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= StIdle;
      count_q <= '0;
      b_kind_q <= '0;
      b_segment_log2_q <= '0;
      b_kim_pipelined_q <= 1'b0;
      b_density_log2_q <= '0;
      b_correction_q <= 1'b0;
      b_persp_q <= 1'b0;
      b_quadratic_q <= 1'b0;
      band_lo_q <= '0;
      band_hi_q <= '0;
      band_lines_q <= '0;
      offset_q <= '0;
      span_offset_q <= '0;
      span_last_q <= 1'b0;
      major_q <= '0;
      minor_q <= '0;
      last_q <= '0;
      line_shift_q <= '0;
      direction_q <= '0;
      weight_q <= '0;
      lines_q <= '0;
      bands_q <= '0;
      pixels_q <= '0;
      flags_q <= '0;
    end else if (!hold && !starve) begin
      state_q <= state_d;
      count_q <= count_d;
      b_kind_q <= b_kind_d;
      b_segment_log2_q <= b_segment_log2_d;
      b_kim_pipelined_q <= b_kim_pipelined_d;
      b_density_log2_q <= b_density_log2_d;
      b_correction_q <= b_correction_d;
      b_persp_q <= b_persp_d;
      b_quadratic_q <= b_quadratic_d;
      band_lo_q <= band_lo_d;
      band_hi_q <= band_hi_d;
      band_lines_q <= band_lines_d;
      offset_q <= offset_d;
      span_offset_q <= span_offset_d;
      span_last_q <= span_last_d;
      major_q <= major_d;
      minor_q <= minor_d;
      last_q <= last_d;
      line_shift_q <= line_shift_d;
      direction_q <= direction_d;
      weight_q <= weight_d;
      lines_q <= lines_d;
      bands_q <= bands_d;
      pixels_q <= pixels_d;
      flags_q <= flags_d;
    end
  end

  // ---------------------------------------------------------------- outputs
  logic [PixelBits-1:0] frag_major, frag_minor;
  assign frag_major = mode_divide ? pipe_tag[PixelBits +: PixelBits] :
                      mode_kim ? kim_tag[PixelBits +: PixelBits] :
                      !per_pixel ? table_tag[PixelBits +: PixelBits] : major_q;
  assign frag_minor = mode_divide ? pipe_tag[0 +: PixelBits] : mode_kim ? kim_tag[0 +: PixelBits] :
                      !per_pixel ? table_tag[0 +: PixelBits] : minor_q;
  assign frag_valid_o = mode_divide ? pipe_valid : mode_kim ? kim_valid :
                        TablePipe && !per_pixel ? table_valid && !starve :
                        state_q == StPixel && (!mode_sub || sub_valid) && !starve;
  assign frag_x_o = setup_x_major ? 16'(frag_major) : 16'(frag_minor);
  assign frag_y_o = setup_x_major ? 16'(frag_minor) : 16'(frag_major);
  assign frag_u_o = 64'(frag_u);
  assign frag_v_o = 64'(frag_v);
  assign frag_flags_o = frag_flags;

  assign rec_valid_o = state_q == StRecord;
  logic [CountBits-1:0] record_cycles;  // this cycle included
  assign record_cycles = cycles_q + CountBits'(1);
  assign rec_cycles_o = 64'(record_cycles);
  assign rec_lines_o = 32'(lines_q);
  assign rec_bands_o = 32'(bands_q);
  assign rec_pixels_o = 32'(pixels_q);
  assign rec_flags_o = flags_q;

  localparam int TBits = `CD_T_BITS;
  localparam int SBits = `CD_S_BITS;
  // Observation: the setup results and the table writes (what the design
  // uses), or 0 when HasObservation is off (synthesis), so that the ports keep
  // no logic alive that the design itself does not need.
  logic [WordBits-1:0] observed_entry;
  assign observed_entry = HasObservation && HasTable ? write_entry : '0;
  always_comb begin
    obs_setup_valid_o = '0;
    obs_setup_bits_o = '0;
    obs_setup_g_o = '0;
    obs_setup_box_o = '0;
    obs_setup_lines_o = '0;
    obs_write_valid_o = '0;
    obs_write_addr_o = '0;
    if (HasObservation) begin
      obs_setup_valid_o = front_q == FrSetup && fcount_q == StepCountBits'(SetupCycles - 1) && !hold;
      obs_setup_bits_o[`CD_OBS_SETUP_EMPTY] = setup_empty;
      obs_setup_bits_o[`CD_OBS_SETUP_X_MAJOR] = s_x_major;
      obs_setup_bits_o[`CD_OBS_SETUP_NO_LINES] = setup_no_lines;
      obs_setup_bits_o[`CD_OBS_SETUP_DEPTH_RANGE] = setup_flags[`CD_FLAG_DEPTH_RANGE];
      obs_setup_box_o[`CD_OBS_BOX_MAJOR_LO +: 16] = 16'(s_major_lo);
      obs_setup_box_o[`CD_OBS_BOX_MAJOR_COUNT +: 16] = 16'(s_major_count);
      obs_setup_box_o[`CD_OBS_BOX_MINOR_LO +: 16] = 16'(s_minor_lo);
      obs_setup_box_o[`CD_OBS_BOX_MINOR_HI +: 16] = 16'(s_minor_hi);
      if (HasTable) begin
        obs_setup_g_o = 32'(s_g);
        obs_setup_lines_o[`CD_OBS_LINES_LO +: 32] = 32'(s_pixel_line_lo);
        obs_setup_lines_o[`CD_OBS_LINES_HI +: 32] = 32'(s_pixel_line_hi);
        obs_write_valid_o = write_valid;
        obs_write_addr_o = 32'(write_addr);
      end
    end
  end
  assign obs_write_tu_o = 64'($signed(observed_entry[`CD_WORD_TU_LSB +: TBits]));
  assign obs_write_tv_o = 64'($signed(observed_entry[`CD_WORD_TV_LSB +: TBits]));
  assign obs_write_su_o = 64'($signed(observed_entry[`CD_WORD_SU_LSB +: SBits]));
  assign obs_write_sv_o = 64'($signed(observed_entry[`CD_WORD_SV_LSB +: SBits]));
  logic observed_eps_saturated;
  if (Persp) begin : gen_observe_eps
    assign obs_write_eps_o = 64'($signed(observed_entry[`CD_WORD_EPS_LSB +: `CD_EPS_BITS]));
    assign observed_eps_saturated = observed_entry[`CD_WORD_EPS_SATURATED_BIT];
  end else begin : gen_observe_no_eps
    assign obs_write_eps_o = '0;
    assign observed_eps_saturated = 1'b0;
  end
  always_comb begin
    obs_write_flags_o = '0;
    obs_write_flags_o[`CD_OBS_WRITE_SATURATED] = observed_entry[`CD_WORD_SATURATED_BIT];
    obs_write_flags_o[`CD_OBS_WRITE_DEPTH_RANGE] = observed_entry[`CD_WORD_DEPTH_RANGE_BIT];
    obs_write_flags_o[`CD_OBS_WRITE_EPS_SATURATED] = observed_eps_saturated;
  end

`ifndef SYNTHESIS
  // Handshakes: a fragment or record offered and refused stays unchanged until
  // taken; table reads stay inside the band's lines.
  logic frag_stalled_q, rec_stalled_q;
  logic [15:0] frag_x_held_q, frag_y_held_q;
  logic [63:0] frag_u_held_q, frag_v_held_q;
  logic [7:0]  frag_flags_held_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      frag_stalled_q <= 1'b0;
      rec_stalled_q <= 1'b0;
    end else begin
      frag_stalled_q <= frag_valid_o && !frag_ready_i;
      rec_stalled_q <= rec_valid_o && !rec_ready_i;
      frag_x_held_q <= frag_x_o;
      frag_y_held_q <= frag_y_o;
      frag_u_held_q <= frag_u_o;
      frag_v_held_q <= frag_v_o;
      frag_flags_held_q <= frag_flags_o;
    end
  end
  always_ff @(posedge clk_i) begin
    if (frag_stalled_q) begin
      assert (frag_valid_o) else $error("cd_scan_unit: frag_valid_o dropped while stalled");
      assert (frag_x_o == frag_x_held_q && frag_y_o == frag_y_held_q && frag_u_o == frag_u_held_q &&
              frag_v_o == frag_v_held_q && frag_flags_o == frag_flags_held_q)
        else $error("cd_scan_unit: fragment changed while stalled");
    end
    if (rec_stalled_q) assert (rec_valid_o) else $error("cd_scan_unit: rec_valid_o dropped while stalled");
    if (read) begin
      assert (read_addr >= 0 && read_addr < band_lines_q)
        else $error("cd_scan_unit: table read at %0d outside the band's %0d lines", read_addr, band_lines_q);
      if (neighbour_read)
        assert (read_addr + BandBits'(direction_d) >= 0 && read_addr + BandBits'(direction_d) < band_lines_q)
          else $error("cd_scan_unit: neighbour read outside the band");
    end
    if (write_valid) assert (32'(write_addr) < SramDepth) else $error("cd_scan_unit: table write past the end");
  end
`endif

endmodule

`default_nettype wire
