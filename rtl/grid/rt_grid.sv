// rt_grid: the integer-DDA uniform-grid traversal unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseGrid (sw/golden/grid.h): for every ray the same
// cells in the same order, every triangle of every visited cell tested (index
// list order, duplicates across cells included), the closest hit by
// fx::closerResult, and the same stop rule (stop once the closest hit so far
// lies within the current cell, or when the ray leaves the grid).
// docs/grid-unit.md specifies the micro-architecture cycle by cycle.
//
//   u_shell    rt_trav_shell: ray input and slot allocation, the arbiters and
//              FIFOs of every port, the index and triangle path to rt_isect,
//              the per-slot ray and closest hit, the exit test, the results
//              (the cell port is its node port, registered: RegRsp = 1)
//   u_setup    per-ray setup, multiplications only (2 stages)
//   u_slots    RaysInFlight ray slots (rt_grid_slots): state machines, DDA
//              frontiers, cell queues, counters, the exit accumulators
//   cell port  cell-table reads, prefetched: each slot reads up to CellQueue
//              cells ahead of the one it is in (round robin over slots); the
//              DDA steps at the grant, one step per cycle
//   visit_*    one record per cell entered (round robin over slots whose next
//              cell has been requested); res_* one record per ray
//   idx port   one index-list read per test (round robin over slots), credit-
//              limited by the index buffer (IdxBufDepth)
//   tri port   one triangle read per index response, in index-response order
//   u_isect    rt_isect; a triangle response enters it in the cycle after it arrives
//   closest    one isect result per cycle updates its slot's closest hit
//   check      one exit test per cycle (round robin over slots with a hit)
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based: index responses land in the index buffer, which is never
// overfilled; cell and triangle responses are registered at the boundary and
// consumed in the next cycle). Responses per port must come in request order;
// the tag is the slot. A cell read past the cell where a ray stops (a
// prefetch) is read and dropped.
//
// Latency:    >= 1 + GRID_SETUP_LATENCY (setup) + per cell: cell read (hidden by the prefetch once
//             the ray is under way) + (index and triangle reads + ISECT_LATENCY
//             if the cell holds triangles) + 1 (visit) cycles per ray.
// Throughput: per cycle at most one ray accepted, one cell read (one DDA
//             step), one visit record, one index read, one triangle read, one
//             intersection test, one exit test and one result.
module rt_grid #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned CellQueue    = 2,   // cells per slot read and not finished (power of 2, >= 2)
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     // derived
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Configuration, static while rays are in flight.
  input  logic [3*rt_pkg::GRID_RESOLUTION_W-1:0] cfg_res_i,    // {Rz, Ry, Rx}, each 1..256
  input  logic [CfgSlotsW-1:0]                   cfg_slots_i,  // slots to use, 1..RaysInFlight

