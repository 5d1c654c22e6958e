// The golden sphere test (golden/quadric.h): the integer square root; every
// answer against exact arithmetic on random spheres and rays (the line meets
// the sphere exactly when it should; the root taken, its side and its error
// within the documented bound); and the hard cases: tangent rays, rays from
// inside, spheres behind the ray, segment ends, tiny and huge radii, and
// secondary rays leaving the surface outwards and inwards.

#include <gtest/gtest.h>

#include <random>

#include "golden/isect.h"
#include "golden/quadric.h"

namespace lancer::fx {
namespace {

TEST(GoldenIsqrt, IsTheFloorOfTheSquareRoot) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 20000; ++i) {
    const int bits = 1 + int(rng() % 126);
    const u128 v = ((u128(rng()) << 64) | rng()) >> (128 - bits);
    const u128 r = isqrt(v);
    ASSERT_LE(r * r, v) << i;
    ASSERT_GT((r + 1) * (r + 1), v) << i;
  }
  for (u128 v : {u128(0), u128(1), u128(2), u128(3), u128(4), u128(15), u128(16), u128(17)}) {
    const u128 r = isqrt(v);
    EXPECT_TRUE(r * r <= v && (r + 1) * (r + 1) > v);
  }
  const u128 top = (u128(1) << 126) - 1;
  EXPECT_EQ(isqrt(top), (u128(1) << 63) - 1);
}

QRay rayFrom(std::array<int64_t, 3> org, std::array<int64_t, 3> dir) {
  QRay r;
  r.org = org;
  r.dir = dir;
  return r;
}

// The exact quantities of the line against the sphere.
struct Exact {
  i128 a = 0, b = 0, c = 0, disc = 0;
  explicit Exact(const QRay& ray, const QSphere& s) {
    for (size_t k = 0; k < 3; ++k) {
      const i128 m = ray.org[k] - s.center[k], d = ray.dir[k];
      a += d * d;
      b += m * d;
      c += m * m;
    }
    c -= i128(s.radius) * s.radius;
    disc = b * b - a * c;
  }
  // -B - sqrt(disc) > 0, decided by squared forms (no square root).
  bool entersAhead() const { return b < 0 && b * b > disc; }
};

