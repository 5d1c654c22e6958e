#pragma once

// One clock cycle at the ports of a traversal unit (rt_octree; rt_grid's
// GridCycle has the same fields with cell_* for node_*), as the testbench
// samples it at the rising edge that ends the cycle. Free of SystemC types so
// that the driver and the tests can hold traces without including SystemC.

#include <cstdint>
#include <vector>

namespace lancer::sc {

struct TraversalCycle {
  uint64_t cycle = 0;                           // counted from the cycle the first ray was offered
  bool rayValid = false, rayReady = false;      // ray_valid_i, ray_ready_o
  bool resValid = false, resReady = false;      // res_valid_o, res_ready_i
  bool visitValid = false, visitReady = false;  // visit_valid_o, visit_ready_i
  // {valid, addr, tag} of node_req_*, idx_req_*, tri_req_* (addr, tag 0 unless valid).
  bool nodeReq = false, idxReq = false, triReq = false;
  uint32_t nodeAddr = 0, nodeTag = 0, idxAddr = 0, idxTag = 0, triAddr = 0, triTag = 0;
  bool triQuadric = false;          // tri_req_quadric_o while tri_req_valid_o (the quadric table)
  bool perfIsectFire = false;       // perf_isect_fire_o
  bool perfStepReady = false;       // perf_step_ready_o (units that have it)
  std::vector<uint32_t> resData;    // res_data_o's wire image while res_valid_o, else empty
  std::vector<uint32_t> visitData;  // visit_data_o's wire image while visit_valid_o, else empty
  bool operator==(const TraversalCycle&) const = default;
};

}  // namespace lancer::sc
