// The adaptive design's split engine (Kamen & Shirman; docs/designs.md,
// "adaptive"): takes a triangle, splits it in four at its edge midpoints
// while linear interpolation misses u or v at a midpoint by more than
// 2^-BoundFrac texels, at most Depth times, and offers the leaves, depth
// first, to an affine unit at the leaves' widths. Twin of
// model/adaptive_split.cpp, cycle for cycle:
// - Idle: accepts a triangle (tri_ready_o). Intake: 1/w normalised as the
//   setup engine does, U = u q, V = v q; the root is current from the next
//   cycle.
// - Node (a node's first cycle): a sub-triangle whose clipped box holds no
//   pixel centre is dropped (1 cycle); a node at the depth limit (or the
//   root with nothing to cover) is offered in this cycle; any other node is
//   evaluated.
// - Eval: the midpoints registered in the node cycle, three reciprocals
//   issued in the next three cycles, each result multiplied and narrowed in
//   the cycle it arrives, the tests in the cycle after the last: split (the
//   corner-A child is current next, the others wait in its level) or offer the node.
// - Offer: the leaf waits for leaf_ready_i; the engine goes on in the cycle
//   after. tri_done_o follows a triangle's last node, with its flags.
// - hold_i (the unit behind it holds a fragment): nothing moves, as in the
//   unit, so that a stall delays everything by one cycle.
`default_nettype none

module adaptive_split #(
  parameter int SubpixelBits = 8,   // the input's
  parameter int UvInFrac     = 8,   // the input's
  parameter int QBits        = 24,
  parameter int RecipBits    = 24,
  parameter int RecipLatency = 4,
  parameter int Depth        = 3,   // adapt_depth
  parameter int BoundFrac    = 4,   // adapt_bound_frac
  parameter int UvExtra      = 4,   // adapt_uv_extra
  parameter int GuardBits    = 4,   // quotient_guard_bits
  localparam int CoordBits     = 16 + SubpixelBits,
  localparam int LeafCoordBits = CoordBits + Depth,
  localparam int UvBits        = 16 + UvInFrac,
  localparam int LeafUvFrac    = UvInFrac + UvExtra,
  localparam int LeafUvBits    = 16 + LeafUvFrac
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic                            hold_i,
  // Read while a triangle is in the engine: held from its acceptance to its
  // done (adaptive_unit.sv registers them).
  input  logic [13:0]                     viewport_width_i,
  input  logic [13:0]                     viewport_height_i,
  input  logic                            tri_valid_i,
  output logic                            tri_ready_o,
  // Vertex k of each field at [k W +: W]; 1/w as binary32.
  input  logic [3*CoordBits-1:0]          tri_x_i,
  input  logic [3*CoordBits-1:0]          tri_y_i,
  input  logic [95:0]                     tri_q_i,
  input  logic [3*UvBits-1:0]             tri_u_i,
  input  logic [3*UvBits-1:0]             tri_v_i,
  output logic                            leaf_valid_o,
  input  logic                            leaf_ready_i,
  output logic [3*LeafCoordBits-1:0]      leaf_x_o,
  output logic [3*LeafCoordBits-1:0]      leaf_y_o,
  output logic [95:0]                     leaf_q_o,
  output logic [3*LeafUvBits-1:0]         leaf_u_o,
  output logic [3*LeafUvBits-1:0]         leaf_v_o,
  output logic [7:0]                      leaf_depth_o,
  // The cycle after a triangle's last node (a leaf taken or a sub-triangle
  // dropped), with its flags: {output saturated, depth range}; held with
  // hold_i.
  output logic                            tri_done_o,
  output logic [1:0]                      tri_flags_o
);

  localparam int QVertexBits = QBits + 1;
  localparam int NodeQBits   = QVertexBits + Depth;          // unsigned
  localparam int BigBits     = QVertexBits + 1 + UvBits + Depth;  // signed U = u q, scaled
  localparam int DepthBits   = 8;
  localparam int Levels      = Depth > 0 ? Depth : 1;         // nodes split at depth 0 .. Depth - 1
  localparam int LevelBits   = $clog2(Levels + 1);
  // An index of the per-level arrays: narrower than LevelBits when Levels is
  // a power of two (adapt_depth 2, 4), which Verilator's WIDTH check refuses.
  localparam int IndexBits   = Levels > 1 ? $clog2(Levels) : 1;
  // The operand unit shifts q within its QBits and compares the exponent
  // with RecipBits: q is zero-extended to at least RecipBits + 1 bits and the
  // exponent holds both (q_bits 4 or recip_bits 32 refused the build).
  localparam int OperandQBits = NodeQBits + 1 > RecipBits + 1 ? NodeQBits + 1 : RecipBits + 1;
  localparam int ExpBits     = $clog2(OperandQBits) + 1;
  // A midpoint's U, V narrowed by e to LeafUvFrac + GuardBits fraction bits
  // and one integer bit more than a leaf's (cdsim::quotient), then times R.
  localparam int OperandBits = LeafUvBits + 1 + GuardBits;
  localparam int ProductBits = OperandBits + RecipBits + 2;
  localparam int ShiftBits   = ExpBits + 8;
  localparam int DiffBits    = LeafCoordBits + 1;
  localparam int DetBits     = 2 * DiffBits;
  localparam int LeafShift   = SubpixelBits + Depth;
  localparam int ErrorBits   = LeafUvBits + 3 + BoundFrac;

  // ------------------------------------------------------------- node storage
  typedef enum logic [2:0] { StIdle, StIntake, StNode, StEval, StOffer } state_t;
  state_t state_q;

  logic signed [LeafCoordBits-1:0] cur_x [3], cur_y [3];
  logic        [NodeQBits-1:0]     cur_q [3];
  logic signed [BigBits-1:0]       cur_bu [3], cur_bv [3];
  logic signed [LeafUvBits-1:0]    cur_u [3], cur_v [3];
  logic        [DepthBits-1:0]     cur_depth;

  // The levels (the depth-first walk's stack, one entry per depth): level d
  // holds the six vertices of the node split at depth d, at 6 d + slot
  // (slots 0-2 its vertices, 3-5 its edge midpoints m0, m1, m2; level 0's
  // first three are the triangle itself), which of its children comes next
  // (1 B's, 2 C's, 3 the middle; A's is taken as it splits), and whether any
  // is left. The deepest level with one left is the stack's top.
  logic signed [LeafCoordBits-1:0] lv_x [6*Levels], lv_y [6*Levels];
  logic        [NodeQBits-1:0]     lv_q [6*Levels];
  logic signed [BigBits-1:0]       lv_bu [6*Levels], lv_bv [6*Levels];
  logic signed [LeafUvBits-1:0]    lv_u [6*Levels], lv_v [6*Levels];
  logic        [1:0]               lv_next [Levels];
  logic        [Levels-1:0]        lv_open_q;

  // Midpoint j lies on the edge opposite vertex j.
  logic signed [LeafCoordBits-1:0] mid_x [3], mid_y [3];
  logic        [NodeQBits-1:0]     mid_q [3];
  logic signed [BigBits-1:0]       mid_bu [3], mid_bv [3];
  logic signed [LeafUvBits-1:0]    mid_u [3], mid_v [3];

  logic [31:0] in_q_q [3];
  logic signed [CoordBits-1:0] in_x_q [3], in_y_q [3];
  logic signed [UvBits-1:0]    in_u_q [3], in_v_q [3];

  logic       any_leaf_q;
  logic       done_q;
  logic [1:0] flags_q;         // {saturated, depth range}
  logic [7:0] eval_count_q;    // cycles since the node cycle

  // ------------------------------------------------------------------ intake
  logic [7:0]              max_exponent;
  logic signed [9:0]       q_shift [3];
  logic [33:0]             q_wide [3];
  logic [QVertexBits-1:0]  q_vertex [3];
  logic                    intake_depth_range;

  always_comb begin
    max_exponent = in_q_q[0][30:23];
    for (int i = 1; i < 3; i++) if (in_q_q[i][30:23] > max_exponent) max_exponent = in_q_q[i][30:23];
    intake_depth_range = 1'b0;
    for (int i = 0; i < 3; i++) begin
      q_shift[i] = $signed({2'b00, max_exponent - in_q_q[i][30:23]}) + 10'sd24 - 10'(QBits);
      q_wide[i] = {10'd0, 1'b1, in_q_q[i][22:0]};
      if (q_shift[i] <= 0) q_wide[i] = q_wide[i] << (-q_shift[i]);
      else if (q_shift[i] > 10'sd25) q_wide[i] = '0;
      else q_wide[i] = (q_wide[i] + (34'd1 << (q_shift[i] - 10'sd1))) >> q_shift[i];
      q_vertex[i] = QVertexBits'(q_wide[i]);
      if (q_vertex[i] == '0) intake_depth_range = 1'b1;
    end
  end

  // --------------------------------------------------- the current node's box
  logic signed [LeafCoordBits:0] min_x, max_x, min_y, max_y;
  logic signed [LeafCoordBits:0] x_lo, x_hi, y_lo, y_hi;
  logic signed [DiffBits-1:0]    dx1, dy1, dx2, dy2;
  logic signed [DetBits-1:0]     det;
  logic                          nothing;
  logic signed [LeafCoordBits:0] last_x, last_y;  // the viewport's last pixel

  assign last_x = (LeafCoordBits+1)'($signed({1'b0, viewport_width_i})) - (LeafCoordBits+1)'(1);
  assign last_y = (LeafCoordBits+1)'($signed({1'b0, viewport_height_i})) - (LeafCoordBits+1)'(1);

  localparam logic signed [LeafCoordBits:0] OnePx  = (LeafCoordBits+1)'(1) <<< LeafShift;
  localparam logic signed [LeafCoordBits:0] HalfPx = (LeafCoordBits+1)'(1) <<< (LeafShift - 1);

  always_comb begin
    min_x = (LeafCoordBits+1)'(cur_x[0]);
    max_x = min_x;
    min_y = (LeafCoordBits+1)'(cur_y[0]);
    max_y = min_y;
    for (int i = 1; i < 3; i++) begin
      if ((LeafCoordBits+1)'(cur_x[i]) < min_x) min_x = (LeafCoordBits+1)'(cur_x[i]);
      if ((LeafCoordBits+1)'(cur_x[i]) > max_x) max_x = (LeafCoordBits+1)'(cur_x[i]);
      if ((LeafCoordBits+1)'(cur_y[i]) < min_y) min_y = (LeafCoordBits+1)'(cur_y[i]);
      if ((LeafCoordBits+1)'(cur_y[i]) > max_y) max_y = (LeafCoordBits+1)'(cur_y[i]);
    end
    // The first pixel centre at or after min, the last at or before max.
    x_lo = (min_x - HalfPx + OnePx - 1) >>> LeafShift;
    x_hi = (max_x - HalfPx) >>> LeafShift;
    y_lo = (min_y - HalfPx + OnePx - 1) >>> LeafShift;
    y_hi = (max_y - HalfPx) >>> LeafShift;
    if (x_lo < 0) x_lo = '0;
    if (y_lo < 0) y_lo = '0;
    if (x_hi > last_x) x_hi = last_x;
    if (y_hi > last_y) y_hi = last_y;
    dx1 = DiffBits'(cur_x[1]) - DiffBits'(cur_x[0]);
    dy1 = DiffBits'(cur_y[1]) - DiffBits'(cur_y[0]);
    dx2 = DiffBits'(cur_x[2]) - DiffBits'(cur_x[0]);
    dy2 = DiffBits'(cur_y[2]) - DiffBits'(cur_y[0]);
    det = DetBits'(dx1) * DetBits'(dy2) - DetBits'(dx2) * DetBits'(dy1);
    nothing = det == '0 || x_lo > x_hi || y_lo > y_hi;
  end

  // ------------------------------------------------ reciprocals of midpoints
  logic [1:0]               issue_index;
  logic                     issue_valid;
  logic                     operand_depth_out;
  logic [ExpBits-1:0]       operand_exponent;
  logic [RecipBits:0]       operand_mantissa;
  logic                     recip_valid;
  logic [RecipBits:0]       recip;
  logic [ExpBits+2:0]       recip_tag;

  assign issue_valid = state_q == StEval && eval_count_q >= 8'd1 && eval_count_q <= 8'd3;
  assign issue_index = 2'(eval_count_q - 8'd1);

  reciprocal_operand #(.QBits(OperandQBits), .RecipBits(RecipBits), .ExponentBits(ExpBits)) u_operand (
    .enable_i    (issue_valid),
    .q_i         ($signed(OperandQBits'({1'b0, mid_q[issue_index]}))),
    .depth_out_o (operand_depth_out),
    .exponent_o  (operand_exponent),
    .mantissa_o  (operand_mantissa)
  );

  reciprocal #(.RecipBits(RecipBits), .Latency(RecipLatency), .TagBits(ExpBits + 3)) u_reciprocal (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .advance_i  (!hold_i),
    .valid_i    (issue_valid),
    .mantissa_i (operand_mantissa),
    .tag_i      ({operand_depth_out, issue_index, operand_exponent}),
    .valid_o    (recip_valid),
    .recip_o    (recip),
    .tag_o      (recip_tag)
  );

  logic [1:0]                    result_index;
  logic [ExpBits-1:0]            result_exponent;
  logic signed [ShiftBits-1:0]   operand_shift;
  logic signed [OperandBits-1:0] operand_u, operand_v;
  logic signed [ProductBits-1:0] product_u, product_v;
  logic signed [LeafUvBits-1:0]  result_u, result_v;
  logic [1:0]                    operand_saturated;
  logic                          saturated_u, saturated_v;
  localparam logic signed [ShiftBits-1:0] QuotientShift = ShiftBits'(RecipBits + GuardBits);

  always_comb begin
    result_index = recip_tag[ExpBits +: 2];
    result_exponent = recip_tag[ExpBits-1:0];
    // U 2^-uv_in_frac, by e to LeafUvFrac + GuardBits fraction bits.
    operand_shift = ShiftBits'($signed({1'b0, result_exponent})) - ShiftBits'(UvExtra + GuardBits);
  end

  shift_round #(.InBits(BigBits), .OutBits(OperandBits), .ShiftBits(ShiftBits),
                .MaxLeft(UvExtra + GuardBits)) u_operand_u (
    .enable_i (recip_valid), .in_i (mid_bu[result_index]), .shift_i (operand_shift),
    .out_o (operand_u), .saturated_o (operand_saturated[0]));
  shift_round #(.InBits(BigBits), .OutBits(OperandBits), .ShiftBits(ShiftBits),
                .MaxLeft(UvExtra + GuardBits)) u_operand_v (
    .enable_i (recip_valid), .in_i (mid_bv[result_index]), .shift_i (operand_shift),
    .out_o (operand_v), .saturated_o (operand_saturated[1]));

  always_comb begin
    product_u = ProductBits'(operand_u) * ProductBits'($signed({1'b0, recip}));
    product_v = ProductBits'(operand_v) * ProductBits'($signed({1'b0, recip}));
  end

  shift_round #(.InBits(ProductBits), .OutBits(LeafUvBits), .ShiftBits(ShiftBits)) u_round_u (
    .enable_i (recip_valid), .in_i (product_u), .shift_i (QuotientShift),
    .out_o (result_u), .saturated_o (saturated_u));
  shift_round #(.InBits(ProductBits), .OutBits(LeafUvBits), .ShiftBits(ShiftBits)) u_round_v (
    .enable_i (recip_valid), .in_i (product_v), .shift_i (QuotientShift),
    .out_o (result_v), .saturated_o (saturated_v));

  // ------------------------------------------------------------------ tests
  localparam logic [ErrorBits-1:0] Limit = ErrorBits'(1) << (LeafUvFrac + 1);

  function automatic logic misses(input logic signed [LeafUvBits-1:0] a,
                                  input logic signed [LeafUvBits-1:0] b,
                                  input logic signed [LeafUvBits-1:0] m);
    logic signed [ErrorBits-1:0] error;
    logic [ErrorBits-1:0] magnitude;
    begin
      error = ErrorBits'(a) + ErrorBits'(b) - (ErrorBits'(m) <<< 1);
      magnitude = error < 0 ? ErrorBits'(-error) : ErrorBits'(error);
      misses = (magnitude << BoundFrac) > Limit;
    end
  endfunction

  logic split;
  always_comb begin
    split = 1'b0;
    for (int j = 0; j < 3; j++)
      split = split || misses(cur_u[(j + 1) % 3], cur_u[(j + 2) % 3], mid_u[j]) ||
              misses(cur_v[(j + 1) % 3], cur_v[(j + 2) % 3], mid_v[j]);
  end

  // ------------------------------------------------------------------ output
  always_comb begin
    leaf_q_o = '0;
    for (int k = 0; k < 3; k++) begin
      leaf_x_o[k*LeafCoordBits +: LeafCoordBits] = cur_x[k];
      leaf_y_o[k*LeafCoordBits +: LeafCoordBits] = cur_y[k];
      leaf_u_o[k*LeafUvBits +: LeafUvBits] = cur_u[k];
      leaf_v_o[k*LeafUvBits +: LeafUvBits] = cur_v[k];
      // q as binary32, the mantissa truncated.
      for (int b = 0; b < NodeQBits; b++) begin
        if (cur_q[k][b]) begin
          leaf_q_o[k*32 + 23 +: 8] = 8'(b + 127);
          if (b >= 23) leaf_q_o[k*32 +: 23] = 23'(64'(cur_q[k]) >> (b - 23));
          else leaf_q_o[k*32 +: 23] = 23'(64'(cur_q[k]) << (23 - b));
        end
      end
    end
  end

  logic drop;     // in a node cycle: a sub-triangle with nothing to cover
  logic at_leaf;  // in a node cycle: offered now
  assign drop = state_q == StNode && nothing && cur_depth != '0;
  assign at_leaf = state_q == StNode && !drop && (cur_depth == DepthBits'(Depth) || nothing);
  assign leaf_valid_o = at_leaf || state_q == StOffer;
  assign leaf_depth_o = cur_depth;
  assign tri_done_o = done_q;
  assign tri_flags_o = flags_q;
  assign tri_ready_o = state_q == StIdle && !hold_i;

  // ------------------------------------------------------------------- state
  // Vertex k of child c (0 A's, 1 B's, 2 C's, 3 the middle) among its
  // parent's six: A (v0, m2, m1), B (m2, v1, m0), C (m1, m0, v2), the
  // middle (m2, m0, m1), each with the parent's orientation.
  function automatic logic [2:0] child_slot(input logic [1:0] child, input logic [1:0] k);
    logic [8:0] slots;  // vertex 0's slot in the low bits
    begin
      case (child)
        2'd0: slots = {3'd4, 3'd5, 3'd0};
        2'd1: slots = {3'd3, 3'd1, 3'd5};
        2'd2: slots = {3'd2, 3'd3, 3'd4};
        default: slots = {3'd4, 3'd3, 3'd5};
      endcase
      child_slot = slots[3 * k +: 3];
    end
  endfunction

  logic                 any_open;
  logic [LevelBits-1:0] open_level;  // the deepest level with a child left
  logic [1:0]           open_child;
  logic [LevelBits-1:0] split_level;
  always_comb begin
    any_open = 1'b0;
    open_level = '0;
    for (int l = 0; l < Levels; l++)
      if (lv_open_q[l]) begin
        any_open = 1'b1;
        open_level = LevelBits'(l);
      end
    open_child = lv_next[IndexBits'(open_level)];
    split_level = LevelBits'(cur_depth);
  end

  // The next node after this one is done: the deepest level's next child,
  // else (nothing sent) the whole triangle, else idle.
  task automatic next_node(input logic leaf_sent);
    begin
      if (any_open) begin
        for (int k = 0; k < 3; k++) begin
          cur_x[k] <= lv_x[6 * open_level + child_slot(open_child, 2'(k))];
          cur_y[k] <= lv_y[6 * open_level + child_slot(open_child, 2'(k))];
          cur_q[k] <= lv_q[6 * open_level + child_slot(open_child, 2'(k))];
          cur_bu[k] <= lv_bu[6 * open_level + child_slot(open_child, 2'(k))];
          cur_bv[k] <= lv_bv[6 * open_level + child_slot(open_child, 2'(k))];
          cur_u[k] <= lv_u[6 * open_level + child_slot(open_child, 2'(k))];
          cur_v[k] <= lv_v[6 * open_level + child_slot(open_child, 2'(k))];
        end
        cur_depth <= DepthBits'(open_level) + DepthBits'(1);
        if (open_child == 2'd3) lv_open_q[IndexBits'(open_level)] <= 1'b0;
        else lv_next[IndexBits'(open_level)] <= open_child + 2'd1;
        state_q <= StNode;
      end else if (!leaf_sent && !any_leaf_q) begin
        // Every sub-triangle was dropped: the triangle was split, so level 0 holds it.
        for (int k = 0; k < 3; k++) begin
          cur_x[k] <= lv_x[k];
          cur_y[k] <= lv_y[k];
          cur_q[k] <= lv_q[k];
          cur_u[k] <= lv_u[k];
          cur_v[k] <= lv_v[k];
        end
        cur_depth <= '0;
        state_q <= StOffer;
      end else begin
        state_q <= StIdle;
        done_q <= 1'b1;
      end
    end
  endtask

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= StIdle;
      lv_open_q <= '0;
      any_leaf_q <= 1'b0;
      flags_q <= '0;
      eval_count_q <= '0;
      done_q <= 1'b0;
    end else if (!hold_i) begin
      done_q <= 1'b0;
      case (state_q)
        StIdle: if (tri_valid_i) begin
          for (int k = 0; k < 3; k++) begin
            in_x_q[k] <= tri_x_i[k*CoordBits +: CoordBits];
            in_y_q[k] <= tri_y_i[k*CoordBits +: CoordBits];
            in_q_q[k] <= tri_q_i[k*32 +: 32];
            in_u_q[k] <= tri_u_i[k*UvBits +: UvBits];
            in_v_q[k] <= tri_v_i[k*UvBits +: UvBits];
          end
          state_q <= StIntake;
        end
        StIntake: begin
          for (int k = 0; k < 3; k++) begin
            cur_x[k] <= LeafCoordBits'(in_x_q[k]) <<< Depth;
            cur_y[k] <= LeafCoordBits'(in_y_q[k]) <<< Depth;
            cur_q[k] <= NodeQBits'(q_vertex[k]) << Depth;
            cur_bu[k] <= (BigBits'($signed({1'b0, q_vertex[k]})) * BigBits'(in_u_q[k])) <<< Depth;
            cur_bv[k] <= (BigBits'($signed({1'b0, q_vertex[k]})) * BigBits'(in_v_q[k])) <<< Depth;
            cur_u[k] <= LeafUvBits'(in_u_q[k]) <<< UvExtra;
            cur_v[k] <= LeafUvBits'(in_v_q[k]) <<< UvExtra;
          end
          cur_depth <= '0;
          any_leaf_q <= 1'b0;
          flags_q <= {1'b0, intake_depth_range};
          state_q <= StNode;
        end
        StNode: begin
          if (drop) begin
            next_node(1'b0);
          end else if (at_leaf) begin
            if (leaf_ready_i) begin
              any_leaf_q <= 1'b1;
              next_node(1'b1);
            end else begin
              state_q <= StOffer;
            end
          end else begin
            for (int j = 0; j < 3; j++) begin
              mid_x[j] <= LeafCoordBits'((DiffBits'(cur_x[(j + 1) % 3]) + DiffBits'(cur_x[(j + 2) % 3])) >>> 1);
              mid_y[j] <= LeafCoordBits'((DiffBits'(cur_y[(j + 1) % 3]) + DiffBits'(cur_y[(j + 2) % 3])) >>> 1);
              mid_q[j] <= NodeQBits'(((NodeQBits+1)'(cur_q[(j + 1) % 3]) + (NodeQBits+1)'(cur_q[(j + 2) % 3])) >> 1);
              mid_bu[j] <= BigBits'(((BigBits+1)'(cur_bu[(j + 1) % 3]) + (BigBits+1)'(cur_bu[(j + 2) % 3])) >>> 1);
              mid_bv[j] <= BigBits'(((BigBits+1)'(cur_bv[(j + 1) % 3]) + (BigBits+1)'(cur_bv[(j + 2) % 3])) >>> 1);
            end
            eval_count_q <= 8'd1;
            state_q <= StEval;
          end
        end
        StEval: begin
          eval_count_q <= eval_count_q + 8'd1;
          if (recip_valid) begin
            mid_u[result_index] <= result_u;
            mid_v[result_index] <= result_v;
            if (saturated_u || saturated_v || |operand_saturated) flags_q[1] <= 1'b1;
            if (recip_tag[ExpBits + 2]) flags_q[0] <= 1'b1;
          end
          if (eval_count_q == 8'(RecipLatency + 4)) begin
            eval_count_q <= '0;
            if (split) begin
              // Corner A's child is current; B's, C's and the middle wait in this level.
              cur_x[1] <= mid_x[2]; cur_y[1] <= mid_y[2]; cur_q[1] <= mid_q[2];
              cur_bu[1] <= mid_bu[2]; cur_bv[1] <= mid_bv[2]; cur_u[1] <= mid_u[2]; cur_v[1] <= mid_v[2];
              cur_x[2] <= mid_x[1]; cur_y[2] <= mid_y[1]; cur_q[2] <= mid_q[1];
              cur_bu[2] <= mid_bu[1]; cur_bv[2] <= mid_bv[1]; cur_u[2] <= mid_u[1]; cur_v[2] <= mid_v[1];
              cur_depth <= cur_depth + DepthBits'(1);
              for (int k = 0; k < 3; k++) begin
                lv_x[6 * split_level + k] <= cur_x[k];     lv_x[6 * split_level + 3 + k] <= mid_x[k];
                lv_y[6 * split_level + k] <= cur_y[k];     lv_y[6 * split_level + 3 + k] <= mid_y[k];
                lv_q[6 * split_level + k] <= cur_q[k];     lv_q[6 * split_level + 3 + k] <= mid_q[k];
                lv_bu[6 * split_level + k] <= cur_bu[k];   lv_bu[6 * split_level + 3 + k] <= mid_bu[k];
                lv_bv[6 * split_level + k] <= cur_bv[k];   lv_bv[6 * split_level + 3 + k] <= mid_bv[k];
                lv_u[6 * split_level + k] <= cur_u[k];     lv_u[6 * split_level + 3 + k] <= mid_u[k];
                lv_v[6 * split_level + k] <= cur_v[k];     lv_v[6 * split_level + 3 + k] <= mid_v[k];
              end
              lv_next[IndexBits'(split_level)] <= 2'd1;
              lv_open_q[IndexBits'(split_level)] <= 1'b1;
              state_q <= StNode;
            end else begin
              state_q <= StOffer;
            end
          end
        end
        StOffer: if (leaf_ready_i) begin
          any_leaf_q <= 1'b1;
          next_node(1'b1);
        end
        default: state_q <= StIdle;
      endcase
    end
  end

endmodule

`default_nettype wire
