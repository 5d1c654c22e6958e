#include <gtest/gtest.h>

#include <random>

#include "golden/isect.h"
#include "golden/records.h"

namespace lancer::fx {
namespace {

QRay rayAlongZ(int64_t x, int64_t y) {
  return QRay{7, {x, y, 0}, {0, 0, kDirMax}};
}

QTriangle triangle(uint32_t id, std::array<int64_t, 3> a, std::array<int64_t, 3> b,
                   std::array<int64_t, 3> c) {
  return QTriangle{id, {a, b, c}};
}

TEST(GoldenIsect, HitsAndReportsExactFractions) {
  const int64_t z = kPosMax / 2;
  const auto tri = triangle(3, {0, 0, z}, {kPosMax / 4, 0, z}, {0, kPosMax / 4, z});
  const QRay ray = rayAlongZ(kPosMax / 16, kPosMax / 16);
  const IsectResult res = intersect(ray, tri);
  ASSERT_TRUE(res.hit);
  EXPECT_EQ(res.rayId, 7u);
  EXPECT_EQ(res.primId, 3u);
  // The ray travels z/kDirMax parameter units to reach the plane.
  EXPECT_NEAR(tOf(res, ray), double(z) / double(kDirMax), 1e-12);
  // (kPosMax/16) / (kPosMax/4) is 1/4 up to the integer divisions.
  EXPECT_NEAR(uOf(res), 0.25, 8.0 / double(kPosMax));
  EXPECT_NEAR(vOf(res), 0.25, 8.0 / double(kPosMax));
}

TEST(GoldenIsect, MissesAreAllZero) {
  const auto tri = triangle(1, {0, 0, 10}, {10, 0, 10}, {0, 10, 10});
  const IsectResult res = intersect(rayAlongZ(20, 20), tri);
  EXPECT_FALSE(res.hit);
  EXPECT_EQ(res.tNum, 0u);
  EXPECT_EQ(res.det, 0u);
  EXPECT_EQ(res.uNum, 0u);
  EXPECT_EQ(res.vNum, 0u);
}

TEST(GoldenIsect, BehindOriginParallelAndDegenerateMiss) {
  const auto behind = triangle(1, {0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  EXPECT_FALSE(intersect(QRay{0, {2, 2, 5}, {0, 0, kDirMax}}, behind).hit);
  const auto inPlane = triangle(2, {0, 0, 5}, {10, 0, 5}, {0, 10, 5});
  EXPECT_FALSE(intersect(QRay{0, {0, 2, 5}, {kDirMax, 0, 0}}, inPlane).hit);
  const auto degenerate = triangle(3, {0, 0, 9}, {5, 5, 9}, {10, 10, 9});
  EXPECT_FALSE(intersect(rayAlongZ(5, 5), degenerate).hit);
}

TEST(GoldenIsect, SharedEdgeAndVertexNeverLeak) {
  // A closed square of two triangles sharing the diagonal; rays along its
  // diagonal and through its corners must hit at least one of them.
  const int64_t z = 100;
  const auto lower = triangle(0, {0, 0, z}, {1000, 0, z}, {1000, 1000, z});
  const auto upper = triangle(1, {0, 0, z}, {1000, 1000, z}, {0, 1000, z});
  for (int64_t s = 0; s <= 1000; s += 7) {
    const QRay ray = rayAlongZ(s, s);
    EXPECT_TRUE(intersect(ray, lower).hit || intersect(ray, upper).hit) << s;
  }
  // Tilted rays through points of the shared diagonal: the origin is the point
  // minus one direction vector, so the ray passes the diagonal exactly at t = 1.
  const int64_t lo = kPosMax / 4, hi = 3 * kPosMax / 4, zc = 3 * kPosMax / 4;
  if (kDirMax > zc) GTEST_SKIP() << "direction format wider than the lattice";
  const auto lowerBig = triangle(0, {lo, lo, zc}, {hi, lo, zc}, {hi, hi, zc});
  const auto upperBig = triangle(1, {lo, lo, zc}, {hi, hi, zc}, {lo, hi, zc});
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int64_t> lateral(-kDirMax / 8, kDirMax / 8);
  std::uniform_int_distribution<int64_t> along(lo, hi);
  for (int i = 0; i < 2000; ++i) {
    const std::array<int64_t, 3> d{lateral(rng), lateral(rng), kDirMax};
    const int64_t s = along(rng);
    const QRay ray{uint32_t(i), {s - d[0], s - d[1], zc - d[2]}, d};
    const IsectResult a = intersect(ray, lowerBig), b = intersect(ray, upperBig);
    ASSERT_TRUE(a.hit || b.hit) << "ray " << i << " leaked through the shared edge at " << s;
    if (a.hit) {
      EXPECT_EQ(a.tNum, a.det * u128(kDirMax)) << "t must be exactly 1";
    }
  }
}

TEST(GoldenIsect, CloserResultUsesExactCrossMultiplicationAndPrimTies) {
  IsectResult a{0, 5, true, 10, 3, 0, 0};  // t = 10/3
  IsectResult b{0, 2, true, 20, 6, 0, 0};  // t = 20/6, the same value
  EXPECT_TRUE(closerResult(b, a));          // tie: lower prim id wins
  EXPECT_FALSE(closerResult(a, b));
  IsectResult c{0, 9, true, 33, 10, 0, 0};  // 3.3 < 3.333
  EXPECT_TRUE(closerResult(c, a));
  // Values near the top of the formats must not overflow the comparison.
  const u128 big = (u128(1) << (kTNumBits - 1)) + 12345;
  IsectResult d{0, 1, true, big, (u128(1) << (kDetAbsBits - 1)) + 1, 0, 0};
  IsectResult e{0, 2, true, big + 1, (u128(1) << (kDetAbsBits - 1)) + 1, 0, 0};
  EXPECT_TRUE(closerResult(d, e));
  EXPECT_FALSE(closerResult(e, d));
}

TEST(Records, WireRoundTripAtExtremes) {
  const QRay ray{0xdeadbeef, {0, kPosMax, 12345 % (kPosMax + 1)}, {-kDirMax, kDirMax, -1}};
  EXPECT_EQ(unpackRay(packWire(ray)), ray);
  const QTriangle tri{42, {{{kPosMax, 0, 1}, {2, kPosMax, 3}, {kPosMax, kPosMax, kPosMax}}}};
  EXPECT_EQ(unpackTriangle(packWire(tri)), tri);
  const IsectResult res{1, 2, true, (u128(1) << kTNumBits) - 1, (u128(1) << kDetAbsBits) - 1, 5,
                        (u128(1) << kBaryBits) - 1};
  EXPECT_EQ(unpackResult(packWire(res)), res);
  EXPECT_EQ(packWire(res).size(), size_t(wireWords(kIsectResBits)));
  // The first field is the most significant: the ray id sits at the top bits.
  const Wire wire = packWire(QRay{1, {}, {}});
  const int top = kIsectRayBits - kRayIdBits;
  EXPECT_EQ((wire[size_t(top / 32)] >> (top % 32)) & 1u, 1u);
}

// The allocation-free forms write the same images as the vector forms, overwrite
// stale words of a reused buffer, leave words past the image alone, and refuse
// a span that is too short.
TEST(Records, SpanFormsMatchVectorFormsAndReuseBuffers) {
  std::mt19937_64 rng(11);
  auto pos = [&] { return int64_t(rng() % uint64_t(kPosMax + 1)); };
  auto dir = [&] { return int64_t(rng() % uint64_t(2 * kDirMax + 1)) - kDirMax; };
  auto wide = [&](int bits) { return ((u128(rng()) << 64) | rng()) & ((u128(1) << bits) - 1); };
  std::array<uint32_t, kIsectResWords + 1> buffer;
  buffer.fill(0xffffffffu);  // stale bits everywhere, and a guard word past the image
  for (int i = 0; i < 200; ++i) {
    const QRay ray{uint32_t(rng()), {pos(), pos(), pos()}, {dir(), dir(), dir()}};
    const QTriangle tri{uint32_t(rng()), {{{pos(), pos(), pos()}, {pos(), pos(), pos()}, {pos(), pos(), pos()}}}};
    const IsectResult res{uint32_t(rng()), uint32_t(rng()), (rng() & 1) != 0, wide(kTNumBits),
                          wide(kDetAbsBits),  wide(kBaryBits),  wide(kBaryBits)};

    packWire(ray, std::span<uint32_t>(buffer));
    EXPECT_TRUE(std::equal(buffer.begin(), buffer.begin() + kIsectRayWords, packWire(ray).begin()));
    QRay rayBack;
    unpackRay(std::span<const uint32_t>(buffer), rayBack);
    EXPECT_EQ(rayBack, ray);

    packWire(tri, std::span<uint32_t>(buffer));
    EXPECT_TRUE(std::equal(buffer.begin(), buffer.begin() + kIsectTriWords, packWire(tri).begin()));
    QTriangle triBack;
    unpackTriangle(std::span<const uint32_t>(buffer), triBack);
    EXPECT_EQ(triBack, tri);

    ResWire resWire;
    resWire.fill(0xffffffffu);
    packWire(res, resWire);
    EXPECT_TRUE(std::equal(resWire.begin(), resWire.end(), packWire(res).begin()));
    IsectResult resBack{1, 1, true, 1, 1, 1, 1};
    unpackResult(resWire, resBack);
    EXPECT_EQ(resBack, res);
    EXPECT_EQ(unpackResult(resWire), res);

    const auto values = fieldArray(ray);
    EXPECT_EQ(std::vector<u128>(values.begin(), values.end()), fieldValues(ray));
    std::array<u128, kIsectTriValues> triValues;
    unpackFields(kIsectTriFields, packWire(tri), triValues);
    EXPECT_EQ(std::vector<u128>(triValues.begin(), triValues.end()), fieldValues(tri));
  }
  EXPECT_EQ(buffer.back(), 0xffffffffu) << "a word past the image was written";
  std::array<uint32_t, kIsectRayWords - 1> shortWire{};
  EXPECT_THROW(packWire(QRay{}, std::span<uint32_t>(shortWire)), std::logic_error);
  QRay ray;
  EXPECT_THROW(unpackRay(std::span<const uint32_t>(shortWire), ray), std::logic_error);
  static_assert(kIsectRayValues == 9 && kIsectTriValues == 10 && kIsectResValues == 7);
  static_assert(std::tuple_size_v<RayWire> == size_t(wireWords(kIsectRayBits)));
}

}  // namespace
}  // namespace lancer::fx
