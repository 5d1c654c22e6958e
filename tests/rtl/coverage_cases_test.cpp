// Cases for the RTL coverage and the stream assertions (docs/coverage.md):
// the traversal units' ray input check a_ray_hold (rt_trav_shell: an offered
// ray stays offered, unchanged, until taken) is compiled in and fires when
// the producer breaks the rule, in rt_grid and in rt_octree, as rt_isect's
// a_req_hold does in RtIsectPorts.AssertionsAreLive.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "Vrt_grid.h"
#include "Vrt_octree.h"
#include "driver/verilated_port.h"
#include "driver/verilated_unit.h"
#include "golden/records.h"
#include "isect/isect_cases.h"
#include "stream_rule.h"

namespace lancer {
namespace {

// What both units share at reset: nothing offered, no result or visit taken
// (so slots fill and stay full), memory ready and silent, one ray slot.
template <class Top>
void idleShared(Top& top) {
  top.ray_valid_i = 0;
  top.res_ready_i = 0;
  top.visit_ready_i = 0;
  top.idx_req_ready_i = 1;
  top.tri_req_ready_i = 1;
  top.idx_rsp_valid_i = 0;
  top.tri_rsp_valid_i = 0;
  top.cfg_slots_i = 1;
}

void idleGrid(Vrt_grid& top) {
  idleShared(top);
  top.node_req_ready_i = 1;
  top.node_rsp_valid_i = 0;
  top.cfg_res_i = 1 | (1 << 9) | (1 << 18);  // 1 x 1 x 1 cells
}

void idleOctree(Vrt_octree& top) {
  idleShared(top);
  top.node_req_ready_i = 1;
  top.node_rsp_valid_i = 0;
  top.cfg_root_i = 0;  // an empty root leaf
}

// Offers rays, each held until taken, until one has been refused for three
// cycles (its slot and the result queue are full), then withdraws it untaken.
// Returns what the unit threw ("" if nothing, or why the setup failed).
template <class Top, class Idle>
std::string withdrawRefusedRay(VerilatedUnit<Top>& unit, Idle idle) {
  unit.reset(idle);
  Top& top = unit.top();
  const auto pairs = rtltest::randomPairs(16, 11);
  fx::RayWire ray;
  const auto offer = [&]() -> std::string {
    int refused = 0;
    for (size_t k = 0, cycle = 0; refused < 3; ++cycle) {
      if (cycle > 200 || k >= pairs.size()) return "no ray was ever refused";
      fx::packWire(pairs[k].ray, ray);
      writePort(top.ray_data_i, ray.data(), ray.size());
      top.ray_valid_i = 1;
      unit.settle();
      const bool taken = top.ray_ready_o;
      unit.tick();
      if (taken) {
        ++k;
        refused = 0;
      } else {
        ++refused;
      }
    }
    return "";
  };
  return rtltest::withdrawRefused(unit, offer, [](Top& t) { t.ray_valid_i = 0; });
}

TEST(StreamAssertions, GridRayInputHoldIsLive) {
  VerilatedUnit<Vrt_grid> unit("rt_grid");
  const std::string what = withdrawRefusedRay(unit, idleGrid);
  EXPECT_NE(what.find("assertion of rt_grid failed"), std::string::npos) << what;
}

TEST(StreamAssertions, OctreeRayInputHoldIsLive) {
  VerilatedUnit<Vrt_octree> unit("rt_octree");
  const std::string what = withdrawRefusedRay(unit, idleOctree);
  EXPECT_NE(what.find("assertion of rt_octree failed"), std::string::npos) << what;
}

// The same stimulus with the rule kept (the ray stays offered) fires nothing.
TEST(StreamAssertions, HeldRayFiresNothing) {
  VerilatedUnit<Vrt_grid> unit("rt_grid");
  unit.reset(idleGrid);
  Vrt_grid& top = unit.top();
  fx::RayWire ray;
  fx::packWire(rtltest::randomPairs(1, 11)[0].ray, ray);
  writePort(top.ray_data_i, ray.data(), ray.size());
  top.ray_valid_i = 1;
  for (int cycle = 0; cycle < 50; ++cycle) EXPECT_NO_THROW(unit.step()) << "cycle " << cycle;
}

}  // namespace
}  // namespace lancer
