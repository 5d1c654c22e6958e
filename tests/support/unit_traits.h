#pragma once

// Each traversal unit as the shared test suites see it (tests/sc/trav_sc_suite.h):
// its image and devices, the image the driver would build for a scene, its hard
// cases, how a failing trace is described, and the one rule in which the units
// differ before a run is compared (the node reads). One specialization per unit;
// a unit's test file instantiates the suites over its descriptor in one line.

#include <array>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/accel_options.h"
#include "golden/units.h"
#include "support/bvh_cases.h"
#include "support/grid_cases.h"
#include "support/octree_cases.h"
#include "support/unit_devices.h"

namespace lancer::test {

template <class Desc>
struct UnitTraits;

// A walk that steps has cycles in which a slot could step, no more than its
// cycles and the few in which the last results drain.
inline void expectSomeStepReadyCycles(const TraversalRunStats& r, const std::string& what) {
  if (r.steps == 0) return;
  EXPECT_GT(r.stepReadyCycles, 0u) << what;
  EXPECT_LE(r.stepReadyCycles, r.cycles + 8) << what;
}

// What most units share: every hard case compared cycle for cycle, node reads
// exactly golden's, some step-ready cycles while nodes are stepped.
struct ExactWalkTraits {
  static bool cycleCase(const std::string&) { return true; }
  static void expectNodeReads(uint64_t golden, uint64_t device, size_t, const std::string& what) {
    EXPECT_EQ(device, golden) << what;
  }
  static void expectStepReadyCycles(const TraversalRunStats& r, const std::string& what) {
    expectSomeStepReadyCycles(r, what);
  }
};

// What follows from the descriptor, its SystemC traits and its Verilated
// class: the devices, the image the driver builds (its defaults), the slots,
// the trace's description. A unit's traits derive from it and add the rest.
template <class Desc, class ScTraits, class Vtop, class Rules = ExactWalkTraits>
struct UnitTraitsOf : Rules {
  using Image = typename Desc::Image;
  using Golden = GoldenTraversalDevice<Image>;
  using SystemC = SystemCTraversalDevice<Image, ScTraits>;
  using Verilator = VerilatorTraversalDevice<Vtop, Image>;
  static constexpr int kScRaysInFlight = ScTraits::RAYS_IN_FLIGHT;

