// rt_octree: the octree stepping unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseOctree (sw/golden/octree.h): for every ray the
// same nodes in the same order (Revelles' parametric walk in exact integers),
// every triangle of every visited leaf tested (index-list order), the closest
// hit by fx::closerResult, and the same stop rule (stop once the closest hit
// so far lies within the current leaf, fx::hitWithin, or when the walk leaves
// the root). docs/octree-unit.md, "Micro-architecture of rt_octree", specifies
// it cycle by cycle; the SystemC model (systemc/octree/) implements the same text.
//
//   u_shell    rt_trav_shell: ray input and slot allocation, the arbiters and
//              FIFOs of every port, the index and triangle path to rt_isect,
//              the per-slot ray and closest hit, the exit test, the counts,
//              the results (the node port is its node port, not registered:
//              RegRsp = 0)
//   u_setup    rt_octree_setup: per-ray setup, multiplications only
//              (OCTREE_SETUP_LATENCY stages), and the root test
//   the walk   RaysInFlight slots (below): walk state, the child groups
//              read, stacks, steps
//   visit_*    one record per node entered (round robin over slots in ENTER)
//   node port  one child-group read per interior node entered, and one per
//              refill of a group lost to a pop (round robin over slots)
//   idx port   one index-list read per test (round robin over slots), credit-
//              limited by the index buffer (IdxBufDepth)
//   tri port   one triangle read per index response, in index-response order
//   u_isect    rt_isect; a triangle response enters it in the cycle it arrives
//   closest    one isect result per cycle updates its slot's closest hit
//   check      one exit test per cycle (round robin over slots with a hit)
//   res_*      one record per ray
//
// This module is the walk, beside its rt_trav_shell, which keeps the ray, its
// closest hit, the dominant and common of the exit test, and the counts; the
// two are joined by name (the ports of rt_walk_ports.svh).
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based: index responses land in the index buffer, which is never
// overfilled; child groups and triangles are consumed in their cycle).
// Responses per port must come in request order; the tag is the slot.
//
// Latency:    >= 3 (setup) + per interior node ENTER, GROUP_REQ, the read,
//             DESCEND (L + 4 cycles at memory latency L); per leaf ENTER,
//             the reads and ISECT_LATENCY if it holds triangles, CHECK.
// Throughput: per cycle at most one ray accepted, one node entered, one child
//             group read, one index read, one triangle read, one intersection
//             test, one closest-hit update, one exit test and one result; any
//             number of DESCEND and advance steps (one per slot).
//
// The walk: the ray slots — per-slot state machines, the current node's plane
// parameters, the stacks and the DESCEND and advance steps — updated by the
// unit's events, each addressed to one slot by index.
//
//   FREE -alloc-> SETUP -init-> ENTER (root test passes) | DONE
//   ENTER -visit grant-> GROUP_REQ (interior) | FETCH (leaf, count > 0) | CHECK (empty leaf)
//   GROUP_REQ -node grant-> WAIT_GROUP -node response-> DESCEND -> ENTER | NEXT
//   FETCH: one index request per index grant; -> CHECK once every result is in
//   CHECK without a bound (no hit, no segment end): advance on an advance-lane
//   grant; with one: on the check grant DONE if the exit test holds (or an
//   any-hit ray has its hit), else advance in the exit lane
//   NEXT: advance on an advance-lane grant
//   advance: DONE at depth 0; sibling -> ENTER | REFILL_REQ | NEXT; pop -> NEXT | DONE
//   REFILL_REQ -node grant-> WAIT_REFILL -node response-> ENTER
//   DONE -done grant-> FREE
//   ENTER of an interior node with cfg_suspend_i, its child group (first) in
//          another block (first >> cfg_block_shift_i) than the last group the
//          slot read, and at most OCTREE_SUSPEND_LEVELS levels on the stack:
//          DONE, suspended instead of GROUP_REQ (its result carries the walk:
//          res_suspended_o, res_walk_o); it resumes as a new ray with
//          ray_resume_i, in GROUP_REQ for that group at init
//
// Every step after setup is additions, halvings, comparisons and table look-ups
// (fx::firstChild, fx::nextChild). Halvings are exact, so the stack holds no
// parameters: a child's [t0, t1] on an axis gives its parent's back
// (t0_parent = 2 t0 - t1 on the upper half, t1_parent = 2 t1 - t0 on the lower),
// and a sibling step on the exit axis x is t0 <- t1, t1 <- 2 t1 - t0.
//
// An axis the ray never crosses has t0 = -inf, t1 = +inf (no value), and its
// mid-plane parameter is +inf below the node's mid-plane, -inf on or above it.
// On such an axis the walk always takes the child that holds o' (table 1 puts
// -inf before any entry parameter and +inf after), and no sibling step ever
// moves along it (its t1 is +inf), so the node's lower corner on that axis is
// o' with its low P - depth bits cleared, and "o' below the mid-plane" is bit
// P-1-depth of o' being 0. (Rays need some non-zero direction component.)
//
// Which slots step in a cycle. DESCEND is entered only on a node response (one
// per cycle) and lasts one cycle: one slot at most, the registered response
// tag. FETCH ends the cycle after the result that completes the leaf (one per
// cycle): the registered result slot. The advance runs in AdvLanes shared
// lanes, granted round robin to the slots in NEXT or in CHECK without a bound
// (the grant registered: the slot advances in the next cycle), and in one more
// lane for the slot whose exit test fails, in the cycle of the answer:
// AdvLanes + 1 advance datapaths, not one per slot; a slot waits only when
// more than AdvLanes slots want to advance in the same cycle.
//
// Storage: one-hot state vectors (N bits each, reset); per-slot registers as
// arrays written by index (no reset; written before read). The current node's
// entry {group base, child} sits in registers; the stack below it is written
// by DESCEND and a resumption: its bottom levels (the suspend window) in
// flip-flops, those above in a memory (a macro). A slot's node id (group base + (child ^ a)) and its node
// read address are formed when they are granted.
//
// Shape (as rt_grid's walk): the steps are combinational (b_advance, the
// lanes'; b_descend), p_state holds the reset state (the state vectors, each
// its old value less the slots an event takes out plus those it brings in),
// and p_walk, p_stack, p_ray and p_node write the per-slot arrays, which have
// no reset; u_idx_count counts a leaf's reads and results.
//
// Latency: every transition takes one clock edge. Throughput: per cycle one
// allocation, one init, one visit, one node grant, one node response, one
// DESCEND, one index grant, one result, one end of FETCH, one exit test, one
// result record, AdvLanes + 1 advance steps.
`include "rt_walk_core.svh"
module rt_octree #(
  `RT_WALK_UNIT_PARAMS,
  parameter int unsigned AdvLanes     = 2,   // advance lanes besides the exit test's
  parameter int unsigned NodeRspW = rt_pkg::OCTREE_CHILDREN * rt_pkg::OCTREE_NODE_W  // derived: a node response's bits
) (
`include "rt_trav_ports.svh"

  // Configuration, static while rays are in flight.
  input  rt_pkg::octree_node_t                   cfg_root_i,   // node 0 (the root's record)
  // The treelet schedule (docs/scheduling.md): set walks aside before they
  // descend into a child group of another treelet block of
  // 2^cfg_block_shift_i node-table entries.
  input  logic                                   cfg_suspend_i,
  input  logic [rt_pkg::OCTREE_BLOCK_SHIFT_W-1:0] cfg_block_shift_i,

  // With a ray accepted: it resumes the walk of ray_walk_i.
  input  logic                                   ray_resume_i,
  input  rt_pkg::octree_walk_t                   ray_walk_i,

  // One result per ray (per walk: a suspended walk's result comes with its
  // record, res_walk_o, 0 otherwise), one record per node entered.
  output rt_pkg::octree_res_t                      res_data_o,
  output logic                                     res_suspended_o,
  output rt_pkg::octree_walk_t                     res_walk_o,
  output rt_pkg::octree_visit_t                    visit_data_o
);

  // The figures of the walk's ports toward its shell, and the shell, with
  // the slot core's events and checks (rt_walk_core.svh).
  localparam int unsigned VisitIdW  = 32;
  localparam int unsigned ExitW     = rt_pkg::OCTREE_T_W;
  localparam int unsigned DenW      = rt_pkg::OCTREE_COMMON_W;
  localparam int unsigned RunPorts  = 1;
  localparam bit          RegRsp    = 1'b0;  // node responses straight to the walk
  // A suspended walk's record less its closest hit (the result carries that).
  localparam int unsigned WalkPartW = rt_pkg::OCTREE_WALK_W - `RT_WALK_HIT_W;
`define RT_WALK_CORE_BODY
`include "rt_walk_core.svh"

  // ---- The walk ----------------------------------------------------------------------
  localparam int P       = rt_pkg::POS_W;
  localparam int T_W     = rt_pkg::OCTREE_T_W;
  localparam int ORG_W   = P + 1;
  localparam int ADDR_W  = rt_pkg::MEM_ADDR_W;
  localparam int DEPTH_W = $clog2(rt_pkg::OCTREE_MAX_DEPTH + 1);
  localparam int STACK   = rt_pkg::OCTREE_MAX_DEPTH;             // levels 0 .. P-1
  localparam int STK_W   = (STACK > 1) ? $clog2(STACK) : 1;
  localparam int ENTRY_W = 35;                                   // {group base, child}
  // The ancestors' entries in two parts: each slot's bottom WIN levels (the
  // suspend window: a suspension reads them and a resumption writes them at
  // once) in flip-flops, the levels above them in one memory of one write
  // port (DESCEND's push) and AdvLanes + 1 read ports (the lanes' pops). A
  // walk set aside has at most OCTREE_SUSPEND_LEVELS levels, the current
  // one in registers: the window holds the others.
  localparam int SUSPEND = rt_pkg::OCTREE_SUSPEND_LEVELS;
  localparam int WIN     = (SUSPEND - 1 < STACK) ? SUSPEND - 1 : STACK;
  localparam int UPPER   = STACK - WIN;                          // levels above the window, per slot
  localparam int WIN_AW  = $clog2(N * WIN);
  localparam int UP_N    = (N * UPPER > 0) ? N * UPPER : 1;
  localparam int UP_AW   = (UP_N > 1) ? $clog2(UP_N) : 1;

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

  // Where slot s keeps its stack entry of level d (in the window below WIN).
  function automatic logic [WIN_AW-1:0] win_addr(input logic [SlotW-1:0] s, input logic [STK_W-1:0] d);
    win_addr = WIN_AW'(s) * WIN_AW'(WIN) + WIN_AW'(d);
  endfunction
  function automatic logic [UP_AW-1:0] upper_addr(input logic [SlotW-1:0] s, input logic [STK_W-1:0] d);
    logic [STK_W-1:0] above;  // the level's place above the window
    above = d - STK_W'(WIN);
    upper_addr = UP_AW'(s) * UP_AW'(UPPER) + UP_AW'(above);
  endfunction

  // ---- State vectors (bit s = slot s) -------------------------------------------
  logic [N-1:0] enter_q, group_req_q, wait_group_q, fetch_q, check_q;
  logic [N-1:0] next_q, refill_req_q, wait_refill_q, done_q;
  logic [N-1:0] gv_q;       // the child group holding the current node is in the group buffer
  logic [N-1:0] suspending_q;  // DONE: the walk is set aside before a descent, not over
  logic         desc_q;     // a slot is in DESCEND: desc_slot_q
  logic [SlotW-1:0] desc_slot_q;
  // The DESCEND slot's operands, read at its node response (the slot waits in
  // WAIT_GROUP, its registers still): DESCEND computes from these registers,
  // not through the slots' read multiplexers (issue #23).
  logic [3*T_W-1:0]   desc_op_t0_q, desc_op_t1_q;
  logic [3*ORG_W-1:0] desc_op_org_q;
  logic [2:0]         desc_op_active_q;
  logic [DEPTH_W-1:0] desc_op_depth_q;
  logic         fin_q;      // a slot's last result came in the previous cycle: fin_slot_q
  logic [SlotW-1:0] fin_slot_q;

  // ---- Per-slot registers -------------------------------------------------------------
  // Written by index (events, DESCEND).
  logic [2:0]             mirror_q   [N];
  logic [2:0]             active_q   [N];
  logic [3*ORG_W-1:0]     org_q      [N];   // o' {z, y, x}
  logic [31:0]            first_q    [N];   // the current node's record (its count: u_idx_count)
  // The ancestors' entries: levels 0 .. WIN-1 of slot s at s * WIN + level
  // (flip-flops), the levels above at s * UPPER + level - WIN (a memory).
  logic [ENTRY_W-1:0]     win_q      [N * WIN];
  logic [ENTRY_W-1:0]     upper_q    [UP_N];
  logic [31:0]            blk_q      [N];   // the last child group read (its block: the bits above the shift)
  // Written by the advance too.
  logic [3*T_W-1:0]       t0_q       [N];   // the current node's parameters {z, y, x}
  logic [3*T_W-1:0]       t1_q       [N];
  logic [DEPTH_W-1:0]     depth_q    [N];
  logic [31:0]            grp_q      [N];   // base of the child group holding the current node
  logic [2:0]             child_q    [N];   // the current node's child index (mirrored space)

  // ---- Events ----------------------------------------------------------------------------
  // The walk's own (the shell's are the slot core's: rt_walk_core.svh).
  logic [N-1:0] desc_oh, fin_oh;
  assign desc_oh  = onehot(desc_q, desc_slot_q);
  assign fin_oh   = onehot(fin_q, fin_slot_q);

  // ---- The ray's setup (rt_octree_setup) ------------------------------------------------
  logic                 init_enter;
  logic [2:0]           init_mirror, init_active;
  logic [3*ORG_W-1:0]   init_origin;
  logic [3*T_W-1:0]     init_t0, init_t1;

  rt_octree_setup #(.SlotW(SlotW)) u_setup (
    `RT_WALK_SETUP_PORTS,
    .mirror_o (init_mirror),
    .active_o (init_active),
    .origin_o (init_origin),
    .t0_o     (init_t0),
    .t1_o     (init_t1),
    .common_o (init_den),
    .enter_o  (init_enter)
  );

  // ---- Child groups, and the visited node's record --------------------------------------
  // A slot's child group as it arrives (plain vectors, read into group_t:
  // Yosys 0.23 keeps only one element's flops of an unpacked array of a packed
  // struct, reads a two-dimensional packed array only inside a struct, and a
  // package type only outside one). The visited node's record is the root's at
  // depth 0, else entry `visit_sel` of the slot's child group (its parent's
  // children).
  typedef struct packed {
    logic [rt_pkg::OCTREE_CHILDREN-1:0][rt_pkg::OCTREE_NODE_W-1:0] node;
  } group_t;
  logic [NodeRspW-1:0]  group_q [N];
  group_t               visit_grp;
  rt_pkg::octree_node_t visit_rec;
  logic [2:0]           visit_sel;
  logic                 visit_at_root;

  always_ff @(posedge clk_i) begin : p_group
    if (node_valid) group_q[node_tag] <= node_data;
  end
  // (The whole element first: Yosys 0.23 takes no field of an array element.)
  assign visit_grp     = group_q[visit_slot];
  assign visit_sel     = child_q[visit_slot] ^ mirror_q[visit_slot];
  assign visit_at_root = (depth_q[visit_slot] == '0);
  assign visit_rec     = visit_at_root ? cfg_root_i : visit_grp.node[visit_sel];

  // The visited node's record decides where the slot goes.
  logic visit_leaf, visit_empty;
  assign visit_leaf  = visit_rec.leaf;
  assign visit_empty = (visit_rec.count == '0);

  // ---- The advance lanes -----------------------------------------------------------
  // A slot advances (fx::nextChild) in NEXT, in CHECK without a bound, and when
  // the exit test it is granted fails. The first two wait in want_adv for one
  // of AdvLanes round-robin lanes (lane l takes the next requester that no
  // lane before it took); the exit test has a lane of its own (lane AdvLanes).
  // Each lane is one advance datapath reading its slot's registers:
  //   depth 0: DONE;
  //   the node is the lower half on the exit axis x (argmin t1, exact ties to
  //   the later axis): the sibling, t0 <- t1, t1 <- 2 t1 - t0 on x, then NEXT
  //   if it lies behind the origin, else ENTER (child group held) or REFILL_REQ;
  //   else a pop: the parent's parameters from the child's (upper half:
  //   t0 <- 2 t0 - t1; lower half: t1 <- 2 t1 - t0) and entry from the stack,
  //   then NEXT, or DONE when the parent is the root.
  localparam int LANES = AdvLanes + 1;
  localparam int CHECK_LANE = AdvLanes;

  // The round-robin lanes' grants are registered: a slot granted in cycle t
  // advances in t+1 (its lane's arithmetic then starts from registers, not
  // from the chained arbiters), and is left out of the arbitration in t+1.
  logic [N-1:0]          want_adv, in_lane;
  // Requesters left for lane l (split: lane l's element depends on lane l-1's).
  logic [N-1:0]          lane_req [AdvLanes + 1] /* verilator split_var */;
  logic                  arb_go [AdvLanes];
  logic [SlotW-1:0]      arb_slot [AdvLanes];
  logic [AdvLanes-1:0]   lane_go_q;
  logic [SlotW-1:0]      lane_slot_q [AdvLanes];
  logic                  lane_go [LANES];
  logic [SlotW-1:0]      lane_slot [LANES];

  assign want_adv    = next_q | (check_q & ~bound);
  assign lane_req[0] = want_adv & ~in_lane;
  for (genvar l = 0; l < AdvLanes; l++) begin : g_adv_arb
    logic [N-1:0] gnt;
    rt_rr_arb #(.N(N)) u_arb (
      .clk_i, .rst_ni, .req_i(lane_req[l]), .ack_i(arb_go[l]),
      .valid_o(arb_go[l]), .gnt_o(gnt), .idx_o(arb_slot[l]));
    assign lane_req[l+1] = lane_req[l] & ~gnt;
    assign lane_go[l]    = lane_go_q[l];
    assign lane_slot[l]  = lane_slot_q[l];
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lane_go_q <= '0;
    end else begin
      for (int l = 0; l < AdvLanes; l++) lane_go_q[l] <= arb_go[l];
    end
  end
  always_ff @(posedge clk_i) begin
    for (int l = 0; l < AdvLanes; l++) begin
      if (arb_go[l]) lane_slot_q[l] <= arb_slot[l];
    end
  end
  always_comb begin
    in_lane = '0;
    for (int l = 0; l < AdvLanes; l++) in_lane = in_lane | onehot(lane_go_q[l], lane_slot_q[l]);
  end
  // The slot whose exit test fails advances in the exit lane in the cycle of
  // the answer (registers: rt_exit_test's output).
  assign lane_go[CHECK_LANE]   = check_go && !check_holds;
  assign lane_slot[CHECK_LANE] = check_slot;

  // ---- The next advance, prepared ---------------------------------------------------
  // What an advance compares depends on the slot's parameters only: the exit
  // axis x, up = 2 t1 - t0 on x (the sibling's t1), and whether the sibling
  // lies behind the origin (up < 0 on x, or t1 < 0 on another active axis).
  // Each slot works them out in the cycle after its parameters are written
  // (fresh_q: a lane's step, DESCEND, init) and keeps them, so a lane starts
  // from registers rather than from the comparisons (issue #23: the lane step
  // was rt_octree's critical path). A slot never advances in that cycle: a
  // written slot next waits for a visit, or in NEXT for a registered lane
  // grant (a_prepared).
  logic [N-1:0]          fresh_q, behind_q;
  logic [1:0]            xa_q [N];
  logic signed [T_W-1:0] up_q [N];

  always_ff @(posedge clk_i) begin : p_prep
    for (int k = 0; k < N; k++) begin
      if (fresh_q[k]) begin : b_prep_slot
        logic signed [T_W-1:0] t0 [3];
        logic signed [T_W-1:0] t1 [3];
        logic [2:0]            active;
        logic [1:0]            xa;
        logic signed [T_W-1:0] up;
        logic                  behind;
        active = active_q[k];
        for (int a = 0; a < 3; a++) begin
          t0[a] = t0_q[k][a*T_W +: T_W];
          t1[a] = t1_q[k][a*T_W +: T_W];
        end
        xa     = exit_axis(active, t1[0], t1[1], t1[2]);
        up     = (t1[xa] <<< 1) - t0[xa];
        behind = active[xa] && up < 0;
        for (int a = 0; a < 3; a++) begin
          if (32'(a) != 32'(xa) && active[a] && t1[a] < 0) behind = 1'b1;
        end
        xa_q[k]     <= xa;
        up_q[k]     <= up;
        behind_q[k] <= behind;
      end
    end
  end

  // ---- The advance lanes' steps -------------------------------------------------------
  // Each lane reads its slot's registers only; the lanes' slots differ (a slot
  // waits in one arbiter's requests, or holds the exit-test grant), so their
  // writes never meet.
  logic [3*T_W-1:0]   lane_t0_d    [LANES];  // the slot's parameters after the step
  logic [3*T_W-1:0]   lane_t1_d    [LANES];
  logic [2:0]         lane_child_d [LANES];
  logic [31:0]        lane_grp_d   [LANES];  // a pop's: the parent's entry and depth
  logic [DEPTH_W-1:0] lane_depth_d [LANES];
  logic [LANES-1:0]   lane_step;             // depth > 0: parameters and child written
  logic [LANES-1:0]   lane_pop;              // a pop: group base and depth written too
  logic [N-1:0]       adv_oh, to_enter, to_refill, to_next, to_done, popped;

  always_comb begin : b_advance
    logic signed [T_W-1:0] t0 [3];      // the slot's parameters
    logic signed [T_W-1:0] t1 [3];
    logic [SlotW-1:0]      s;
    logic signed [T_W-1:0] up;          // 2 t1 - t0 on the exit axis
    logic [2:0]            active, child, bits;
    logic [1:0]            xa;
    logic [DEPTH_W-1:0]    depth;
    logic [ENTRY_W-1:0]    parent;
    logic [STK_W-1:0]      level;
    logic                  sibling, behind;
    logic [N-1:0]          oh;
    {adv_oh, to_enter, to_refill, to_next, to_done, popped} = '0;
    for (int l = 0; l < LANES; l++) begin
      // A lane without a grant writes nothing: its arithmetic is skipped (a
      // simulator then evaluates it only for the slots that step).
      lane_t0_d[l]    = '0;
      lane_t1_d[l]    = '0;
      lane_child_d[l] = '0;
      lane_grp_d[l]   = '0;
      lane_depth_d[l] = '0;
      lane_step[l]    = 1'b0;
      lane_pop[l]     = 1'b0;
      {s, active, child, depth, xa, bits, sibling, up, behind, parent, level, oh} = '0;
      for (int a = 0; a < 3; a++) begin
        t0[a] = '0;
        t1[a] = '0;
      end
      if (lane_go[l]) begin
        s      = lane_slot[l];
        active = active_q[s];
        child  = child_q[s];
        depth  = depth_q[s];
        for (int a = 0; a < 3; a++) begin
          t0[a] = t0_q[s][a*T_W +: T_W];
          t1[a] = t1_q[s][a*T_W +: T_W];
        end
        // The exit axis, 2 t1 - t0 on it and "behind": prepared (p_prep).
        xa      = xa_q[s];
        up      = up_q[s];
        behind  = behind_q[s];
        bits    = 3'b100 >> xa;
        sibling = (child & bits) == '0;
        // The parent's entry: level depth - 2, in the window or the memory.
        level           = STK_W'(depth - DEPTH_W'(2));
        parent          = level < STK_W'(WIN) ? win_q[win_addr(s, level)] : upper_q[upper_addr(s, level)];
        lane_t0_d[l]    = t0_q[s];
        lane_t1_d[l]    = t1_q[s];
        lane_grp_d[l]   = parent[34:3];
        lane_depth_d[l] = depth - 1'b1;
        lane_step[l]    = depth != '0;
        lane_pop[l]     = lane_step[l] && !sibling;
        if (sibling) begin
          lane_t0_d[l][xa*T_W +: T_W] = t1[xa];
          lane_t1_d[l][xa*T_W +: T_W] = up;
          lane_child_d[l]             = child | bits;
        end else begin
          for (int a = 0; a < 3; a++) begin
            if (active[a]) begin
              if (child[2-a]) begin
                lane_t0_d[l][a*T_W +: T_W] = (t0[a] <<< 1) - t1[a];
              end else begin
                lane_t1_d[l][a*T_W +: T_W] = (t1[a] <<< 1) - t0[a];
              end
            end
          end
          lane_child_d[l] = parent[2:0];
        end

        // Where the slot goes: DONE at depth 0; after a sibling step NEXT,
        // ENTER or REFILL_REQ; after a pop NEXT, or DONE at the root.
        oh     = onehot(lane_go[l], s);
        adv_oh = adv_oh | oh;
        if (depth == '0) begin
          to_done = to_done | oh;
        end else if (sibling) begin
          to_next   = to_next   | (oh & {N{behind}});
          to_enter  = to_enter  | (oh & {N{!behind && gv_q[s]}});
          to_refill = to_refill | (oh & {N{!behind && !gv_q[s]}});
        end else begin
          popped  = popped | oh;
          to_done = to_done | (oh & {N{depth == DEPTH_W'(1)}});
          to_next = to_next | (oh & {N{depth != DEPTH_W'(1)}});
        end
      end
    end
  end

  // ---- DESCEND (one slot) ----------------------------------------------------------------
  // The mid-plane parameters (exact halvings), the first child (table 1) and
  // its parameters; the current entry is pushed (none at the root).
  logic [3*T_W-1:0]   desc_t0_d, desc_t1_d;  // the first child's parameters
  logic [2:0]         desc_child_d;          // the first child
  logic [DEPTH_W-1:0] desc_depth;            // the node's depth
  logic               desc_behind;           // the first child lies behind the origin

  always_comb begin : b_descend
    logic signed [T_W-1:0] t0 [3];
    logic signed [T_W-1:0] t1 [3];
    logic signed [T_W-1:0] tm [3];
    logic signed [T_W+1:0] sum [3];     // t0 + t1 = 2 tm
    logic [ORG_W-1:0]      org [3];
    logic [1:0]            r0 [3];
    logic [1:0]            rm [3];
    logic [2:0]            active;
    logic [DEPTH_W-1:0]    mid_bit;
    logic [1:0]            entry;
    logic [8:0]            below_entry;      // [3a + e]: tm[a] before t0[e] (t_lt), a != e
    logic                  lt10, lt20, lt21;  // t0[1] before t0[0], ...
    // Only a slot in DESCEND writes these (desc_q): without one, nothing is computed.
    desc_t0_d    = '0;
    desc_t1_d    = '0;
    desc_child_d = '0;
    desc_depth   = '0;
    desc_behind  = 1'b0;
    {active, mid_bit, entry, lt10, lt20, lt21, below_entry} = '0;
    for (int a = 0; a < 3; a++) begin
      {t0[a], t1[a], tm[a], sum[a], org[a], r0[a], rm[a]} = '0;
    end
    if (desc_q) begin : b_descend_slot
      active     = desc_op_active_q;
      desc_depth = desc_op_depth_q;
      mid_bit    = DEPTH_W'(P - 1) - desc_depth;
      for (int a = 0; a < 3; a++) begin
        t0[a]  = desc_op_t0_q[a*T_W +: T_W];
        t1[a]  = desc_op_t1_q[a*T_W +: T_W];
        org[a] = desc_op_org_q[a*ORG_W +: ORG_W];
        // (t0 + t1) / 2 without the carry bit: t0 and t1 have the same parity.
        tm[a]  = (t0[a] >>> 1) + (t1[a] >>> 1) + $signed({{(T_W-1){1'b0}}, t0[a][0] & t1[a][0]});
        sum[a] = (T_W+2)'(t0[a]) + (T_W+2)'(t1[a]);
        r0[a]  = active[a] ? FINITE : NEG_INF;
        rm[a]  = active[a] ? FINITE : (org[a][mid_bit] ? NEG_INF : POS_INF);
      end
      // Every comparison at once, the entry plane then only selects (issue
      // #23: the entry's comparisons, then the mid-planes' against it, were
      // rt_octree's critical path). tm[a] < t0[e] is t0[a] + t1[a] < 2 t0[e]
      // (tm is an exact half).
      for (int a = 0; a < 3; a++) begin
        for (int e = 0; e < 3; e++) begin
          if (a != e) begin
            below_entry[3*a+e] = (rm[a] < r0[e]) ||
                                (rm[a] == FINITE && r0[e] == FINITE && sum[a] < ((T_W+2)'(t0[e]) <<< 1));
          end
        end
      end
      lt10 = t_lt(r0[1], t0[1], r0[0], t0[0]);
      lt20 = t_lt(r0[2], t0[2], r0[0], t0[0]);
      lt21 = t_lt(r0[2], t0[2], r0[1], t0[1]);
      // The entry plane: the axis of the largest t0 (fx::firstChild's order).
      if (lt10) entry = lt20 ? 2'd0 : 2'd2;
      else      entry = lt21 ? 2'd1 : 2'd2;
      desc_child_d = '0;
      for (int a = 0; a < 3; a++) begin
        if (32'(a) != 32'(entry) && below_entry[3*a+32'(entry)]) desc_child_d[2-a] = 1'b1;
      end
      desc_t0_d   = desc_op_t0_q;
      desc_t1_d   = desc_op_t1_q;
      desc_behind = 1'b0;
      for (int a = 0; a < 3; a++) begin
        if (active[a]) begin
          if (desc_child_d[2-a]) begin
            desc_t0_d[a*T_W +: T_W] = tm[a];
            if (t1[a] < 0) desc_behind = 1'b1;
          end else begin
            desc_t1_d[a*T_W +: T_W] = tm[a];
            if (sum[a] < 0) desc_behind = 1'b1;
          end
        end
      end
    end
  end

  // ---- Suspension (the treelet schedule) ------------------------------------------------
  // An interior node entered whose child group lies in another block than the
  // last group the slot read, with at most SUSPEND levels on the stack: the
  // walk leaves the unit instead of reading the group (DONE, suspended; its
  // result carries the record). Two indices share a block when they agree
  // above the block's shift: a mask (registered: the configuration is
  // static), not a shifter.
  logic [31:0] blk_mask_q;
  logic [31:0] node_index;  // node_slot's group: its node's children, or a refill's
  assign node_index = group_req_q[node_slot] ? first_q[node_slot] : grp_q[node_slot];
  always_ff @(posedge clk_i) blk_mask_q <= ~((32'(1) << cfg_block_shift_i) - 32'(1));
  logic visit_leaves;
  assign visit_leaves = cfg_suspend_i && ((visit_rec.first ^ blk_q[visit_slot]) & blk_mask_q) != '0
                        && depth_q[visit_slot] <= DEPTH_W'(SUSPEND);

  // A resumed walk's record, captured with its ray and carried beside the
  // ray's setup (OCTREE_SETUP_LATENCY stages, as rt_octree_setup): at init the
  // slot takes its parameters, stack and closest hit, and asks for the group.
  localparam int CHILD_W = 3;
  // octree_walk_t's fields as bit offsets (Yosys 0.23 takes no element of a
  // packed array field): stack_child[k] at k * CHILD_W, stack_first[k] at
  // W_FIRST + 32 k, t1[a] at W_T1 + a T_W, t0[a] at W_T0 + a T_W, then depth,
  // group and the closest hit on top.
  localparam int W_FIRST = SUSPEND * CHILD_W;
  localparam int W_T1    = W_FIRST + SUSPEND * 32;
  localparam int W_T0    = W_T1 + 3 * T_W;
  localparam int W_DEPTH = W_T0 + 3 * T_W;
  localparam int W_GROUP = W_DEPTH + DEPTH_W;
  localparam int W_HIT   = W_GROUP + 32;
  logic [rt_pkg::OCTREE_WALK_W-1:0] init_walk;
  rt_pipe_regs #(.Width(rt_pkg::OCTREE_WALK_W), .Stages(rt_pkg::OCTREE_SETUP_LATENCY)) u_resumed (
    .clk_i, .rst_ni, .valid_i(alloc && ray_resume_i), .data_i(ray_walk_i), .valid_o(init_resume), .data_o(init_walk));
  logic [DEPTH_W-1:0]               init_walk_depth;
  logic [31:0]                      init_walk_group;
  logic [ENTRY_W-1:0]               init_walk_top;    // its current level's entry (none at depth 0)
  assign init_hit        = init_walk[W_HIT +: `RT_WALK_HIT_W];
  assign init_walk_depth = init_walk[W_DEPTH +: DEPTH_W];
  assign init_walk_group = init_walk[W_GROUP +: 32];
  always_comb begin
    init_walk_top = '0;
    for (int k = 0; k < SUSPEND; k++) begin
      if (init_walk_depth == DEPTH_W'(k + 1)) begin
        init_walk_top = {init_walk[W_FIRST + k * 32 +: 32], init_walk[k * CHILD_W +: CHILD_W]};
      end
    end
  end

  // ---- State (reset) ---------------------------------------------------------------------
  // Each vector loses the slots whose event leaves its state and gains those
  // whose event enters it. (Written at the edge, not as an always_comb _d: a
  // simulator then evaluates it once per cycle instead of at every input
  // change, for the same gates.)
  always_ff @(posedge clk_i or negedge rst_ni) begin : p_state
    if (!rst_ni) begin
      enter_q       <= '0;
      group_req_q   <= '0;
      wait_group_q  <= '0;
      fetch_q       <= '0;
      check_q       <= '0;
      next_q        <= '0;
      refill_req_q  <= '0;
      wait_refill_q <= '0;
      done_q        <= '0;
      gv_q          <= '0;
      suspending_q  <= '0;
      desc_q        <= 1'b0;
      desc_slot_q   <= '0;
      fin_q         <= 1'b0;
      fin_slot_q    <= '0;
      fresh_q       <= '0;
    end else begin : b_next
      logic [N-1:0] visit_group, visit_leave, visit_fetch, visit_check, init_fresh, stepped;
      visit_group   = visit_oh & {N{!visit_leaf && !visit_leaves}};
      visit_leave   = visit_oh & {N{!visit_leaf && visit_leaves}};
      init_fresh    = init_oh & {N{!init_resume}};
      visit_fetch   = visit_oh & {N{visit_leaf && !visit_empty}};
      visit_check   = visit_oh & {N{visit_leaf && visit_empty}};
      stepped       = '0;
      for (int l = 0; l < LANES; l++) stepped = stepped | onehot(lane_step[l], lane_slot[l]);
      enter_q       <= (enter_q & ~visit_oh) | (init_fresh & {N{init_enter}})
                       | (desc_oh & {N{!desc_behind}}) | to_enter | (rsp_oh & wait_refill_q);
      group_req_q   <= (group_req_q & ~node_oh) | visit_group | (init_oh & {N{init_resume}});
      refill_req_q  <= (refill_req_q & ~node_oh) | to_refill;
      wait_group_q  <= (wait_group_q & ~rsp_oh) | (node_oh & group_req_q);
      wait_refill_q <= (wait_refill_q & ~rsp_oh) | (node_oh & refill_req_q);
      fetch_q       <= (fetch_q & ~fin_oh) | visit_fetch;
      check_q       <= (check_q & ~adv_oh & ~check_oh) | fin_oh | visit_check;
      next_q        <= (next_q & ~adv_oh) | to_next | (desc_oh & {N{desc_behind}});
      done_q        <= (done_q & ~done_oh) | (init_fresh & {N{!init_enter}}) | to_done
                       | (check_oh & {N{check_holds}}) | visit_leave;
      // Set when the walk leaves, cleared when the slot takes its next ray.
      suspending_q  <= (suspending_q & ~init_oh) | visit_leave;
      gv_q          <= (gv_q & ~popped & ~init_oh) | rsp_oh;
      desc_q        <= node_valid && wait_group_q[node_tag];
      desc_slot_q   <= node_tag;
      // The result that completes the leaf: FETCH ends in the next cycle.
      fin_q         <= res_last;
      fin_slot_q    <= isect_slot;
      // The slots whose parameters are written at this edge (p_walk).
      fresh_q       <= stepped | desc_oh | init_oh;
    end
  end

  // ---- Per-slot registers (no reset: written before read) ------------------------------
  // The walk's registers: the lanes, then DESCEND, then init (a later write wins;
  // the events' slots differ).
  always_ff @(posedge clk_i) begin : p_walk
    for (int l = 0; l < LANES; l++) begin
      // (One write of the parameters per lane: each write site costs a
      // simulator a staging copy in every cycle.)
      if (lane_step[l]) begin
        t0_q[lane_slot[l]]    <= lane_t0_d[l];
        t1_q[lane_slot[l]]    <= lane_t1_d[l];
        child_q[lane_slot[l]] <= lane_child_d[l];
      end
      if (lane_pop[l]) begin
        grp_q[lane_slot[l]]   <= lane_grp_d[l];
        depth_q[lane_slot[l]] <= lane_depth_d[l];
      end
    end
    if (desc_q) begin
      t0_q[desc_slot_q]    <= desc_t0_d;
      t1_q[desc_slot_q]    <= desc_t1_d;
      grp_q[desc_slot_q]   <= first_q[desc_slot_q];
      child_q[desc_slot_q] <= desc_child_d;
      depth_q[desc_slot_q] <= desc_depth + 1'b1;
    end
    // A resumed walk's parameters, depth and current entry (its inactive
    // axes' parameters are 0: never read).
    if (init) begin
      t0_q[init_slot]    <= init_resume ? init_walk[W_T0 +: 3 * T_W] : init_t0;
      t1_q[init_slot]    <= init_resume ? init_walk[W_T1 +: 3 * T_W] : init_t1;
      depth_q[init_slot] <= init_resume ? init_walk_depth : '0;
      grp_q[init_slot]   <= init_resume ? init_walk_top[ENTRY_W-1:3] : '0;
      child_q[init_slot] <= init_resume ? init_walk_top[2:0] : '0;
    end
  end

  // The stack: DESCEND pushes the current entry (none at the root); a resumed
  // walk's levels come into the window at init (those at or above its
  // current level are never read before DESCEND writes them).
  always_ff @(posedge clk_i) begin : p_stack
    if (desc_q && desc_depth != '0) begin
      if (STK_W'(desc_depth - 1'b1) < STK_W'(WIN)) begin
        win_q[win_addr(desc_slot_q, STK_W'(desc_depth - 1'b1))] <= {grp_q[desc_slot_q], child_q[desc_slot_q]};
      end else begin
        upper_q[upper_addr(desc_slot_q, STK_W'(desc_depth - 1'b1))] <= {grp_q[desc_slot_q], child_q[desc_slot_q]};
      end
    end
    if (init && init_resume) begin
      for (int k = 0; k < WIN; k++) begin
        win_q[win_addr(init_slot, STK_W'(k))] <= {init_walk[W_FIRST + k * 32 +: 32], init_walk[k * CHILD_W +: CHILD_W]};
      end
    end
  end

  // The last child group the slot read (its block: the bits above the
  // shift): the root's at init, a resumed walk's group.
  always_ff @(posedge clk_i) begin : p_block
    if (node_go) blk_q[node_slot] <= node_index;
    if (init) blk_q[init_slot] <= init_resume ? init_walk_group : cfg_root_i.first;
  end

  // A suspended walk's part of its record, for done_slot: the group it reads
  // first, its depth, the parameters (an inactive axis's 0) and the stack
  // (the window's levels, then the current entry; levels at or above the
  // depth read as 0).
  logic [SUSPEND*32-1:0]      done_stack_first;  // level k at 32 k
  logic [SUSPEND*CHILD_W-1:0] done_stack_child;  // level k at CHILD_W k
  logic [3*T_W-1:0]           done_t0, done_t1;
  always_comb begin
    logic [DEPTH_W-1:0] depth;
    depth = depth_q[done_slot];
    for (int k = 0; k < SUSPEND; k++) begin
      {done_stack_first[k * 32 +: 32], done_stack_child[k * CHILD_W +: CHILD_W]} = '0;
      if (DEPTH_W'(k + 1) == depth) begin
        {done_stack_first[k * 32 +: 32], done_stack_child[k * CHILD_W +: CHILD_W]} =
            {grp_q[done_slot], child_q[done_slot]};
      end else if (k < WIN && DEPTH_W'(k + 1) < depth) begin
        {done_stack_first[k * 32 +: 32], done_stack_child[k * CHILD_W +: CHILD_W]} =
            win_q[win_addr(done_slot, STK_W'(k))];
      end
    end
    done_t0 = t0_q[done_slot];
    done_t1 = t1_q[done_slot];
    for (int a = 0; a < 3; a++) begin
      if (!active_q[done_slot][a]) begin
        done_t0[a*T_W +: T_W] = '0;
        done_t1[a*T_W +: T_W] = '0;
      end
    end
  end
  assign done_suspend    = suspending_q[done_slot];
  assign done_walk       = {first_q[done_slot], depth_q[done_slot], done_t0, done_t1, done_stack_first,
                            done_stack_child};
  assign res_suspended_o = res_suspend;
  assign res_walk_o      = res_walk;

  // The ray's setup, and the current node's record.
  always_ff @(posedge clk_i) begin : p_ray
    if (init) begin
      mirror_q[init_slot] <= init_mirror;
      active_q[init_slot] <= init_active;
      org_q[init_slot]    <= init_origin;
    end
  end

  always_ff @(posedge clk_i) begin : p_node
    if (visit_go) first_q[visit_slot] <= visit_rec.first;
    if (init && init_resume) first_q[init_slot] <= init_walk_group;
  end

  always_ff @(posedge clk_i) begin : p_desc_operands
    if (node_valid && wait_group_q[node_tag]) begin
      desc_op_t0_q     <= t0_q[node_tag];
      desc_op_t1_q     <= t1_q[node_tag];
      desc_op_org_q    <= org_q[node_tag];
      desc_op_active_q <= active_q[node_tag];
      desc_op_depth_q  <= depth_q[node_tag];
    end
  end

  // ---- Outputs ----------------------------------------------------------------------------
  assign visit_id        = visit_at_root ? '0 : grp_q[visit_slot] + 32'(visit_sel);
  // (The walk reads the exit-test state from bound, not the result's hit.)
  logic unused_isect_hit;
  assign unused_isect_hit = isect_hit;
  // A leaf's triangles are counted when it is entered.
  assign run_start       = visit_go && visit_leaf;
  assign run_slot        = visit_slot;
  assign run_count       = 32'(visit_rec.count);
  assign node_addr     = ADDR_W'(node_index);
  assign idx_addr      = ADDR_W'(first_q[idx_slot] + idx_issued);
  assign check_exit    = min_active(active_q[check_sel], t1_q[check_sel][0*T_W +: T_W], t1_q[check_sel][1*T_W +: T_W],
                                      t1_q[check_sel][2*T_W +: T_W]);

  assign want_visit   = enter_q;
  assign want_node    = group_req_q | refill_req_q;
  assign want_check   = check_q & bound;
  assign want_done    = done_q;
  assign fetching     = fetch_q;

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Events meet slots in the states that expect them.
  `RT_CHECK_IF(a_node_rsp_slot, node_valid, wait_group_q[node_tag] || wait_refill_q[node_tag])
  // A lane's slot has its advance prepared (p_prep).
  for (genvar l = 0; l < LANES; l++) begin : g_prepared
    `RT_CHECK_IF(a_prepared, lane_go[l], !fresh_q[lane_slot[l]])
  end
  // An interior node one lattice unit wide cannot be split: the image is malformed.
  `RT_CHECK_IF(a_stack_depth, desc_q, desc_depth < DEPTH_W'(STACK))
  // The record's layout, as octree_walk_t packs it.
  `RT_ASSERT_STATIC(g_walk_layout_check, W_HIT + `RT_WALK_HIT_W == rt_pkg::OCTREE_WALK_W &&
                    DEPTH_W == rt_pkg::OCTREE_DEPTH_W,
                    "rt_octree: the offsets of octree_walk_t's fields differ from rt_pkg")
`endif

endmodule
