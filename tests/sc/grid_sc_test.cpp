// The SystemC side of rt_grid beyond the shared suite (trav_sc_suite.h, run
// over the unit by trav_sc_units.cpp, with the grid's third implementation,
// the cycle model holding the Verilated rt_isect): one kernel shared with the
// intersection pipeline's device.
#include <gtest/gtest.h>

#include <vector>

#include "driver/golden_device.h"
#include "driver/systemc_isect_device.h"
#include "golden/grid.h"
#include "trav_sc_suite.h"

namespace lancer {
namespace {

using Grid = test::ScUnit<fx::GridUnit>;

TEST(ScGridDevice, GridAndIsectDevicesShareOneKernel) {
  // Either unit's SystemC system may run first; both are elaborated together
  // (the pin-level models: the value-port ones use no kernel).
  const test::QuantizedScene q = Grid::bunny(4, 4);
  const fx::GridImage image = fx::buildGridImage(q.triangles, {8, 8, 8});
  std::vector<IsectRequest> pairs;
  for (size_t i = 0; i < 20; ++i) pairs.push_back({q.rays[i % q.rays.size()], q.triangles[i]});
  std::vector<fx::IsectResult> want, got;
  GoldenIsectDevice().run(pairs, want);
  for (int round = 0; round < 2; ++round) {
    SystemCIsectDevice isect(SystemCIsectDevice::Impl::Pins);
    got.clear();
    isect.run(pairs, got);
    EXPECT_EQ(got, want);
    SystemCGridDevice grid(SystemCImpl::Pins);
    Grid::expectSameTraces(grid, image, q.rays, Grid::rough(40 + round), "interleaved");
  }
}

}  // namespace
}  // namespace lancer
