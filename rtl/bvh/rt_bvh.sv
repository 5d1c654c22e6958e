// rt_bvh: the BVH traversal unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseBvh (sw/golden/bvh.h): for every ray the same
// nodes in the same order (nearest child first, the farther pushed; exact
// ray-box tests over the lattice planes, fx::boxTest), every triangle of every
// entered leaf tested (index-list order), the closest hit by fx::closerResult,
// the cull rule of a candidate whose bound lies before it (fx::culledBy, the
// shell's exit test with exit = entry - 1), and an any-hit ray answered after
// the leaf of its first hit. docs/bvh-unit.md, "Micro-architecture of
// rt_bvh", specifies it cycle by cycle; the SystemC model (systemc/bvh/)
// implements the same text.
//
//   u_shell    rt_trav_shell: ray input and slot allocation, the arbiters and
//              FIFOs of every port, the index and triangle path to rt_isect,
//              the per-slot ray and closest hit, the exit test, the results
//              (the node port is its node port, not registered: RegRsp = 0)
//   u_setup    per-ray setup, multiplications only (3 stages)
//   u_box      rt_bvh_box: both children's box tests of a node response,
//              pipelined (BVH_BOX_LATENCY stages), one node a cycle
//   u_slots    RaysInFlight slots (rt_bvh_slots): walk state, candidates,
//              stacks, the pop lane
//   visit_*    one record per node entered (round robin over slots in ENTER)
//   node port  one node read per interior node entered (round robin)
//   idx port   one index-list read per test (round robin), credit-limited
//   tri port   one triangle read per index response, in index-response order
//   check      one exit test per cycle (round robin over the candidates of
//              bound slots with a non-zero entry)
//   res_*      one record per ray
//
// The node and test counters are kept here in arrays by slot index;
// rt_bvh_slots keeps the walks, rt_trav_shell the ray, its closest hit, the
// dominant and the common denominator of the exit test.
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based index responses; nodes and triangles consumed in their cycle).
// Responses per port must come in request order; the tag is the slot.
//
// Latency:    >= 1 + BVH_SETUP_LATENCY (setup) + per interior node ENTER,
//             NODE_REQ, the read, the box test (L + 5 cycles from ENTER to the
//             child's ENTER at memory latency L); per leaf ENTER, the reads
//             and ISECT_LATENCY if it holds triangles, then a pop.
// Throughput: per cycle at most one ray accepted, one node entered, one node
//             read, one box test, one index read, one triangle read, one
//             intersection test, one closest-hit update, one exit test, one
//             pop and one result.
module rt_bvh #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     // derived
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Configuration, static while rays are in flight.
  input  logic [CfgSlotsW-1:0]                   cfg_slots_i,  // slots to use, 1..RaysInFlight
  input  rt_pkg::bvh_ref_t                       cfg_root_i,   // the root's reference

