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
//   u_walk     rt_octree_slots: the per-ray setup (multiplications only, 3
//              stages), the child groups read, RaysInFlight slots: walk
//              state, stacks, steps
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
// rt_octree_slots keeps the walks and their child groups; rt_trav_shell the
// ray, its closest hit, the dominant and common of the exit test, the counts.
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

  // The figures of the shell's ports toward the walk (rt_walk_ports.svh).
  localparam int unsigned N         = RaysInFlight;
  localparam int unsigned NodeRspW  = rt_pkg::OCTREE_CHILDREN * rt_pkg::OCTREE_NODE_W;
  localparam int unsigned VisitIdW  = 32;
  localparam int unsigned ExitW     = rt_pkg::OCTREE_T_W;
  localparam int unsigned DenW      = rt_pkg::OCTREE_COMMON_W;
  localparam int unsigned TestPorts = 1;
`include "rt_walk_ports.svh"

  // The shell (streams, memory ports, rt_isect, closest hits, exit tests, the
  // counts) and the octree walk, joined by name.
  rt_trav_shell   #(`RT_WALK_PARAMS, .IdxBufDepth(IdxBufDepth), .RegRsp(1'b0)) u_shell (.*);
  rt_octree_slots #(`RT_WALK_PARAMS) u_walk (.*);

endmodule