  static Image image(const std::vector<fx::QTriangle>& triangles) { return Desc::build(triangles, AccelOptions{}); }
  static std::string describeTrace(const fx::TraversalTrace& trace) {
    return describeTraversalTrace(trace, Desc::kNames.elements, 16);
  }
};

// The grid prefetches: every cell entered is read, plus at most CellQueue - 1
// past a ray's last one; and a visit goes in every cycle some slot can step.
struct GridWalkTraits {
  // The cycle-for-cycle comparisons take the crowded and planar cases (the
  // others walk long empty stretches that add time, not coverage).
  static bool cycleCase(const std::string& name) { return name.rfind("crowded", 0) == 0 || name.rfind("planes", 0) == 0; }
  static void expectNodeReads(uint64_t golden, uint64_t device, size_t rays, const std::string& what) {
    EXPECT_GE(device, golden) << what;
    EXPECT_LE(device, golden + (kGridCellQueue - 1) * rays) << what;
  }
  static void expectStepReadyCycles(const TraversalRunStats& r, const std::string& what) {
    if (r.steps == 0) return;
    EXPECT_GE(r.stepReadyCycles, r.steps) << what;
    EXPECT_LE(r.stepReadyCycles, r.cycles) << what;
  }
};

template <>
struct UnitTraits<fx::GridUnit> : UnitTraitsOf<fx::GridUnit, sc::rt_grid_unit, Vrt_grid, GridWalkTraits> {
  // The cycle model, the Verilated RTL, and the cycle model holding the Verilated rt_isect.
  static constexpr std::array kScImpls{SystemCImpl::Model, SystemCImpl::Pins, SystemCImpl::Rtl, SystemCImpl::ModelRtlIsect};
  using KernelPartner = fx::OctreeUnit;  // a unit whose SystemC runs interleave with its own
  static Image empty() { return fx::buildGridImage({}, {1, 1, 1}); }
  static std::vector<TraversalCase<Image>> hardCases() { return gridHardCases(); }
  // A corrupt image: a cell whose triangles lie outside the index list (its
  // name: what the run's error says).
  static TraversalCase<Image> corruptImage() {
    Image broken = empty();
    broken.cells[0] = fx::GridCell{5, 1};
    return {"index list read at 5", broken, {fx::QRay{0, {0, 0, 0}, {fx::kDirMax, 0, 0}}}};
  }
  static std::vector<BuildVariant<Image>> buildVariants(const std::vector<fx::QTriangle>& tris) {
    std::vector<BuildVariant<Image>> out;
    for (const int r : {1, 4, 16, 64}) {
      out.push_back({fmt::format("res {}", r), fx::buildGridImage(tris, {r, r, r}), size_t(r == 1 ? 40 : 300),
                     uint64_t(3 + r)});
    }
    return out;
  }
  static std::string describeImage(const Image& image) {
    return fmt::format("grid {}x{}x{}", image.res[0], image.res[1], image.res[2]);
  }
};

template <>
struct UnitTraits<fx::OctreeUnit> : UnitTraitsOf<fx::OctreeUnit, sc::rt_octree_unit, Vrt_octree> {
  static constexpr std::array kScImpls{SystemCImpl::Model, SystemCImpl::Pins, SystemCImpl::Rtl};
  using KernelPartner = fx::GridUnit;
  static Image empty() { return fx::buildOctreeImage({}, 1, 1); }
  static std::vector<TraversalCase<Image>> hardCases() { return octreeHardCases(); }
  // A corrupt image: an interior node whose children lie outside the node table.
  static TraversalCase<Image> corruptImage() {
    Image broken = fx::buildOctreeImage({}, 1, 8);
    broken.nodes[0] = fx::OctreeNode{false, 5, 0};
    return {"outside the node table", broken, {fx::QRay{0, {0, 0, 0}, {fx::kDirMax, 0, 0}}}};
  }
  // A shallow tree tests hundreds of triangles per leaf: fewer rays there.
  static std::vector<BuildVariant<Image>> buildVariants(const std::vector<fx::QTriangle>& tris) {
    std::vector<BuildVariant<Image>> out;
    for (const auto& [depth, leaf] : {std::pair{1, 8}, {4, 8}, {8, 1}, {fx::kOctreeMaxDepth, 2}}) {
      out.push_back({fmt::format("depth {} leaf {}", depth, leaf), fx::buildOctreeImage(tris, depth, leaf),
                     size_t(depth == 1 ? 40 : 300), uint64_t(3 + depth)});
    }
    return out;
  }
  static std::string describeImage(const Image& image) { return fmt::format("octree depth {}", image.depth); }
};

template <>
struct UnitTraits<fx::BvhUnit> : UnitTraitsOf<fx::BvhUnit, sc::rt_bvh_unit, Vrt_bvh> {
  static constexpr std::array kScImpls{SystemCImpl::Model, SystemCImpl::Pins, SystemCImpl::Rtl};
  using KernelPartner = fx::OctreeUnit;
  static Image empty() { return fx::buildBvhImage({}, 4); }
  static std::vector<TraversalCase<Image>> hardCases() { return bvhHardCases(); }
  // A corrupt image: an interior child that lies outside the node table.
  static TraversalCase<Image> corruptImage() {
    Image broken = bvhTwoEmptyLeaves();
    broken.nodes[0].child[1] = fx::BvhRef{false, 0, 5};
    return {"outside the node table", broken, {fx::QRay{0, {5, 5, 5}, {fx::kDirMax, 3, 7}}}};
  }
  static std::vector<BuildVariant<Image>> buildVariants(const std::vector<fx::QTriangle>& tris) {
    std::vector<BuildVariant<Image>> out;
    for (const int leaf : {1, 4, 16, 255}) {
      out.push_back({fmt::format("leaf {}", leaf), fx::buildBvhImage(tris, leaf), size_t(leaf == 255 ? 60 : 300),
                     uint64_t(3 + leaf)});
    }
    return out;
  }
  static std::string describeImage(const Image& image) { return fmt::format("bvh depth {}", image.depth); }
};

}  // namespace lancer::test
