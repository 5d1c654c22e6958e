#pragma once

// The treelet schedule's walks in the golden models, as the run loop drives
// them (docs/scheduling.md): every ray's walk set aside where it leaves its
// block within the unit's suspend window, carried through the unit's walk
// record (as its ports carry it), and resumed block by block, the fullest
// queue first, interleaved with every other ray's.
//
// Ops names a unit's walk: Image, Walk, start(image), resume(image, ray, walk,
// block), carry(walk, ray) (through the record and back), window (the stack
// entries a suspension may hold), traverse(image, ray) (the unbroken walk),
// crossings(image, ray) (the golden count of its block crossings).

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <map>
#include <random>
#include <span>
#include <vector>

#include "golden/records.h"
#include "golden/trace.h"
#include "support/traversal_cases.h"

namespace lancer::test {

// Each walk must end where its unbroken walk ends (the same visits, tests and
// hit); returns the suspensions.
template <class Ops>
uint64_t walkBlockByBlock(const typename Ops::Image& image, std::span<const fx::QRay> rays) {
  std::vector<typename Ops::Walk> walks;
  std::map<uint32_t, std::deque<size_t>> queues;  // block -> rays waiting for it
  for (size_t r = 0; r < rays.size(); ++r) {
    walks.push_back(Ops::start(image));
    queues[walks.back().waitsFor(image)].push_back(r);
  }
  uint64_t suspensions = 0;
  while (!queues.empty()) {
    auto fullest = std::max_element(queues.begin(), queues.end(),
                                    [](const auto& a, const auto& b) { return a.second.size() < b.second.size(); });
    const uint32_t block = fullest->first;
    std::deque<size_t> batch = std::move(fullest->second);
    queues.erase(fullest);
    for (const size_t r : batch) {
      Ops::resume(image, rays[r], walks[r], block);
      if (walks[r].done()) continue;
      EXPECT_LE(walks[r].stack.size(), size_t(Ops::window)) << "ray " << r << ": beyond the window";
      typename Ops::Walk carried = Ops::carry(walks[r], rays[r]);
      carried.trace.visits = std::move(walks[r].trace.visits);  // the visits and counts stay with the driver
      carried.trace.tests = walks[r].trace.tests;
      carried.trace.quadricTests = walks[r].trace.quadricTests;
      walks[r] = std::move(carried);
      queues[walks[r].waitsFor(image)].push_back(r);
      ++suspensions;
    }
  }
  for (size_t r = 0; r < rays.size(); ++r) {
    EXPECT_EQ(walks[r].trace, Ops::traverse(image, rays[r])) << "ray " << r << ", blocks of " << image.treeletNodes;
  }
  return suspensions;
}

// walkBlockByBlock, and the count: the walks set aside are exactly the
// crossings within the window (Ops::crossings); returns them.
template <class Ops>
uint64_t checkBlockByBlock(const typename Ops::Image& image, std::span<const fx::QRay> rays) {
  const uint64_t suspensions = walkBlockByBlock<Ops>(image, rays);
  fx::TreeletCrossings crossings;
  for (const fx::QRay& ray : rays) crossings += Ops::crossings(image, ray);
  EXPECT_EQ(suspensions, crossings.suspensions) << "blocks of " << image.treeletNodes;
  EXPECT_GE(crossings.crossings, crossings.suspensions);
  return suspensions;
}

// `count` random lattice rays for a treelet walk, every third an any-hit ray.
inline std::vector<fx::QRay> treeletRays(uint64_t seed, uint32_t count) {
  std::mt19937_64 rng{seed};
  std::vector<fx::QRay> rays;
  for (uint32_t i = 0; i < count; ++i) {
    rays.push_back(randomLatticeRay(rng, i));
    rays.back().anyHit = i % 3 == 0;
  }
  return rays;
}

}  // namespace lancer::test
