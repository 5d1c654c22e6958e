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
//              the per-slot ray and closest hit, the exit test, the counts,
//              the results (the cell port is its node port, registered:
//              RegRsp = 1)
//   u_walk     rt_grid_slots: the per-ray setup (multiplications only, 3
//              stages) and RaysInFlight ray slots: state machines, DDA
//              frontiers, cell queues, the exit accumulators
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

  // The figures of the shell's ports toward the walk (rt_walk_ports.svh).
  localparam int unsigned N         = RaysInFlight;
  localparam int unsigned NodeRspW  = rt_pkg::GRID_CELL_W;
  localparam int unsigned VisitIdW  = 3 * rt_pkg::CELL_INDEX_W;
  localparam int unsigned ExitW     = rt_pkg::GRID_ACC_W;
  localparam int unsigned DenW      = rt_pkg::GRID_TRIPLE_W;
  localparam int unsigned TestPorts = 2;
`include "rt_walk_ports.svh"

  // The shell (streams, memory ports, rt_isect, closest hits, exit tests, the
  // counts) and the DDA walk, joined by name; the cell port is the shell's
  // node port.
  rt_trav_shell #(`RT_WALK_PARAMS, .IdxBufDepth(IdxBufDepth), .RegRsp(1'b1)) u_shell (
    .*,
    .node_req_valid_o (cell_req_valid_o),
    .node_req_ready_i (cell_req_ready_i),
    .node_req_addr_o  (cell_req_addr_o),
    .node_req_tag_o   (cell_req_tag_o),
    .node_rsp_valid_i (cell_rsp_valid_i),
    .node_rsp_data_i  (cell_rsp_data_i),
    .node_rsp_tag_i   (cell_rsp_tag_i));
  rt_grid_slots #(`RT_WALK_PARAMS, .CellQueue(CellQueue)) u_walk (.*);

endmodule
