// rt_octree_slot: the walk of one ray in flight in rt_octree (docs/octree-unit.md,
// "Micro-architecture of rt_octree"): its state machine, the current node's
// plane parameters, the stack and the DESCEND and advance steps.
//
//   FREE -alloc-> SETUP -init-> ENTER (root test passes) | DONE
//   ENTER -visit grant-> GROUP_REQ (interior) | FETCH (leaf, count > 0) | CHECK (empty leaf)
//   GROUP_REQ -node grant-> WAIT_GROUP -node response-> DESCEND -> ENTER | NEXT
//   FETCH: one index request per index grant; -> CHECK once every result is in
//   CHECK without a hit: advance now; with a hit: on the check grant DONE if it
//   holds, else advance
//   NEXT: advance
//   advance: DONE at depth 0; sibling -> ENTER | REFILL_REQ | NEXT; pop -> NEXT | DONE
//   REFILL_REQ -node grant-> WAIT_REFILL -node response-> ENTER
//   DONE -done grant-> FREE
//
// Every step after setup is additions, halvings, comparisons and table look-ups
// (fx::firstChild, fx::nextChild). Halvings are exact, so the stack holds no
// parameters: a child's [t0, t1] on an axis gives its parent's back
// (t0_parent = 2 t0 - t1 on the upper half, t1_parent = 2 t1 - t0 on the lower),
// and a sibling step on the exit axis x is t0 <- t1, t1 <- 2 t1 - t0.
//
// The records read by slot index live in rt_octree (the ray, the closest hit,
// the counters, the child group); the slot names the current node's record in
// the group by `sel_o` (its index there: child ^ a) and takes the record when
// its visit is granted (visit_rec_i). Observably the same as holding `rec`.
//
// An axis the ray never crosses has t0 = -inf, t1 = +inf (no value), and its
// mid-plane parameter is +inf below the node's mid-plane, -inf on or above it.
// On such an axis the walk always takes the child that holds o' (table 1 puts
// -inf before any entry parameter and +inf after), and no sibling step ever
// moves along it (its t1 is +inf), so the node's lower corner on that axis is
// o' with its low P - depth bits cleared, and "o' below the mid-plane" is bit
// P-1-depth of o' being 0. (Rays need some non-zero direction component.)
//
// Latency: every transition takes one clock edge. Throughput: one node step
// per slot per cycle at most; the slots work concurrently.
module rt_octree_slot (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Allocation (a ray was accepted for this slot) and setup results.
  input  logic                                   alloc_i,
  input  logic                                   init_i,
  input  logic                                   init_enter_i,   // the root test passes
  input  logic [2:0]                             init_mirror_i,
  input  logic [2:0]                             init_active_i,
  input  logic [3*(rt_pkg::POS_W+1)-1:0]         init_origin_i,
  input  logic [3*rt_pkg::OCTREE_T_W-1:0]        init_t0_i,
  input  logic [3*rt_pkg::OCTREE_T_W-1:0]        init_t1_i,

  // Grants and responses addressed to this slot.
  input  logic                                   visit_gnt_i,
  input  rt_pkg::octree_node_t                   visit_rec_i,    // the current node's record
  input  logic                                   node_gnt_i,
  input  logic                                   node_rsp_i,     // its child group arrives
  input  logic                                   idx_gnt_i,
  input  logic                                   res_i,          // an isect result of this ray
  input  logic                                   has_hit_i,
  input  logic                                   check_gnt_i,
  input  logic                                   check_holds_i,
  input  logic                                   done_gnt_i,

  // Requests and state.
  output logic                                   free_o,
  output logic                                   want_visit_o,   // in ENTER
  output logic                                   want_node_o,    // in GROUP_REQ or REFILL_REQ
  output logic                                   want_idx_o,
  output logic                                   want_check_o,
  output logic                                   want_done_o,
  output logic                                   fetching_o,     // in FETCH (results may arrive)
  output logic                                   waiting_node_o, // in WAIT_GROUP or WAIT_REFILL
  output logic                                   at_root_o,      // depth 0: the record is cfg_root_i
  output logic [2:0]                             sel_o,          // the record's index in the group
  output logic [31:0]                            node_id_o,
  output logic [31:0]                            node_addr_o,    // the child group to read
  output logic [31:0]                            idx_addr_o,     // first + issued
  output logic [rt_pkg::OCTREE_T_W-1:0]          exit_o          // min t1 over the active axes
);

  // One copy of the slot's code in the Verilated model for every instance (32 or
  // 256 inlined copies only fill the instruction cache).
  /* verilator no_inline_module */

  localparam int P       = rt_pkg::POS_W;
  localparam int T_W     = rt_pkg::OCTREE_T_W;
  localparam int ORG_W   = P + 1;
  localparam int DEPTH_W = $clog2(rt_pkg::OCTREE_MAX_DEPTH + 1);
  localparam int STACK   = rt_pkg::OCTREE_MAX_DEPTH;             // levels 0 .. P-1
  localparam int STK_W   = (STACK > 1) ? $clog2(STACK) : 1;

  typedef enum logic [3:0] {
    FREE        = 4'd0,
    SETUP       = 4'd1,
    ENTER       = 4'd2,
    GROUP_REQ   = 4'd3,
    WAIT_GROUP  = 4'd4,
    DESCEND     = 4'd5,
    FETCH       = 4'd6,
    CHECK       = 4'd7,
    NEXT        = 4'd8,
    REFILL_REQ  = 4'd9,
    WAIT_REFILL = 4'd10,
    DONE        = 4'd11
  } slot_state_e;

  // Rank of a parameter in the order -inf < finite < +inf.
  localparam logic [1:0] NEG_INF = 2'd0;
  localparam logic [1:0] FINITE  = 2'd1;
  localparam logic [1:0] POS_INF = 2'd2;

  // a < b for parameters that may be infinite (fx::OctT::operator<).
  function automatic logic t_lt(input logic [1:0] ra, input logic signed [T_W-1:0] a,
                                input logic [1:0] rb, input logic signed [T_W-1:0] b);
    t_lt = (ra < rb) || (ra == FINITE && rb == FINITE && a < b);
  endfunction

  // The exit axis (fx::nextChild): the smallest t1, exact ties to the later
  // axis; an inactive axis has t1 = +inf.
  function automatic logic [1:0] exit_axis(input logic [2:0] active, input logic signed [T_W-1:0] x,
                                           input logic signed [T_W-1:0] y, input logic signed [T_W-1:0] z);
    logic [1:0] rx, ry, rz;
    rx = active[0] ? FINITE : POS_INF;
    ry = active[1] ? FINITE : POS_INF;
    rz = active[2] ? FINITE : POS_INF;
    if (t_lt(rx, x, ry, y)) begin
      exit_axis = t_lt(rx, x, rz, z) ? 2'd0 : 2'd2;
    end else begin
      exit_axis = t_lt(ry, y, rz, z) ? 2'd1 : 2'd2;
    end
  endfunction

  // The smallest t1 over the active axes (the exit test's parameter).
  function automatic logic [T_W-1:0] min_active(input logic [2:0] active, input logic signed [T_W-1:0] x,
                                                input logic signed [T_W-1:0] y, input logic signed [T_W-1:0] z);
    min_active = '1;
    if (active[0]) min_active = x;
    if (active[1] && (!active[0] || y < x)) min_active = y;
    if (active[2] && (!(active[0] || active[1]) || z < $signed(min_active))) min_active = z;
  endfunction

  slot_state_e           state_q;
  logic [2:0]            mirror_q, active_q;
  logic [ORG_W-1:0]      org_x_q, org_y_q, org_z_q;        // o'
  logic signed [T_W-1:0] t0_x_q, t0_y_q, t0_z_q;           // the current node's parameters
  logic signed [T_W-1:0] t1_x_q, t1_y_q, t1_z_q;
  logic [T_W-1:0]        exit_q;                           // min t1 over the active axes
  logic [DEPTH_W-1:0]    depth_q;
  logic [31:0]           node_id_q, node_addr_q, idx_addr_q;
  logic [2:0]            sel_q;
  logic                  group_valid_q;
  logic [31:0]           first_q, count_q, issued_q, received_q;
  logic [31:0]           stack_first_q [STACK];
  logic [2:0]            stack_child_q [STACK];

  // The entry at depth - 1: the parent's group base and which child the walk is in.
  logic [STK_W-1:0]      top_idx;
  logic [31:0]           top_first;
  logic [2:0]            top_child;
  assign top_idx   = STK_W'(depth_q - 1'b1);
  assign top_first = stack_first_q[top_idx];
  assign top_child = stack_child_q[top_idx];

  // ---- The walk: state machine and datapath in one clocked process ----------------
  // Each state's work sits in its branch: a slot that waits costs a simulator
  // one test of its event. In the branch that steps (DESCEND, CHECK, NEXT)
  // every decision is taken from the registers first, then the registers are
  // written (and no later branch reads what an earlier one writes), so a
  // simulator keeps no shadow copies of them. The state has the asynchronous
  // reset; the datapath registers are written before they are read.
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_walk
    logic signed [T_W-1:0] t0 [3];    // the current node's parameters
    logic signed [T_W-1:0] t1 [3];
    logic signed [T_W-1:0] tm [3];    // DESCEND: mid-plane parameters
    logic signed [T_W-1:0] n0 [3];    // the next node's parameters
    logic signed [T_W-1:0] n1 [3];
    logic [ORG_W-1:0]      org [3];
    logic [1:0]            r0 [3];    // ranks of t0 and tm
    logic [1:0]            rm [3];
    logic [DEPTH_W-1:0]    mid_bit;   // the bit of o' that says which half holds it
    logic [1:0]            entry, xa;
    logic [2:0]            c, bits, sel;
    logic                  behind, descend, sibling, pop;
    slot_state_e           nx_state;
    if (!rst_ni) begin
      state_q <= FREE;
    end else begin
