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
//              the per-slot ray and closest hit, the exit test, the counts,
//              the results (the node port is its node port, not registered:
//              RegRsp = 0)
//   u_walk     rt_bvh_slots: the per-ray setup (multiplications only, 3
//              stages), the box tester (both children of a node response,
//              BVH_BOX_LATENCY stages, one node a cycle) and RaysInFlight
//              slots: walk state, candidates, stacks, the pop lane
//   visit_*    one record per node entered (round robin over slots in ENTER)
//   node port  one node read per interior node entered (round robin)
//   idx port   one index-list read per test (round robin), credit-limited
//   tri port   one triangle read per index response, in index-response order
//   check      one exit test per cycle (round robin over the candidates of
//              bound slots with a non-zero entry)
//   res_*      one record per ray
//
// rt_bvh_slots keeps the walks; rt_trav_shell the ray, its closest hit, the
// dominant, the common denominator of the exit test and the counts.
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

  // The figures of the shell's ports toward the walk (rt_walk_ports.svh).
  localparam int unsigned N         = RaysInFlight;
  localparam int unsigned NodeRspW  = rt_pkg::BVH_NODE_W;
  localparam int unsigned VisitIdW  = 32;
  localparam int unsigned ExitW     = rt_pkg::BVH_ENTRY_W;
  localparam int unsigned DenW      = rt_pkg::BVH_COMMON_W;
  localparam int unsigned TestPorts = 1;
`include "rt_walk_ports.svh"

  // The shell (streams, memory ports, rt_isect, closest hits, exit tests, the
  // counts) and the BVH walk, joined by name.
  rt_trav_shell #(`RT_WALK_PARAMS, .IdxBufDepth(IdxBufDepth), .RegRsp(1'b0)) u_shell (.*);
  rt_bvh_slots  #(`RT_WALK_PARAMS) u_walk (.*);

endmodule
