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
//              the per-slot ray and closest hit, the exit test, the results
//              (the node port is its node port, not registered: RegRsp = 0)
//   u_setup    per-ray setup, multiplications only (2 stages)
//   u_slots    RaysInFlight slots (rt_octree_slots): walk state, stacks, steps
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
// The records read by slot index are kept here in arrays (the node and test
// counters, the child group); rt_octree_slots keeps the walks, rt_trav_shell
// the ray, its closest hit, the dominant and common of the exit test.
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
module rt_octree #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     // derived
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Configuration, static while rays are in flight.
  input  logic [CfgSlotsW-1:0]                   cfg_slots_i,  // slots to use, 1..RaysInFlight
  input  rt_pkg::octree_node_t                   cfg_root_i,   // node 0 (the root's record)

`include "rt_trav_ports.svh"

  // One result per ray, one record per node entered.
  output rt_pkg::octree_res_t                    res_data_o,
  output rt_pkg::octree_visit_t                  visit_data_o,

  // Child-group reads: the eight octree_node_t records first .. first+7,
  // element 0 least significant (as plain bits: Yosys 0.23 reads a port of a
  // package type's packed array as one element).
  output logic                                   node_req_valid_o,
  input  logic                                   node_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          node_req_addr_o,
  output logic [SlotW-1:0]                       node_req_tag_o,
  input  logic                                   node_rsp_valid_i,
  input  logic [rt_pkg::OCTREE_CHILDREN*rt_pkg::OCTREE_NODE_W-1:0] node_rsp_data_i,
  input  logic [SlotW-1:0]                       node_rsp_tag_i
);

  localparam int N      = RaysInFlight;
  localparam int P      = rt_pkg::POS_W;
  localparam int ADDR_W = rt_pkg::MEM_ADDR_W;
  localparam int T_W    = rt_pkg::OCTREE_T_W;
  localparam int COM_W  = rt_pkg::OCTREE_COMMON_W;
  localparam int DIR_W  = rt_pkg::DIR_W;
  localparam int GROUP_W = rt_pkg::OCTREE_CHILDREN * rt_pkg::OCTREE_NODE_W;

  // A child group as stored per slot: octree_node_t [7:0] as plain bits
  // (Yosys 0.23 reads a two-dimensional packed array only inside a struct, and
  // a package type only outside one).
  typedef struct packed {
    logic [rt_pkg::OCTREE_CHILDREN-1:0][rt_pkg::OCTREE_NODE_W-1:0] node;
  } group_t;

  // ---- Per-slot signals ---------------------------------------------------------
  logic [N-1:0]        free, want_visit, want_node, want_idx, want_check, want_done, bound;
  logic [N-1:0]        fetching, waiting_node;
  logic                ray_fire, visit_go, node_go, idx_go, check_go, done_go;
  logic [SlotW-1:0]    alloc_idx, check_sel, visit_idx, node_idx, idx_idx, check_idx, done_idx;
  logic                node_valid, isect_valid, check_holds;
  logic                unused_hit;   // the slots read the exit-test state from bound
  logic [SlotW-1:0]    node_tag, res_slot;
  logic [GROUP_W-1:0]  node_data;
  logic                visit_at_root;
  logic [2:0]          visit_sel;
  logic [31:0]         visit_node_id;
  logic [ADDR_W-1:0]   node_addr, idx_addr;
  logic [T_W-1:0]      check_exit;
  logic [31:0]         done_nodes, done_tests;

  // ---- Records kept by slot index -------------------------------------------------
  // The child groups as plain vectors, read into group_t: Yosys 0.23 keeps
  // only one element's flops of an unpacked array of a packed struct.
  logic [31:0]         nodes_q [N];
  logic [31:0]         tests_q [N];
  logic [GROUP_W-1:0]  group_q [N];

  // The setup's outputs.
  logic                 su_valid, su_enter;
  logic [SlotW-1:0]     su_slot;
  rt_pkg::isect_ray_t   su_ray;
  logic [2:0]           su_mirror, su_active;
  logic [3*(P+1)-1:0]   su_origin;
  logic [3*T_W-1:0]     su_t0, su_t1;
  logic [COM_W-1:0]     su_common;
  logic [DIR_W-1:0]     su_dom;

  // ---- The shell: streams, memory ports, rt_isect, closest hits, exit tests ----------
  rt_trav_shell #(
    .N(N), .IdxBufDepth(IdxBufDepth), .NodeRspW(GROUP_W), .RegRsp(1'b0),
    .VisitIdW(32), .ExitW(T_W), .DenW(COM_W)
  ) u_shell (
    // The unit's own ports by name (.*): the same ports as the shell's.
    .*,
    .free_i        (free),
    .alloc_o       (ray_fire),
    .alloc_slot_o  (alloc_idx),
    .init_i        (su_valid),
    .init_slot_i   (su_slot),
    .init_ray_i    (su_ray),
    .init_dom_i    (su_dom),
    .init_den_i    (su_common),
    .want_node_i   (want_node),
    .node_go_o     (node_go),
    .node_slot_o   (node_idx),
    .node_addr_i   (node_addr),
    .node_valid_o  (node_valid),
    .node_tag_o    (node_tag),
    .node_data_o   (node_data),
    .want_visit_i  (want_visit),
    .visit_go_o    (visit_go),
    .visit_slot_o  (visit_idx),
    .visit_id_i    (visit_node_id),
    .want_idx_i    (want_idx),
    .idx_go_o      (idx_go),
    .idx_slot_o    (idx_idx),
    .idx_addr_i    (idx_addr),
    .expect_i      (fetching),
    .isect_valid_o (isect_valid),
    .isect_slot_o  (res_slot),
    .isect_hit_o   (unused_hit),
    .bound_o       (bound),
    .want_check_i  (want_check),
    .check_sel_o   (check_sel),
    .check_go_o    (check_go),
    .check_slot_o  (check_idx),
    .check_exit_i  (check_exit),
    .check_holds_o (check_holds),
    .want_done_i   (want_done),
    .done_go_o     (done_go),
    .done_slot_o   (done_idx),
    .done_count_i  (done_nodes),
    .done_tests_i  (done_tests)
  );

  // ---- Setup ---------------------------------------------------------------------
  rt_octree_setup #(.SlotW(SlotW)) u_setup (
    .clk_i,
    .rst_ni,
    .valid_i  (ray_fire),
    .slot_i   (alloc_idx),
    .ray_i    (ray_data_i),
    .valid_o  (su_valid),
    .slot_o   (su_slot),
    .ray_o    (su_ray),
    .mirror_o (su_mirror),
    .active_o (su_active),
    .origin_o (su_origin),
    .t0_o     (su_t0),
    .t1_o     (su_t1),
    .common_o (su_common),
    .dom_o    (su_dom),
    .enter_o  (su_enter)
  );

  // ---- Visits: the granted slot's node record ---------------------------------------
  // The current node's record is the root's at depth 0, else entry `sel` of
  // the slot's child group (its parent's children).
  rt_pkg::octree_node_t visit_rec;
  group_t               visit_group;
  // (The whole element first: Yosys 0.23 takes no field of an array element.)
  assign visit_group = group_q[visit_idx];
  assign visit_rec   = visit_at_root ? cfg_root_i : visit_group.node[visit_sel];

  // ---- Slots: the octree walks ---------------------------------------------------------
  rt_octree_slots #(.N(N), .SlotW(SlotW)) u_slots (
    .clk_i,
    .rst_ni,
    .free_o           (free),
    .alloc_i          (ray_fire),
    .alloc_slot_i     (alloc_idx),
    .init_i           (su_valid),
    .init_slot_i      (su_slot),
    .init_enter_i     (su_enter),
    .init_mirror_i    (su_mirror),
    .init_active_i    (su_active),
    .init_origin_i    (su_origin),
    .init_t0_i        (su_t0),
    .init_t1_i        (su_t1),
    .want_visit_o     (want_visit),
    .visit_go_i       (visit_go),
    .visit_slot_i     (visit_idx),
    .visit_rec_i      (visit_rec),
    .visit_at_root_o  (visit_at_root),
    .visit_sel_o      (visit_sel),
    .visit_node_id_o  (visit_node_id),
    .want_node_o      (want_node),
    .node_go_i        (node_go),
    .node_slot_i      (node_idx),
    .node_addr_o      (node_addr),
    .waiting_node_o   (waiting_node),
    .node_rsp_valid_i (node_valid),
    .node_rsp_slot_i  (node_tag),
    .want_idx_o       (want_idx),
    .idx_go_i         (idx_go),
    .idx_slot_i       (idx_idx),
    .idx_addr_o       (idx_addr),
    .fetching_o       (fetching),
    .res_valid_i      (isect_valid),
    .res_slot_i       (res_slot),
    .bound_i          (bound),
    .want_check_o     (want_check),
    .check_sel_i     (check_sel),
    .check_go_i       (check_go),
    .check_slot_i     (check_idx),
    .check_exit_o     (check_exit),
    .check_holds_i    (check_holds),
    .want_done_o      (want_done),
    .done_go_i        (done_go),
    .done_slot_i      (done_idx)
  );

  // ---- The records kept by slot index ---------------------------------------------------
  // No reset: each is written (at the slot's setup) before it is read.
  always_ff @(posedge clk_i) begin
    if (su_valid) begin
      nodes_q[su_slot] <= '0;
      tests_q[su_slot] <= '0;
    end
    if (visit_go) begin
      nodes_q[visit_idx] <= nodes_q[visit_idx] + 1'b1;
      if (visit_rec.leaf) tests_q[visit_idx] <= tests_q[visit_idx] + 32'(visit_rec.count);
    end
    if (node_valid) group_q[node_tag] <= node_data;
  end

  assign done_nodes = nodes_q[done_idx];
  assign done_tests = tests_q[done_idx];

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Node responses name a slot that waits for one (rt_trav_shell checks the
  // triangles' and the results' slots).
  `RT_CHECK_IF(a_node_rsp_slot, node_rsp_valid_i, waiting_node[node_rsp_tag_i])
`endif

endmodule
