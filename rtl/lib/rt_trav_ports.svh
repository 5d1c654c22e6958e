// The ports every traversal unit shares with its rt_trav_shell, first in the
// port lists of rt_trav_shell and of each unit (which add their result and
// visit records and their configuration). Needs the module's SlotW,
// CfgSlotsW and NodeRspW; every line ends with a comma.

  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic [CfgSlotsW-1:0]          cfg_slots_i,  // slots to use, 1..N; static while rays are in flight

  // Rays in.
  input  logic                          ray_valid_i,
  output logic                          ray_ready_o,
  input  rt_pkg::isect_ray_t            ray_data_i,

  // One result per ray, in any order (res_data_o: the unit's record).
  output logic                          res_valid_o,
  input  logic                          res_ready_i,

  // One record per region entered, in visiting order per ray (visit_data_o:
  // the unit's record).
  output logic                          visit_valid_o,
  input  logic                          visit_ready_i,

  // Index list reads.
  output logic                          idx_req_valid_o,
  input  logic                          idx_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0] idx_req_addr_o,
  output logic [SlotW-1:0]              idx_req_tag_o,
  input  logic                          idx_rsp_valid_i,
  input  logic [31:0]                   idx_rsp_data_i,
  input  logic [SlotW-1:0]              idx_rsp_tag_i,

  // Primitive reads, one port: the triangle table's record at tri_req_addr_o,
  // or the quadric table's when tri_req_quadric_o (an index entry's kind bit).
  // A triangle comes back on tri_rsp_*, a quadric on quadric_rsp_* (a unit
  // built with Quadrics; else never), never both in a cycle.
  output logic                          tri_req_valid_o,
  input  logic                          tri_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0] tri_req_addr_o,
  output logic                          tri_req_quadric_o,
  output logic [SlotW-1:0]              tri_req_tag_o,
  input  logic                          tri_rsp_valid_i,
  input  rt_pkg::isect_tri_t            tri_rsp_data_i,
  input  logic [SlotW-1:0]              tri_rsp_tag_i,
  input  logic                          quadric_rsp_valid_i,
  input  rt_pkg::isect_quadric_t        quadric_rsp_data_i,
  input  logic [SlotW-1:0]              quadric_rsp_tag_i,

  // Performance: a ray-primitive pair enters rt_isect or rt_quadric this cycle; some slot
  // waits to enter its next region (the visit arbiter has a request).
  output logic                          perf_isect_fire_o,
  output logic                          perf_step_ready_o,

  // Node reads: a grid's cells (grid_cell_t), an octree's child groups (the
  // eight octree_node_t records first .. first+7, element 0 least
  // significant), a BVH's nodes (bvh_node_t: both children's boxes), as plain
  // bits (Yosys 0.23 reads a port of a package type's packed array as one
  // element).
  output logic                          node_req_valid_o,
  input  logic                          node_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0] node_req_addr_o,
  output logic [SlotW-1:0]              node_req_tag_o,
  input  logic                          node_rsp_valid_i,
  input  logic [NodeRspW-1:0]           node_rsp_data_i,
  input  logic [SlotW-1:0]              node_rsp_tag_i,