`include "rt_trav_ports.svh"

  // One result per ray, one record per node entered.
  output rt_pkg::bvh_res_t                       res_data_o,
  output rt_pkg::bvh_visit_t                     visit_data_o,

  // Node reads: one bvh_node_t (both children's boxes) as plain bits.
  output logic                                   node_req_valid_o,
  input  logic                                   node_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          node_req_addr_o,
  output logic [SlotW-1:0]                       node_req_tag_o,
  input  logic                                   node_rsp_valid_i,
  input  logic [rt_pkg::BVH_NODE_W-1:0]          node_rsp_data_i,
  input  logic [SlotW-1:0]                       node_rsp_tag_i
);

  localparam int N       = RaysInFlight;
  localparam int P       = rt_pkg::POS_W;
  localparam int ADDR_W  = rt_pkg::MEM_ADDR_W;
  localparam int ENTRY_W = rt_pkg::BVH_ENTRY_W;
  localparam int COM_W   = rt_pkg::BVH_COMMON_W;
  localparam int DIR_W   = rt_pkg::DIR_W;
  localparam int PAIR_W  = 2 * (DIR_W - 1);
  localparam int NODE_W  = rt_pkg::BVH_NODE_W;
  localparam int REF_W   = rt_pkg::BVH_REF_W;
  localparam int COUNT_W = rt_pkg::BVH_COUNT_W;

  // ---- Per-slot signals ---------------------------------------------------------
  logic [N-1:0]        free, want_visit, want_node, want_idx, want_check, want_done, bound;
  logic [N-1:0]        fetching, waiting_node;
  logic                ray_fire, visit_go, node_go, idx_go, check_go, done_go;
  logic [SlotW-1:0]    alloc_idx, check_sel, visit_idx, node_idx, idx_idx, check_idx, done_idx;
  logic                node_valid, isect_valid, isect_hit, check_holds;
  logic [SlotW-1:0]    node_tag, res_slot;
  logic [NODE_W-1:0]   node_data;
  logic [31:0]         visit_node_id;
  logic                visit_leaf;
  logic [COUNT_W-1:0]  visit_count;
  logic [ADDR_W-1:0]   node_addr, idx_addr;
  logic [ENTRY_W-1:0]  check_exit;
  logic [31:0]         done_nodes, done_tests;

  // ---- Records kept by slot index ---------------------------------------------------
  logic [31:0]         nodes_q [N];
  logic [31:0]         tests_q [N];

  // The setup's outputs.
  logic                 su_valid;
  logic [SlotW-1:0]     su_slot;
  rt_pkg::isect_ray_t   su_ray;
  logic [2:0]           su_mirror, su_active;
  logic [3*(P+1)-1:0]   su_origin;
  logic [3*PAIR_W-1:0]  su_pair;
  logic [COM_W-1:0]     su_common;
  logic [DIR_W-1:0]     su_dom;

  // The box tester's operands (the responding slot's ray) and answer.
  logic [3*(P+1)-1:0]   box_origin;
  logic [2:0]           box_mirror, box_active;
  logic [3*PAIR_W-1:0]  box_pair;
  logic                 box_valid, box_near;
  logic [SlotW-1:0]     box_slot;
  logic [1:0]           box_hit;
  logic [2*ENTRY_W-1:0] box_entry;
  logic [2*REF_W-1:0]   box_child;

  // ---- The shell: streams, memory ports, rt_isect, closest hits, exit tests ----------
  rt_trav_shell #(
    .N(N), .IdxBufDepth(IdxBufDepth), .NodeRspW(NODE_W), .RegRsp(1'b0),
    .VisitIdW(32), .ExitW(ENTRY_W), .DenW(COM_W)
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
    .isect_hit_o   (isect_hit),
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
  rt_bvh_setup #(.SlotW(SlotW)) u_setup (
    .clk_i,
    .rst_ni,
    .valid_i  (ray_fire),
    .slot_i   (alloc_idx),
    .ray_i    (ray_data_i),
    .valid_o  (su_valid),
    .slot_o   (su_slot),
    .ray_o    (su_ray),
    .dom_o    (su_dom),
    .mirror_o (su_mirror),
    .active_o (su_active),
    .origin_o (su_origin),
    .pair_o   (su_pair),
    .common_o (su_common)
  );

  // ---- The box tester ------------------------------------------------------------------
  rt_bvh_box #(.SlotW(SlotW)) u_box (
    .clk_i,
    .rst_ni,
    .valid_i  (node_valid),
    .slot_i   (node_tag),
    .node_i   (node_data),
    .origin_i (box_origin),
    .mirror_i (box_mirror),
    .active_i (box_active),
    .pair_i   (box_pair),
    .valid_o  (box_valid),
    .slot_o   (box_slot),
    .hit_o    (box_hit),
    .entry_o  (box_entry),
    .near_o   (box_near),
    .child_o  (box_child)
  );

  // ---- Slots: the BVH walks -------------------------------------------------------------
  rt_bvh_slots #(.N(N), .SlotW(SlotW)) u_slots (
    .clk_i,
    .rst_ni,
    .free_o           (free),
    .alloc_i          (ray_fire),
    .alloc_slot_i     (alloc_idx),
    .init_i           (su_valid),
    .init_slot_i      (su_slot),
    .init_root_i      (cfg_root_i),
    .init_any_hit_i   (su_ray.any_hit),
    .init_mirror_i    (su_mirror),
    .init_active_i    (su_active),
    .init_origin_i    (su_origin),
    .init_pair_i      (su_pair),
    .want_visit_o     (want_visit),
    .visit_go_i       (visit_go),
    .visit_slot_i     (visit_idx),
    .visit_node_id_o  (visit_node_id),
    .visit_leaf_o     (visit_leaf),
    .visit_count_o    (visit_count),
    .want_node_o      (want_node),
    .node_go_i        (node_go),
    .node_slot_i      (node_idx),
    .node_addr_o      (node_addr),
    .waiting_node_o   (waiting_node),
    .node_rsp_valid_i (node_valid),
    .node_rsp_slot_i  (node_tag),
    .box_origin_o     (box_origin),
    .box_mirror_o     (box_mirror),
    .box_active_o     (box_active),
    .box_pair_o       (box_pair),
    .box_valid_i      (box_valid),
    .box_slot_i       (box_slot),
    .box_hit_i        (box_hit),
    .box_entry_i      (box_entry),
    .box_near_i       (box_near),
    .box_child_i      (box_child),
    .want_idx_o       (want_idx),
    .idx_go_i         (idx_go),
    .idx_slot_i       (idx_idx),
    .idx_addr_o       (idx_addr),
    .fetching_o       (fetching),
    .res_valid_i      (isect_valid),
    .res_slot_i       (res_slot),
    .res_hit_i        (isect_hit),
    .bound_i          (bound),
    .want_check_o     (want_check),
    .check_sel_i      (check_sel),
    .check_exit_o     (check_exit),
    .check_go_i       (check_go),
    .check_slot_i     (check_idx),
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
      if (visit_leaf) tests_q[visit_idx] <= tests_q[visit_idx] + 32'(visit_count);
    end
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
