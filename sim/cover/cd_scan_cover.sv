// User cover points of cd_scan_unit for `cdsim regress --coverage`, bound into
// the unit by the `bind` at the end (verification collateral: rtl/ holds none
// of it, so synthesis and the area caches never see it). Each point is named
// c_<what> and counts the clock edges at which it holds; docs/coverage.md lists
// them and what the CI regression set leaves uncovered.
`include "cd_widths.svh"

module cd_scan_cover (
  input logic       clk_i,
  input logic       rst_ni,
  input logic [`CD_STATE_BITS-1:0] state_q,
  input logic [`CD_FRONT_BITS-1:0] front_q,
  input logic [`CD_FILL_BITS-1:0] fill_q,
  input logic [1:0] full_q,
  input logic       walk_bank_q,
  input logic       take,
  input logic       starve,
  input logic [`CD_KIND_BITS-1:0] kind_q,
  input logic [2:0] segment_log2_q,
  input logic       kim_pipelined_q,
  input logic [1:0] density_log2_q,
  input logic       correction_q,
  input logic       persp_q,
  input logic       quadratic_q,
  input logic       frag_valid_o,
  input logic       frag_ready_i,
  input logic       rec_valid_o,
  input logic       rec_ready_i,  // always 1 in the bench: a record is taken when valid
  /* verilator lint_off UNUSEDSIGNAL */  // the flags above CD_FLAG_COUNT, the spare setup bits
  input logic [7:0] rec_flags_o,
  input logic       obs_setup_valid_o,
  input logic [7:0] obs_setup_bits_o
  /* verilator lint_on UNUSEDSIGNAL */
);
  // The back's states (cd_scan_unit.sv state_e; CD_STATE_*, model/encodings.def).
  c_state_idle:      cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_IDLE);
  c_state_fill_wait: cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_FILL_WAIT);
  c_state_init:      cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_INIT);
  c_state_column:    cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_COLUMN);
  c_state_pixel:     cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_PIXEL);
  c_state_scan:      cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_SCAN);
  c_state_record:    cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_RECORD);
  c_state_drain:     cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_DRAIN);
  // The front's (FrIdle .. FrFillHeld) and the fill's (FlIdle .. FlBandWait),
  // and the overlap: the next triangle set up while the back walks, a band
  // filled while the back walks another, a band in the table before the back
  // asks for it, and a triangle taken in the cycle of the last one's record.
  c_front_setup:      cover property (@(posedge clk_i) rst_ni && front_q == `CD_FRONT_SETUP);
  c_front_offer:      cover property (@(posedge clk_i) rst_ni && front_q == `CD_FRONT_OFFER);
  c_front_fill_held:  cover property (@(posedge clk_i) rst_ni && front_q == `CD_FRONT_FILL_HELD);
  c_fill_filling:     cover property (@(posedge clk_i) rst_ni && fill_q == `CD_FILL_FILLING);
  c_fill_band_wait:   cover property (@(posedge clk_i) rst_ni && fill_q == `CD_FILL_BAND_WAIT);
  c_setup_during_walk: cover property (@(posedge clk_i) rst_ni && front_q == `CD_FRONT_SETUP &&
                                       (state_q == `CD_STATE_COLUMN || state_q == `CD_STATE_PIXEL));
  c_fill_during_walk: cover property (@(posedge clk_i) rst_ni && fill_q == `CD_FILL_FILLING &&
                                      (state_q == `CD_STATE_COLUMN || state_q == `CD_STATE_PIXEL));
  c_band_filled_ahead: cover property (@(posedge clk_i) rst_ni && state_q == `CD_STATE_FILL_WAIT && full_q[walk_bank_q]);
  c_take_at_record:   cover property (@(posedge clk_i) rst_ni && take && state_q == `CD_STATE_RECORD);
  // early_walk: the back walks a band whose fill has not ended, and stalls for
  // a line not yet written (or for the fill's end, to end the band).
  c_walk_during_own_fill: cover property (@(posedge clk_i) rst_ni && kind_q == `CD_KIND_CONSTANT_DEPTH && !full_q[walk_bank_q] &&
                                          (state_q == `CD_STATE_COLUMN || state_q == `CD_STATE_PIXEL));
  c_walk_starved:     cover property (@(posedge clk_i) rst_ni && starve);

  // Back-pressure: a fragment held by the sink (the bench never holds a record),
  // and such a hold freezing a triangle in setup.
  c_fragment_stall: cover property (@(posedge clk_i) rst_ni && frag_valid_o && !frag_ready_i);
  c_hold_in_setup:  cover property (@(posedge clk_i) rst_ni && frag_valid_o && !frag_ready_i && front_q == `CD_FRONT_SETUP);

  // Triangles finished with each flag (model/flags.hpp): a band refill sets
  // banded; the saturations are those of the table and of the output.
  wire record = rst_ni && rec_valid_o && rec_ready_i;
  c_flag_table_saturated:    cover property (@(posedge clk_i) record && rec_flags_o[`CD_FLAG_TABLE_SATURATED]);
  c_flag_output_saturated:   cover property (@(posedge clk_i) record && rec_flags_o[`CD_FLAG_OUTPUT_SATURATED]);
  c_flag_depth_range:        cover property (@(posedge clk_i) record && rec_flags_o[`CD_FLAG_DEPTH_RANGE]);
  c_flag_banded:             cover property (@(posedge clk_i) record && rec_flags_o[`CD_FLAG_BANDED]);
  c_flag_neighbour_dropped:  cover property (@(posedge clk_i) record && rec_flags_o[`CD_FLAG_NEIGHBOUR_DROPPED]);

  // Both scan orientations, and empty and line-less triangles.
  wire setup = rst_ni && obs_setup_valid_o;
  c_x_major:  cover property (@(posedge clk_i) setup && !obs_setup_bits_o[`CD_OBS_SETUP_EMPTY] && obs_setup_bits_o[`CD_OBS_SETUP_X_MAJOR]);
  c_y_major:  cover property (@(posedge clk_i) setup && !obs_setup_bits_o[`CD_OBS_SETUP_EMPTY] && !obs_setup_bits_o[`CD_OBS_SETUP_X_MAJOR]);
  c_empty:    cover property (@(posedge clk_i) setup && obs_setup_bits_o[`CD_OBS_SETUP_EMPTY]);
  c_no_lines: cover property (@(posedge clk_i) setup && !obs_setup_bits_o[`CD_OBS_SETUP_EMPTY] && obs_setup_bits_o[`CD_OBS_SETUP_NO_LINES]);

  // A triangle of every design finished (model/design.cpp's kind and options).
  wire cd = record && kind_q == `CD_KIND_CONSTANT_DEPTH;
  c_design_cd_none:          cover property (@(posedge clk_i) cd && density_log2_q == 2'd0 && !correction_q);
  c_design_cd_linear:        cover property (@(posedge clk_i) cd && density_log2_q == 2'd0 && correction_q && !persp_q);
  c_design_cd_persp:         cover property (@(posedge clk_i) cd && density_log2_q == 2'd0 && correction_q && persp_q);
  c_design_cd_dense2:        cover property (@(posedge clk_i) cd && density_log2_q == 2'd1 && !correction_q);
  c_design_cd_dense4:        cover property (@(posedge clk_i) cd && density_log2_q == 2'd2 && !correction_q);
  c_design_cd_dense2_linear: cover property (@(posedge clk_i) cd && density_log2_q == 2'd1 && correction_q);
  c_design_divide:           cover property (@(posedge clk_i) record && kind_q == `CD_KIND_DIVIDE);
  c_design_kim_iter:         cover property (@(posedge clk_i) record && kind_q == `CD_KIND_KIM && !kim_pipelined_q);
  c_design_kim_pipe:         cover property (@(posedge clk_i) record && kind_q == `CD_KIND_KIM && kim_pipelined_q);
  wire sub = record && kind_q == `CD_KIND_AFFINE;
  c_design_affine_sub16:     cover property (@(posedge clk_i) sub && segment_log2_q == 3'd4 && !quadratic_q);
  c_design_affine_sub8:      cover property (@(posedge clk_i) sub && segment_log2_q == 3'd3 && !quadratic_q);
  c_design_quad_sub16:       cover property (@(posedge clk_i) sub && segment_log2_q == 3'd4 && quadratic_q);
  c_design_quad_sub8:        cover property (@(posedge clk_i) sub && segment_log2_q == 3'd3 && quadratic_q);
  c_design_quad_sub32:       cover property (@(posedge clk_i) sub && segment_log2_q == 3'd5 && quadratic_q);
  c_design_affine:           cover property (@(posedge clk_i) record && kind_q == `CD_KIND_AFFINE && segment_log2_q == 3'd0);
  // cd-linear-div, cd-persp-div: a triangle the divide fallback walked (the
  // back's kind is divide, its design select a constant-depth one's).
  c_design_fallback:         cover property (@(posedge clk_i) record && kind_q == `CD_KIND_DIVIDE && correction_q);
endmodule

bind cd_scan_unit cd_scan_cover u_cover (
  .clk_i, .rst_ni, .state_q, .front_q, .fill_q, .full_q, .walk_bank_q, .take, .starve, .kind_q, .segment_log2_q, .kim_pipelined_q, .density_log2_q,
  .correction_q, .persp_q, .quadratic_q, .frag_valid_o, .frag_ready_i, .rec_valid_o, .rec_ready_i, .rec_flags_o,
  .obs_setup_valid_o, .obs_setup_bits_o);