`ifdef RT_ASSERT_ON
      // Checks of the events addressed to the slot (immediate, so that a
      // simulator tests them only in the slots they name; rt_octree checks
      // the responses' tags).
      if (alloc_i) a_alloc_free : assert (state_q == FREE);
      if (init_i) a_init_setup : assert (state_q == SETUP);
      if (visit_gnt_i) a_visit_enter : assert (state_q == ENTER);
      if (idx_gnt_i) a_idx_fetch : assert (state_q == FETCH && issued_q != count_q);
      if (res_i) a_res_fetch : assert (state_q == FETCH && received_q != issued_q);
      // An interior node one lattice unit wide cannot be split: the image is malformed.
      if (state_q == DESCEND) a_stack_depth : assert (depth_q < DEPTH_W'(STACK));
`endif
      case (state_q)
        DESCEND, CHECK, NEXT: begin
          // ---- Decisions ----
          descend  = (state_q == DESCEND);
          sibling  = 1'b0;
          pop      = 1'b0;
          behind   = 1'b0;
          c        = '0;
          nx_state = state_q;
          t0[0] = t0_x_q;  t0[1] = t0_y_q;  t0[2] = t0_z_q;
          t1[0] = t1_x_q;  t1[1] = t1_y_q;  t1[2] = t1_z_q;
          for (int a = 0; a < 3; a++) begin
            n0[a] = t0[a];
            n1[a] = t1[a];
          end
          if (descend) begin
            // Mid-plane parameters (exact halvings), the first child (table 1),
            // the child's parameters.
            org[0] = org_x_q; org[1] = org_y_q; org[2] = org_z_q;
            mid_bit = DEPTH_W'(P - 1) - depth_q;
            for (int a = 0; a < 3; a++) begin
              // (t0 + t1) / 2 without the carry bit: t0 and t1 have the same parity.
              tm[a] = (t0[a] >>> 1) + (t1[a] >>> 1) + $signed({{(T_W-1){1'b0}}, t0[a][0] & t1[a][0]});
              r0[a] = active_q[a] ? FINITE : NEG_INF;
              rm[a] = active_q[a] ? FINITE : (org[a][mid_bit] ? NEG_INF : POS_INF);
            end
            // The entry plane: the axis of the largest t0 (fx::firstChild's order).
            if (t_lt(r0[1], t0[1], r0[0], t0[0])) begin
              entry = t_lt(r0[2], t0[2], r0[0], t0[0]) ? 2'd0 : 2'd2;
            end else begin
              entry = t_lt(r0[2], t0[2], r0[1], t0[1]) ? 2'd1 : 2'd2;
            end
            for (int a = 0; a < 3; a++) begin
              if (32'(a) != 32'(entry) && t_lt(rm[a], tm[a], r0[entry], t0[entry])) c[2-a] = 1'b1;
            end
            for (int a = 0; a < 3; a++) begin
              if (active_q[a]) begin
                if (c[2-a]) begin
                  n0[a] = tm[a];
                end else begin
                  n1[a] = tm[a];
                end
                if (n1[a] < 0) behind = 1'b1;
              end
            end
            nx_state = behind ? NEXT : ENTER;
          end else if (state_q == CHECK && has_hit_i && !check_gnt_i) begin
            nx_state = CHECK;                       // waits for the exit test
          end else if (state_q == CHECK && has_hit_i && check_holds_i) begin
            nx_state = DONE;                        // the hit lies in the leaf
          end else if (depth_q == '0) begin
            nx_state = DONE;                        // advance from the root
          end else begin
            // advance (fx::nextChild): the exit axis of the current node.
            xa   = exit_axis(active_q, t1[0], t1[1], t1[2]);
            bits = 3'b100 >> xa;
            if ((top_child & bits) == '0) begin
              // Sibling: the upper half on the exit axis: t0 <- t1, t1 <- 2 t1 - t0.
              sibling = 1'b1;
              c = top_child | bits;
              for (int a = 0; a < 3; a++) begin
                if (32'(a) == 32'(xa)) begin
                  n0[a] = t1[a];
                  n1[a] = (t1[a] <<< 1) - t0[a];
                end
                if (active_q[a] && n1[a] < 0) behind = 1'b1;
              end
              if (behind) begin
                nx_state = NEXT;
              end else begin
                nx_state = group_valid_q ? ENTER : REFILL_REQ;
              end
            end else begin
              // Pop: the parent's parameters from the child's (upper half:
              // t0 <- 2 t0 - t1; lower half: t1 <- 2 t1 - t0).
              pop = 1'b1;
              for (int a = 0; a < 3; a++) begin
                if (active_q[a]) begin
                  if (top_child[2-a]) begin
                    n0[a] = (t0[a] <<< 1) - t1[a];
                  end else begin
                    n1[a] = (t1[a] <<< 1) - t0[a];
                  end
                end
              end
              nx_state = (depth_q == DEPTH_W'(1)) ? DONE : NEXT;
            end
          end
          sel = c ^ mirror_q;
          // ---- Register writes ----
          state_q <= nx_state;
          if (descend || sibling || pop) begin
            t0_x_q <= n0[0];
            t0_y_q <= n0[1];
            t0_z_q <= n0[2];
            t1_x_q <= n1[0];
            t1_y_q <= n1[1];
            t1_z_q <= n1[2];
            exit_q <= min_active(active_q, n1[0], n1[1], n1[2]);
          end
          if (descend) begin
            stack_first_q[STK_W'(depth_q)] <= first_q;
            stack_child_q[STK_W'(depth_q)] <= c;
            node_id_q <= first_q + 32'(sel);
            sel_q     <= sel;
            depth_q   <= depth_q + 1'b1;
          end
          if (sibling) begin
            stack_child_q[top_idx] <= c;
            node_id_q   <= top_first + 32'(sel);
            sel_q       <= sel;
            node_addr_q <= top_first;
          end
          if (pop) begin
            depth_q       <= depth_q - 1'b1;
            group_valid_q <= 1'b0;
          end
        end
        FETCH: begin
          if (received_q == count_q) state_q <= CHECK;
          if (idx_gnt_i) begin
            issued_q   <= issued_q + 1'b1;
            idx_addr_q <= idx_addr_q + 1'b1;
          end
          if (res_i) received_q <= received_q + 1'b1;
        end
        ENTER: begin
          if (visit_gnt_i) begin
            first_q     <= visit_rec_i.first;
            count_q     <= 32'(visit_rec_i.count);
            node_addr_q <= visit_rec_i.first;
            idx_addr_q  <= visit_rec_i.first;
            issued_q    <= '0;
            received_q  <= '0;
            if (!visit_rec_i.leaf) begin
              state_q <= GROUP_REQ;
            end else if (visit_rec_i.count == '0) begin
              state_q <= CHECK;
            end else begin
              state_q <= FETCH;
            end
          end
        end
        GROUP_REQ:   if (node_gnt_i) state_q <= WAIT_GROUP;
        REFILL_REQ:  if (node_gnt_i) state_q <= WAIT_REFILL;
        WAIT_GROUP: begin
          if (node_rsp_i) begin
            state_q       <= DESCEND;
            group_valid_q <= 1'b1;
          end
        end
        WAIT_REFILL: begin
          if (node_rsp_i) begin
            state_q       <= ENTER;
            group_valid_q <= 1'b1;
          end
        end
        DONE:        if (done_gnt_i) state_q <= FREE;
        FREE:        if (alloc_i) state_q <= SETUP;
        SETUP: begin
          if (init_i) begin
            state_q       <= init_enter_i ? ENTER : DONE;
            mirror_q      <= init_mirror_i;
            active_q      <= init_active_i;
            org_x_q       <= init_origin_i[0*ORG_W +: ORG_W];
            org_y_q       <= init_origin_i[1*ORG_W +: ORG_W];
            org_z_q       <= init_origin_i[2*ORG_W +: ORG_W];
            t0_x_q        <= init_t0_i[0*T_W +: T_W];
            t0_y_q        <= init_t0_i[1*T_W +: T_W];
            t0_z_q        <= init_t0_i[2*T_W +: T_W];
            t1_x_q        <= init_t1_i[0*T_W +: T_W];
            t1_y_q        <= init_t1_i[1*T_W +: T_W];
            t1_z_q        <= init_t1_i[2*T_W +: T_W];
            exit_q        <= min_active(init_active_i, init_t1_i[0*T_W +: T_W], init_t1_i[1*T_W +: T_W],
                                        init_t1_i[2*T_W +: T_W]);
            depth_q       <= '0;
            node_id_q     <= '0;
            sel_q         <= '0;
            group_valid_q <= 1'b0;
          end
        end
        default:     state_q <= FREE;
      endcase
    end
  end

  assign free_o         = (state_q == FREE);
  assign want_visit_o   = (state_q == ENTER);
  assign want_node_o    = (state_q == GROUP_REQ) || (state_q == REFILL_REQ);
  assign want_idx_o     = (state_q == FETCH) && (issued_q != count_q);
  assign want_check_o   = (state_q == CHECK) && has_hit_i;
  assign want_done_o    = (state_q == DONE);
  assign fetching_o     = (state_q == FETCH);
  assign waiting_node_o = (state_q == WAIT_GROUP) || (state_q == WAIT_REFILL);
  assign at_root_o      = (depth_q == '0);
  assign sel_o          = sel_q;
  assign node_id_o      = node_id_q;
  assign node_addr_o    = node_addr_q;
  assign idx_addr_o     = idx_addr_q;
  assign exit_o         = exit_q;

endmodule