`include "rt_trav_ports.svh"

  // One result per ray, one record per cell entered.
  output rt_pkg::grid_res_t                      res_data_o,
  output rt_pkg::grid_visit_t                    visit_data_o,

  // Cell table reads.
  output logic                                   cell_req_valid_o,
  input  logic                                   cell_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          cell_req_addr_o,
  output logic [SlotW-1:0]                       cell_req_tag_o,
  input  logic                                   cell_rsp_valid_i,
  input  rt_pkg::grid_cell_t                     cell_rsp_data_i,
  input  logic [SlotW-1:0]                       cell_rsp_tag_i
);

  localparam int N        = RaysInFlight;
  localparam int ADDR_W   = rt_pkg::MEM_ADDR_W;
  localparam int CELL_W   = rt_pkg::CELL_INDEX_W;
  localparam int ID_W     = 3 * CELL_W;
  localparam int ACC_W    = rt_pkg::GRID_ACC_W;
  localparam int PAIR_W   = rt_pkg::GRID_PAIR_W;
  localparam int TRIPLE_W = rt_pkg::GRID_TRIPLE_W;
  localparam int DIR_W    = rt_pkg::DIR_W;

  // ---- The shell: streams, memory ports, rt_isect, closest hits, exit tests ----------
  logic [N-1:0]        free, want_cell, want_visit, want_idx, want_check, want_done, fetching, bound;
  logic                ray_fire, cell_go, visit_go, idx_go, check_go, done_go;
  logic [SlotW-1:0]    alloc_idx, check_sel, cell_idx, visit_idx, idx_idx, check_idx, done_idx;
  logic                cell_valid, isect_valid, isect_hit, check_holds;
  logic [SlotW-1:0]    cell_tag, isect_slot;
  rt_pkg::grid_cell_t  cell_data;
  logic [ID_W-1:0]     cell_cell_id, visit_cell_id;
  logic [ADDR_W-1:0]   cell_addr, idx_addr;
  logic [ACC_W-1:0]    check_exit;
  logic [31:0]         done_cells, done_tests;

  // The setup's outputs.
  logic                 su_valid;
  logic [SlotW-1:0]     su_slot;
  rt_pkg::isect_ray_t   su_ray;
  logic [3*CELL_W-1:0]  su_cell, su_cell_id;
  logic [2:0]           su_active, su_neg;
  logic [3*ACC_W-1:0]   su_acc;
  logic [3*PAIR_W-1:0]  su_pair;
  logic [TRIPLE_W-1:0]  su_triple;
  logic [DIR_W-1:0]     su_dom;

  // (The address as a wire of its own: Yosys 0.23 drops a size cast inside a concatenation.)
  assign cell_addr = ADDR_W'(cell_cell_id);

  rt_trav_shell #(
    .N(N), .IdxBufDepth(IdxBufDepth), .NodeRspW(rt_pkg::GRID_CELL_W), .RegRsp(1'b1),
    .VisitIdW(ID_W), .ExitW(ACC_W), .DenW(TRIPLE_W)
  ) u_shell (
    // The unit's own ports by name (.*): the same ports as the shell's, but
    // for the cell port, the shell's node port.
    .*,
    .node_req_valid_o (cell_req_valid_o),
    .node_req_ready_i (cell_req_ready_i),
    .node_req_addr_o  (cell_req_addr_o),
    .node_req_tag_o   (cell_req_tag_o),
    .node_rsp_valid_i (cell_rsp_valid_i),
    .node_rsp_data_i  (cell_rsp_data_i),
    .node_rsp_tag_i   (cell_rsp_tag_i),
    .free_i        (free),
    .alloc_o       (ray_fire),
    .alloc_slot_o  (alloc_idx),
    .init_i        (su_valid),
    .init_slot_i   (su_slot),
    .init_ray_i    (su_ray),
    .init_dom_i    (su_dom),
    .init_den_i    (su_triple),
    .want_node_i   (want_cell),
    .node_go_o     (cell_go),
    .node_slot_o   (cell_idx),
    .node_addr_i   (cell_addr),
    .node_valid_o  (cell_valid),
    .node_tag_o    (cell_tag),
    .node_data_o   (cell_data),
    .want_visit_i  (want_visit),
    .visit_go_o    (visit_go),
    .visit_slot_o  (visit_idx),
    .visit_id_i    (visit_cell_id),
    .want_idx_i    (want_idx),
    .idx_go_o      (idx_go),
    .idx_slot_o    (idx_idx),
    .idx_addr_i    (idx_addr),
    .expect_i      (fetching),
    .isect_valid_o (isect_valid),
    .isect_slot_o  (isect_slot),
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
    .done_count_i  (done_cells),
    .done_tests_i  (done_tests)
  );

  // ---- Setup ---------------------------------------------------------------------
  rt_grid_setup #(.SlotW(SlotW)) u_setup (
    .clk_i,
    .rst_ni,
    .cfg_res_i,
    .valid_i   (ray_fire),
    .slot_i    (alloc_idx),
    .ray_i     (ray_data_i),
    .valid_o   (su_valid),
    .slot_o    (su_slot),
    .ray_o     (su_ray),
    .cell_o    (su_cell),
    .cell_id_o (su_cell_id),
    .active_o  (su_active),
    .neg_o     (su_neg),
    .acc_o     (su_acc),
    .pair_o    (su_pair),
    .triple_o  (su_triple),
    .dom_o     (su_dom)
  );

  // ---- Slots: the DDA walk ---------------------------------------------------------
  rt_grid_slots #(.N(N), .CellQueue(CellQueue), .SlotW(SlotW)) u_slots (
    .clk_i,
    .rst_ni,
    .cfg_res_i,
    .free_o          (free),
    .alloc_i         (ray_fire),
    .alloc_slot_i    (alloc_idx),
    .init_i          (su_valid),
    .init_slot_i     (su_slot),
    .init_cell_i     (su_cell),
    .init_cell_id_i  (su_cell_id),
    .init_active_i   (su_active),
    .init_neg_i      (su_neg),
    .init_acc_i      (su_acc),
    .init_pair_i     (su_pair),
    .want_cell_o     (want_cell),
    .cell_go_i       (cell_go),
    .cell_slot_i     (cell_idx),
    .cell_id_o       (cell_cell_id),
    .cell_rsp_valid_i(cell_valid),
    .cell_rsp_tag_i  (cell_tag),
    .cell_rsp_data_i (cell_data),
    .want_visit_o    (want_visit),
    .visit_go_i      (visit_go),
    .visit_slot_i    (visit_idx),
    .visit_cell_id_o (visit_cell_id),
    .want_idx_o      (want_idx),
    .idx_go_i        (idx_go),
    .idx_slot_i      (idx_idx),
    .idx_addr_o      (idx_addr),
    .fetching_o      (fetching),
    .res_valid_i     (isect_valid),
    .res_slot_i      (isect_slot),
    .bound_i         (bound),
    .res_hit_i       (isect_hit),
    .want_check_o    (want_check),
    .check_sel_i    (check_sel),
    .check_go_i      (check_go),
    .check_slot_i    (check_idx),
    .check_exit_o    (check_exit),
    .check_holds_i   (check_holds),
    .want_done_o     (want_done),
    .done_go_i       (done_go),
    .done_slot_i     (done_idx),
    .done_cells_o    (done_cells),
    .done_tests_o    (done_tests)
  );

endmodule
