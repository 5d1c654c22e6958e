#pragma once

// Every traversal device against the golden walk, as the SystemC and the RTL
// tests compare them (tests/sc/trav_sc_suite.h, tests/rtl/trav_rtl_suite.h),
// and a unit's runs as those tests make them (UnitRuns, over its traits in
// unit_traits.h).

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/traversal_device.h"
#include "golden/trace.h"
#include "support/mixed_scenes.h"
#include "support/traversal_cases.h"
#include "support/unit_traits.h"

namespace lancer::test {

// How a failing ray is described: the image, the ray, a trace.
template <class Image>
struct Describe {
  std::function<std::string(const Image&)> image;
  std::function<std::string(const fx::QRay&)> ray;
  std::function<std::string(const fx::TraversalTrace&)> trace;
};

struct GoldenAndDevice {
  TraversalRunStats golden, device;
};

// Runs `golden` and `device` on the same rays, expects identical traces (the
// first five differing rays reported) and golden's counters where every unit
// must have them (steps, index and triangle reads, tests); node reads are the
// unit's to check (the grid prefetches).
template <class Image>
GoldenAndDevice expectGoldenTraces(TraversalDevice<Image>& golden, TraversalDevice<Image>& device, const Image& image,
                                   const std::vector<fx::QRay>& rays, const TraversalRunOptions& options,
                                   const std::string& what, const Describe<Image>& describe) {
  std::vector<fx::TraversalTrace> want, got;
  const TraversalRunStats g = golden.run(image, rays, want, options);
  const TraversalRunStats r = device.run(image, rays, got, options);
  EXPECT_EQ(got.size(), want.size()) << what;
  int reported = 0;
  for (size_t k = 0; k < std::min(got.size(), want.size()); ++k) {
    if (got[k] == want[k]) continue;
    ADD_FAILURE() << what << ": " << describe.image(image) << ", " << describe.ray(rays[k]) << "\n  " << device.name()
                  << ": " << describe.trace(got[k]) << "\n  golden: " << describe.trace(want[k]);
    if (++reported == 5) break;
  }
  EXPECT_EQ(r.rays, rays.size()) << what;
  EXPECT_EQ(r.steps, g.steps) << what;
  EXPECT_EQ(r.indexReads, g.indexReads) << what;
  EXPECT_EQ(r.triangleReads, g.triangleReads) << what;
  EXPECT_EQ(r.isectTests, g.isectTests) << what;
  EXPECT_EQ(r.quadricTests, g.quadricTests) << what;
  EXPECT_EQ(r.isectBusyCycles, r.isectTests) << what;
  EXPECT_TRUE(r.cycleAccurate) << what;
  EXPECT_GT(r.cycles, 0u) << what;
  return {g, r};
}


// A unit's runs as its tests make them: the bunny's camera rays through the
// image the driver would build, adverse run conditions, the comparison with
// golden under the unit's rules.
template <class Desc>
struct UnitRuns {
  using Traits = UnitTraits<Desc>;
  using Image = typename Traits::Image;
  using Case = TraversalCase<Image>;

  static QuantizedScene bunny(int width, int height) { return quantizedCamera(bunnyScene(), width, height); }
  // The unit's hard case of that name (Traits::hardCases, built once).
  static const Case& hardCase(const std::string& name) { return caseNamed<&Traits::hardCases>(name); }
  static Case bunnyCase(int side) {
    const QuantizedScene q = bunny(side, side);
    return {fmt::format("bunny {}x{}", side, side), Traits::image(q.triangles), q.rays};
  }
  // A random scene of triangles, spheres and cones (support/mixed_scenes.h)
  // in the image the driver would build, with rays at its primitives (a third
  // hard: grazing a sphere, at a cone's rim, from a surface).
  static Case mixedCase(int triangles, int quadrics, int rays, uint32_t seed) {
    QuantizedMixedScene q = quantizedMixedScene(triangles, quadrics, rays, seed);
    return {fmt::format("mixed {} triangles {} quadrics", triangles, quadrics),
            Desc::build(std::move(q.triangles), AccelOptions{}, std::move(q.quadrics)), std::move(q.rays)};
  }
  static TraversalRunOptions rough(uint64_t seed, int raysInFlight = 0) {
    return roughTraversalOptions(seed, raysInFlight);
  }
  static const Describe<Image>& describe() {
    static const Describe<Image> d{Traits::describeImage, describeLatticeRay, Traits::describeTrace};
    return d;
  }

  // Golden and `device` on the same run: identical traces and golden's
  // counters (node reads and step-ready cycles by the unit's rules); returns
  // the device's stats.
  static TraversalRunStats expectSameTraces(TraversalDevice<Image>& device, const Image& image,
                                            const std::vector<fx::QRay>& rays, const TraversalRunOptions& options,
                                            const std::string& what) {
    typename Traits::Golden golden;
    const auto [g, r] = expectGoldenTraces<Image>(golden, device, image, rays, options, what, describe());
    Traits::expectNodeReads(g.nodeReads, r.nodeReads, rays.size(), what);
    Traits::expectStepReadyCycles(r, what);
    return r;
  }
};

}  // namespace lancer::test