TEST(GoldenSphere, EveryAnswerAgreesWithExactArithmetic) {
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  int hits = 0, inside = 0, bounded = 0;
  for (uint32_t i = 0; i < 40000; ++i) {
    QSphere s{i, {pos(rng), pos(rng), pos(rng)}, 1 + int64_t(rng() % uint64_t(kPosMax / (1 + rng() % 64)))};
    std::array<int64_t, 3> d{dir(rng), dir(rng), dir(rng)};
    d[size_t(rng() % 3)] = rng() % 2 ? kDirMax : -kDirMax;  // a dominant component, as quantized rays have
    // Aim near the sphere half the time.
    QRay ray = rayFrom({pos(rng), pos(rng), pos(rng)}, d);
    if (i % 2) {
      for (size_t k = 0; k < 3; ++k) ray.org[k] = std::clamp<int64_t>(s.center[k] - d[k] / 4 + int64_t(rng() % 64) - 32, 0, kPosMax);
    }
    if (i % 5 == 0) {
      ray.tMax = rng() % (kSegEndNone / 2);
      ++bounded;
    }
    const IsectResult got = intersectSphere(ray, s);
    const Exact e(ray, s);
    if (e.disc < 0) {
      ASSERT_FALSE(got.hit) << i;
      continue;
    }
    // The roots as the pipeline rounds them: s = floor(sqrt(disc)), exactly.
    const i128 s0 = i128(isqrt(u128(e.disc)));
    ASSERT_TRUE(s0 * s0 <= e.disc && (s0 + 1) * (s0 + 1) > e.disc) << i;
    const i128 entering = -e.b - s0, leaving = -e.b + s0;
    if (!got.hit) {
      // A line that meets the sphere is missed only behind the ray or beyond the segment.
      const i128 n = entering > 0 ? entering : leaving;
      if (n > 0) {
        const int64_t dz = ray.dir[size_t(dominantAxis(ray.dir))];
        ASSERT_TRUE(mul256(u128(ray.tMax), u128(e.a)) < mul256(u128(n) * u128(dz < 0 ? -dz : dz), u128(1) << kSegFracBits))
            << i;
      }
      continue;
    }
    ++hits;
    ASSERT_EQ(got.det, u128(e.a));
    // The entering root when it is ahead, else the leaving one; each within
    // 1 / A of the exact root (n - n* = sqrt(disc) - s in [0, 1)).
    const i128 n = got.uNum == 0 ? entering : leaving;
    ASSERT_EQ(got.uNum == 0, entering > 0) << i;
    if (got.uNum == 1) ++inside;
    ASSERT_GT(n, 0) << i;
    const int64_t dz = ray.dir[size_t(dominantAxis(ray.dir))];
    ASSERT_EQ(got.tNum, u128(n) * u128(dz < 0 ? -dz : dz)) << i;
    // The exact arbiter's question without a square root: is the exact
    // entering root ahead? -B - sqrt(disc) > 0 iff B < 0 and B^2 > disc.
    if (got.uNum == 0 && !e.entersAhead()) {
      ASSERT_LT(-e.b - s0 - 1, 0) << "only a root within 1 / A of the origin is taken ahead of it";
    }
    // Within the segment.
    ASSERT_FALSE(mul256(u128(ray.tMax), got.det) < mul256(got.tNum, u128(1) << kSegFracBits)) << i;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(inside, 100);
  EXPECT_GT(bounded, 1000);
}

TEST(GoldenSphere, TangentRaysTouchAtOnePoint) {
  const int64_t mid = kPosMax / 2;
  for (const int64_t r : {int64_t(1), int64_t(7), kPosMax / 4}) {
    const QSphere s{3, {mid, mid, mid}, r};
    // Along x at distance exactly r from the center: disc = 0, one root.
    const QRay ray = rayFrom({mid - r - 100, mid + r, mid}, {kDirMax, 0, 0});
    const IsectResult got = intersectSphere(ray, s);
    ASSERT_TRUE(got.hit) << r;
    EXPECT_EQ(got.uNum, 0u);
    // Displacement along x: exactly r + 100 (t_num / det).
    EXPECT_EQ(got.tNum, u128(r + 100) * u128(kDirMax) * u128(kDirMax));
    EXPECT_EQ(got.det, u128(kDirMax) * u128(kDirMax));
    // One unit further out: a miss.
    EXPECT_FALSE(intersectSphere(rayFrom({mid - r - 100, mid + r + 1, mid}, {kDirMax, 0, 0}), s).hit);
  }
}

TEST(GoldenSphere, FromInsideBehindAndAlongTheSegment) {
  const int64_t mid = kPosMax / 2, r = 1000;
  const QSphere s{1, {mid, mid, mid}, r};
  // From the center: the leaving root, r ahead.
  IsectResult got = intersectSphere(rayFrom({mid, mid, mid}, {0, -kDirMax, 0}), s);
  ASSERT_TRUE(got.hit);
  EXPECT_EQ(got.uNum, 1u);
  EXPECT_EQ(got.tNum, u128(r) * u128(kDirMax) * u128(kDirMax));
  // The sphere behind the ray: a miss.
  EXPECT_FALSE(intersectSphere(rayFrom({mid + 2 * r, mid, mid}, {kDirMax, 0, 0}), s).hit);
  // A segment that ends before the sphere: a miss; one that reaches it: the hit.
  QRay seg = rayFrom({mid - 2 * r, mid, mid}, {kDirMax, 0, 0});
  seg.tMax = uint64_t(r - 1) << kSegFracBits;
  EXPECT_FALSE(intersectSphere(seg, s).hit);
  seg.tMax = uint64_t(r) << kSegFracBits;
  got = intersectSphere(seg, s);
  ASSERT_TRUE(got.hit);
  EXPECT_EQ(got.uNum, 0u);
  EXPECT_EQ(got.tNum, u128(r) * u128(kDirMax) * u128(kDirMax));
}

// Secondary rays leave a sphere from one lattice unit off its surface: outwards
// they meet nothing of it; inwards they meet its far side, not the near one.
TEST(GoldenSphere, SecondaryRaysLeavingTheSurfaceDoNotHitItAgain) {
  const int64_t mid = kPosMax / 2;
  for (const int64_t r : {int64_t(2), int64_t(50), kPosMax / 3}) {
    const QSphere s{2, {mid, mid, mid}, r};
    EXPECT_FALSE(intersectSphere(rayFrom({mid + r + 1, mid, mid}, {kDirMax, kDirMax / 3, 0}), s).hit) << r;
    EXPECT_FALSE(intersectSphere(rayFrom({mid, mid - r - 1, mid}, {kDirMax / 5, -kDirMax, kDirMax / 7}), s).hit) << r;
    const IsectResult in = intersectSphere(rayFrom({mid + r - 1, mid, mid}, {-kDirMax, 0, 0}), s);
    ASSERT_TRUE(in.hit) << r;
    EXPECT_EQ(in.uNum, 1u) << "the far side";
    EXPECT_EQ(in.tNum, u128(2 * r - 1) * u128(kDirMax) * u128(kDirMax)) << r;
  }
}

TEST(GoldenSphere, TinyAndHugeRadiiAndTheSceneBox) {
  // Radius 1 at a lattice corner, and a sphere filling the lattice cube.
  const QSphere tiny{5, {0, 0, 0}, 1};
  const IsectResult t = intersectSphere(rayFrom({0, 0, 40}, {0, 0, -kDirMax}), tiny);
  ASSERT_TRUE(t.hit);
  EXPECT_EQ(t.tNum, u128(39) * u128(kDirMax) * u128(kDirMax));
  const int64_t half = kPosMax / 2;
  const QSphere huge{6, {half, half, half}, half};
  const IsectResult h = intersectSphere(rayFrom({0, half, half}, {kDirMax, 0, 0}), huge);
  ASSERT_TRUE(h.hit) << "touching the scene box: the ray starts on the sphere and leaves through it";
  const IsectResult corner = intersectSphere(rayFrom({0, 0, 0}, {kDirMax, kDirMax, kDirMax}), huge);
  ASSERT_TRUE(corner.hit);
  EXPECT_EQ(corner.uNum, 0u);
}

// A sphere and a triangle on the same ray order by closerResult.
TEST(GoldenSphere, OrdersWithTrianglesByTheSameScale) {
  const int64_t mid = kPosMax / 2;
  const QRay ray = rayFrom({100, mid, mid}, {kDirMax, 0, 0});
  const QSphere s{9, {1100, mid, mid}, 500};  // entered at x = 600: displacement 500
  QTriangle tri;
  tri.id = 10;
  tri.v = {{{700, mid - 50, mid - 50}, {700, mid + 50, mid - 50}, {700, mid, mid + 80}}};  // x = 700: displacement 600
  const IsectResult a = intersectSphere(ray, s), b = intersect(ray, tri);
  ASSERT_TRUE(a.hit && b.hit);
  EXPECT_TRUE(closerResult(a, b));
  EXPECT_FALSE(closerResult(b, a));
}

}  // namespace
}  // namespace lancer::fx
