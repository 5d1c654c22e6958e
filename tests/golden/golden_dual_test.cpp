// The dual-precision front end (golden/dual.h): a rejection is a proof that the
// full-width test misses, fewer bits never reject more, and at full width it
// rejects every miss its edge signs or t decide.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "golden/dual.h"
#include "golden/isect.h"
#include "support/traversal_cases.h"

namespace lancer::fx {
namespace {

struct Pair {
  QRay ray;
  QTriangle tri;
};

// Random lattice rays, each against small triangles around points on its line,
// so that a fair share of the pairs hit and many miss by little.
std::vector<Pair> randomPairs(size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Pair> out;
  const int64_t spread = std::max<int64_t>(kPosMax / 64, 2);
  std::uniform_int_distribution<int64_t> offset(-spread, spread);
  std::uniform_real_distribution<double> along(-1.0, 1.0);
  while (out.size() < count) {
    const QRay ray = test::randomLatticeRay(rng, uint32_t(out.size()));
    for (int k = 0; k < 8; ++k) {
      const double s = along(rng) * double(kPosMax) / double(kDirMax);
      QTriangle tri;
      tri.id = uint32_t(k);
      for (auto& v : tri.v) {
        for (int a = 0; a < 3; ++a) {
          const int64_t centre = ray.org[size_t(a)] + int64_t(s * double(ray.dir[size_t(a)]));
          const int64_t jitter = offset(rng);
          v[size_t(a)] = std::clamp<int64_t>(centre + jitter, 0, kPosMax);
        }
      }
      out.push_back({ray, tri});
    }
  }
  return out;
}

TEST(DualPrecision, ARejectionIsAMissAtFullWidth) {
  uint64_t hits = 0, rejected = 0;
  for (const Pair& p : randomPairs(40000, 1)) {
    const bool hit = intersect(p.ray, p.tri).hit;
    hits += hit;
    for (int n = 2; n <= kPosBits; ++n) {
      const bool rejects = narrowRejects(p.ray, p.tri, n);
      rejected += rejects && n == kPosBits - 2;
      ASSERT_FALSE(rejects && hit) << "the " << n << "-bit front end rejected a hit: ray " << p.ray.id
                                   << ", triangle " << p.tri.id;
    }
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(rejected, 1000u);
}

TEST(DualPrecision, FewerBitsNeverRejectMore) {
  for (const Pair& p : randomPairs(20000, 2)) {
    bool coarser = false;
    for (int n = 2; n <= kPosBits; ++n) {
      const bool rejects = narrowRejects(p.ray, p.tri, n);
      ASSERT_TRUE(rejects || !coarser) << "rejected at fewer bits than " << n << ", not at " << n;
      coarser = rejects;
    }
  }
}

TEST(DualPrecision, AtFullWidthEveryDecidedMissIsRejected) {
  uint64_t misses = 0, rejected = 0;
  for (const Pair& p : randomPairs(20000, 3)) {
    // Triangles clamped into a lattice corner or edge are degenerate: their
    // determinant is 0, a miss the front end leaves to the full unit.
    std::array<int64_t, 3> e1{}, e2{};
    for (size_t a = 0; a < 3; ++a) {
      e1[a] = p.tri.v[1][a] - p.tri.v[0][a];
      e2[a] = p.tri.v[2][a] - p.tri.v[0][a];
    }
    const bool degenerate = e1[1] * e2[2] == e1[2] * e2[1] && e1[2] * e2[0] == e1[0] * e2[2] &&
                            e1[0] * e2[1] == e1[1] * e2[0];
    if (degenerate || intersect(p.ray, p.tri).hit) continue;
    ++misses;
    rejected += narrowRejects(p.ray, p.tri, kPosBits > kDirBits ? kPosBits : kDirBits);
  }
  // Only misses for a zero determinant (a ray parallel to the plane) are left.
  EXPECT_GE(double(rejected), 0.999 * double(misses));
}

}  // namespace
}  // namespace lancer::fx
