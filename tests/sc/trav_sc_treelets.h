#pragma once

// The treelet schedule on a unit's SystemC cycle model (docs/scheduling.md),
// shared by the units that set walks aside: a case's rays through the run
// loop's ray queues, on one unit with room for every walk and on four with a
// queue memory too small for them (overflow to DRAM), with the stream's
// bubbles and stalls, the second run repeated on four host threads.

#include <gtest/gtest.h>

#include <span>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "memory/ray_queues.h"
#include "support/traversal_cases.h"

namespace lancer::test {

// Every ray's trace must be `reference`'s, the units must set aside exactly
// `suspensions` walks (the golden walk's), every record on chip must be read
// back once, and the repeated run must be the same in every cycle. Adds the
// runs' queue figures to `all`.
template <class Device, class Image, class Reference>
void checkTreeletRuns(Device& device, const std::string& name, const Image& image, std::span<const fx::QRay> rays,
                      uint64_t suspensions, Reference reference, mem::RayQueueStats& all) {
  for (const auto& [units, kib] : {std::pair{1, 64}, std::pair{4, 1}}) {
    TraversalRunOptions o = treeletStressOptions(units, kib);
    std::vector<fx::TraversalTrace> traces;
    const TraversalRunStats s = device.run(image, rays, traces, o);
    const std::string where = fmt::format("{}, {} units, {} KiB", name, units, kib);
    ASSERT_EQ(traces.size(), rays.size()) << where;
    for (size_t k = 0; k < rays.size(); ++k) ASSERT_EQ(traces[k], reference(image, rays[k])) << where << ", ray " << k;
    EXPECT_EQ(s.queues.suspensions, suspensions) << where;
    EXPECT_EQ(s.queues.bytesRead, s.queues.bytesWritten) << where << ": every record on chip read back once";
    all += s.queues;
    if (units > 1) {
      o.hostThreads = 4;
      std::vector<fx::TraversalTrace> again;
      const TraversalRunStats t = device.run(image, rays, again, o);
      EXPECT_EQ(t.cycles, s.cycles) << where;
      EXPECT_EQ(t.queues, s.queues) << where;
      EXPECT_EQ(again, traces) << where;
    }
  }
}

}  // namespace lancer::test
