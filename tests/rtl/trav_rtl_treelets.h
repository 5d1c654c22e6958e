#pragma once

// The treelet schedule on a unit's RTL (docs/scheduling.md), shared by the
// units that set walks aside: a unit's hard cases, each laid out by `layOut`
// (the most suspensions: each node or child group its own block), on chips of
// one and four units with the stream's bubbles and stalls, with queue
// memories that overflow and that do not. Every ray must take its unbroken
// walk (`reference`), and the RTL must set aside the same walks in the same
// cycles as the SystemC model: the same cycles, traces and queue figures.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/devices.h"
#include "support/traversal_cases.h"

namespace lancer::rtltest {

// Returns the walks the runs set aside.
template <class Unit, class Cases, class LayOut, class Reference>
uint64_t expectTreeletRunsLikeTheModel(Cases cases, LayOut layOut, Reference reference) {
  const auto rtl = makeTraversalDevice<Unit>("rtl");
  const auto model = makeTraversalDevice<Unit>("systemc");
  uint64_t suspensions = 0;
  for (auto& c : cases) {
    layOut(c.image);
    for (const int units : {1, 4}) {
      for (const int kib : {1, 64}) {
        const TraversalRunOptions o = test::treeletStressOptions(units, kib);
        std::vector<fx::TraversalTrace> traces, modelTraces;
        const TraversalRunStats s = rtl->run(c.image, c.rays, traces, o);
        const TraversalRunStats m = model->run(c.image, c.rays, modelTraces, o);
        const std::string where = fmt::format("{}, {} units, {} KiB", c.name, units, kib);
        for (size_t k = 0; k < c.rays.size(); ++k) {
          EXPECT_EQ(traces.at(k), reference(c.image, c.rays[k])) << where << ", ray " << k;
        }
        EXPECT_EQ(s.cycles, m.cycles) << where;
        EXPECT_EQ(s.queues, m.queues) << where;
        EXPECT_EQ(s.unitRays, m.unitRays) << where;
        if (::testing::Test::HasFailure()) return suspensions;
        suspensions += s.queues.suspensions;
      }
    }
  }
  return suspensions;
}

}  // namespace lancer::rtltest
