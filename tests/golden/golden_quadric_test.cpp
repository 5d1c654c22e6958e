// The golden quadric tests (golden/quadric.h): the integer square root; every
// answer against exact arithmetic on random spheres and cones and rays (the
// line meets the quadric exactly when it should; the root taken, its side and
// its error within the documented bound; for cones also the error against the
// scene's cone); and the hard cases: tangent rays, rays from inside, quadrics
// behind the ray, segment ends, tiny and huge radii, secondary rays leaving the
// surface outwards and inwards, and for cones the rims, the open ends, rays
// along a cylinder's axis and pointed cones.

#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cstdio>
#include <optional>
#include <random>
#include <stdexcept>

#include "golden/isect.h"
#include "golden/quadric.h"
#include "support/lattice_rays.h"

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

// ---- Exact arithmetic ----------------------------------------------------------

using Z = mpz_class;
using Rational = mpq_class;

Z toZ(u128 v) {
  Z r((unsigned long)uint64_t(v >> 64));
  r <<= 64;
  return r + Z((unsigned long)uint64_t(v));
}

// sign(u + v sqrt(disc)), disc >= 0, without a square root.
int signWithRoot(const Z& u, const Z& v, const Z& disc) {
  const int su = sgn(u), sv = disc == 0 ? 0 : sgn(v);
  if (su >= 0 && sv >= 0) return su > 0 || sv > 0 ? 1 : 0;
  if (su <= 0 && sv <= 0) return -1;
  const int c = cmp(Z(u * u), Z(v * v * disc));
  return c == 0 ? 0 : c > 0 ? su : sv;
}

// A root (alpha + beta sqrt(disc)) / gamma: exact (beta = +-1) or as the
// pipeline rounds it (beta = 0: num / den).
struct RootForm {
  Z alpha, beta, gamma;
};

Rational valueOf(const RootForm& r) {
  Rational v(r.alpha, r.gamma);
  v.canonicalize();
  return v;
}

// The record's quadric along the ray, in exact integers (the pipeline's
// formulas, without its widths), and the exact root choice.
struct QuadricExact {
  const QRay& ray;
  const QQuadric& rec;
  Z a, b, c, disc, originHeight, dirHeight, dz;
  std::array<Z, 3> q, d;
  QuadricExact(const QRay& r, const QQuadric& cone) : ray(r), rec(cone) {
    for (size_t k = 0; k < 3; ++k) {
      q[k] = 2 * Z(long(ray.org[k])) - Z(long(rec.axisSum[k]));
      d[k] = Z(long(ray.dir[k]));
      originHeight += q[k] * Z(long(rec.axis[k]));
      dirHeight += d[k] * Z(long(rec.axis[k]));
    }
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const Z qij(long(rec.quadAt(i, j)));
        a += d[size_t(i)] * qij * d[size_t(j)];
        b += d[size_t(i)] * qij * q[size_t(j)];
        c += q[size_t(i)] * qij * q[size_t(j)];
      }
      b += Z(long(rec.lin[size_t(i)])) * d[size_t(i)];
      c += 2 * Z(long(rec.lin[size_t(i)])) * q[size_t(i)];
    }
    c += Z(long(rec.constant));
    disc = b * b - a * c;
    dz = abs(Z(long(ray.dir[size_t(dominantAxis(ray.dir))])));
  }
  int signB() const { return b < 0 ? -1 : 1; }
  // sign(p + q x) at the root x.
  int signAt(const Z& p, const Z& qq, const RootForm& r) const {
    return signWithRoot(p * r.gamma + qq * r.alpha, qq * r.beta, disc) * sgn(r.gamma);
  }
  bool accepted(const RootForm& r) const {
    const Z w(long(rec.axisLen2));
    return signAt(0, 1, r) > 0 && signAt(w - originHeight, -2 * dirHeight, r) >= 0 &&
           signAt(w + originHeight, 2 * dirHeight, r) >= 0 &&
           signAt(toZ(u128(ray.tMax)), -dz * (1 << kSegFracBits), r) >= 0;
  }
  // The exact roots: first where 2A x + B = -sgn(B) sqrt(disc), second its conjugate.
  std::optional<RootForm> exactFirst() const {
    if (a == 0) return std::nullopt;
    return RootForm{-b, Z(-signB()), 2 * a};
  }
  std::optional<RootForm> exactSecond() const {
    if (a != 0) return RootForm{-b, Z(signB()), 2 * a};
    if (b != 0) return RootForm{-c, 0, 4 * b};
    return std::nullopt;
  }
  // The pipeline's roots with sqrt(disc) taken as `s`.
  Z big(const Z& s) const { return b < 0 ? Z(-b + s) : Z(-b - s); }
  std::optional<RootForm> roundedFirst(const Z& s) const {
    if (a == 0) return std::nullopt;
    return RootForm{big(s), 0, 2 * a};
  }
  std::optional<RootForm> roundedSecond(const Z& s) const {
    if (big(s) == 0) return std::nullopt;
    return RootForm{c, 0, 2 * big(s)};
  }
  // 0: no hit, 1: the first root, 2: the second; the nearer of two accepted.
  int choice(const std::optional<RootForm>& first, const std::optional<RootForm>& second, bool exact) const {
    const bool f = first && accepted(*first), s = second && accepted(*second);
    if (f && s) {
      bool secondNearer;
      if (exact) {
        secondNearer = disc > 0 && signB() * sgn(a) < 0;  // first - second = -sgn(B) sqrt(disc) / A
      } else {
        secondNearer = valueOf(*second) < valueOf(*first);
      }
      return secondNearer ? 2 : 1;
    }
    return f ? 1 : s ? 2 : 0;
  }
};


// The exact quadric of the lattice cone at a point x: 4 W^2 (radial^2 - radius^2).
Rational sceneQuadric(const LatticeCone& cone, const std::array<Rational, 3>& x) {
  std::array<Rational, 3> qc, w;
  Rational len2 = 0, height = 0, len = 0;
  for (size_t k = 0; k < 3; ++k) {
    w[k] = Rational(long(cone.apex[k] - cone.base[k]));
    qc[k] = 2 * x[k] - Rational(long(cone.apex[k] + cone.base[k]));
    len2 += w[k] * w[k];
    height += qc[k] * w[k];
  }
  Rational q2 = 0;
  for (size_t k = 0; k < 3; ++k) q2 += qc[k] * qc[k];
  const Rational radius = Rational(long(cone.baseRadius + cone.apexRadius)) * len2 +
                          Rational(long(cone.apexRadius - cone.baseRadius)) * height;
  return len2 * len2 * q2 - len2 * height * height - radius * radius;
}

Rational recordQuadric(const QQuadric& rec, const std::array<Rational, 3>& x) {
  std::array<Rational, 3> q;
  for (size_t k = 0; k < 3; ++k) q[k] = 2 * x[k] - Rational(long(rec.axisSum[k]));
  Rational f = Rational(long(rec.constant));
  for (int i = 0; i < 3; ++i) {
    f += 2 * Rational(long(rec.lin[size_t(i)])) * q[size_t(i)];
    for (int j = 0; j < 3; ++j) f += q[size_t(i)] * Rational(long(rec.quadAt(i, j))) * q[size_t(j)];
  }
  return f;
}

// t_num / det == units exactly.
bool atDisplacement(const IsectResult& r, int64_t units) { return r.tNum == u128(units) * r.det; }

struct ExactCounts {
  int hits = 0, inside = 0, boundary = 0, linear = 0;
};

// The pipeline's answer for one ray and record against exact arithmetic: bit
// for bit the rounded choice of QuadricExact; the exact choice unless a root's
// verdict changes between the square root's floor and the next integer; the
// root bracketed within 1 / |big|. `value`: the hit's lambda, as the pipeline
// rounds it.
void checkAgainstExact(const QRay& ray, const QQuadric& rec, const IsectResult& got, ExactCounts& counts,
                       Rational& value) {
  const QuadricExact e(ray, rec);
  if (e.disc < 0) {
    ASSERT_FALSE(got.hit);
    return;
  }
  if (e.a == 0) ++counts.linear;
  const Z s = sqrt(e.disc), s1 = s + 1;
  const auto first = e.roundedFirst(s), second = e.roundedSecond(s);
  const int pick = e.choice(first, second, false);
  ASSERT_EQ(got.hit, pick != 0);
  if (pick != 0) {
    RootForm r = pick == 1 ? *first : *second;
    if (r.gamma < 0) r = {-r.alpha, 0, -r.gamma};
    ASSERT_EQ(toZ(got.tNum), r.alpha * e.dz);
    ASSERT_EQ(toZ(got.det), r.gamma);
    ASSERT_EQ(got.uNum, (pick == 1 ? e.b < 0 : e.b >= 0) && e.disc > 0 ? 1u : 0u);
  }
  const int exactPick = e.choice(e.exactFirst(), e.exactSecond(), true);
  if (exactPick != pick) {
    const bool straddles = e.choice(e.roundedFirst(s1), e.roundedSecond(s1), false) != pick || s <= 1;
    ASSERT_TRUE(straddles) << "the exact and the rounded choices differ away from a boundary";
    ++counts.boundary;
  }
  if (pick == 0) return;
  ++counts.hits;
  if (got.uNum == 1) ++counts.inside;
  // The exact root lies between the roots at s and s + 1, which differ by
  // less than 1 / |big| of the root.
  const RootForm lo = pick == 1 ? *first : *second;
  const auto hiRoot = pick == 1 ? e.roundedFirst(s1) : e.roundedSecond(s1);
  const auto exact = pick == 1 ? e.exactFirst() : e.exactSecond();
  ASSERT_TRUE(hiRoot && exact);
  value = valueOf(lo);
  const Rational vHi = valueOf(*hiRoot);
  ASSERT_LE(e.signAt(-lo.alpha, lo.gamma, *exact) * e.signAt(-hiRoot->alpha, hiRoot->gamma, *exact), 0);
  ASSERT_LE(abs(vHi - value) * abs(e.big(s)), abs(value));
}

TEST(GoldenSphere, EveryAnswerAgreesWithExactArithmetic) {
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  ExactCounts counts;
  int bounded = 0;
  for (uint32_t i = 0; i < 40000; ++i) {
    const QSphere s{i, {pos(rng), pos(rng), pos(rng)}, 1 + int64_t(rng() % uint64_t(kPosMax / (1 + rng() % 64)))};
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
    const QQuadric rec = sphereRecord(s);
    const IsectResult got = intersectQuadric(ray, rec);
    Rational value;
    checkAgainstExact(ray, rec, got, counts, value);
    ASSERT_FALSE(HasFatalFailure()) << "sphere " << i;
    if (!got.hit) continue;
    // The record is the sphere exactly (C = 4(|o - c|^2 - r^2)): the ray
    // leaves it exactly when it starts inside.
    const Z c = QuadricExact(ray, rec).c;
    if (c != 0) {
      ASSERT_EQ(got.uNum == 1, c < 0) << i;
    }
  }
  EXPECT_GT(counts.hits, 5000);
  EXPECT_GT(counts.inside, 100);
  EXPECT_GT(bounded, 1000);
  EXPECT_LT(counts.boundary, 30);
}

TEST(GoldenSphere, TangentRaysTouchAtOnePoint) {
  const int64_t mid = kPosMax / 2;
  for (const int64_t r : {int64_t(1), int64_t(7), kPosMax / 4}) {
    const QSphere s{3, {mid, mid, mid}, r};
    // Along x at distance exactly r from the center: disc = 0, one root.
    const QRay ray = rayFrom({mid - r - 100, mid + r, mid}, {kDirMax, 0, 0});
    const IsectResult got = intersectQuadric(ray, sphereRecord(s));
    ASSERT_TRUE(got.hit) << r;
    EXPECT_EQ(got.uNum, 0u);
    // Displacement along x: exactly r + 100 (t_num / det).
    EXPECT_TRUE(atDisplacement(got, r + 100));
    // One unit further out: a miss.
    EXPECT_FALSE(intersectQuadric(rayFrom({mid - r - 100, mid + r + 1, mid}, {kDirMax, 0, 0}), sphereRecord(s)).hit);
  }
}

TEST(GoldenSphere, FromInsideBehindAndAlongTheSegment) {
  const int64_t mid = kPosMax / 2, r = 1000;
  const QSphere s{1, {mid, mid, mid}, r};
  // From the center: the leaving root, r ahead.
  IsectResult got = intersectQuadric(rayFrom({mid, mid, mid}, {0, -kDirMax, 0}), sphereRecord(s));
  ASSERT_TRUE(got.hit);
  EXPECT_EQ(got.uNum, 1u);
  EXPECT_TRUE(atDisplacement(got, r));
  // The sphere behind the ray: a miss.
  EXPECT_FALSE(intersectQuadric(rayFrom({mid + 2 * r, mid, mid}, {kDirMax, 0, 0}), sphereRecord(s)).hit);
  // A segment that ends before the sphere: a miss; one that reaches it: the hit.
  QRay seg = rayFrom({mid - 2 * r, mid, mid}, {kDirMax, 0, 0});
  seg.tMax = uint64_t(r - 1) << kSegFracBits;
  EXPECT_FALSE(intersectQuadric(seg, sphereRecord(s)).hit);
  seg.tMax = uint64_t(r) << kSegFracBits;
  got = intersectQuadric(seg, sphereRecord(s));
  ASSERT_TRUE(got.hit);
  EXPECT_EQ(got.uNum, 0u);
  EXPECT_TRUE(atDisplacement(got, r));
}

// Secondary rays leave a sphere from one lattice unit off its surface: outwards
// they meet nothing of it; inwards they meet its far side, not the near one.
TEST(GoldenSphere, SecondaryRaysLeavingTheSurfaceDoNotHitItAgain) {
  const int64_t mid = kPosMax / 2;
  for (const int64_t r : {int64_t(2), int64_t(50), kPosMax / 3}) {
    const QSphere s{2, {mid, mid, mid}, r};
    EXPECT_FALSE(intersectQuadric(rayFrom({mid + r + 1, mid, mid}, {kDirMax, kDirMax / 3, 0}), sphereRecord(s)).hit) << r;
    EXPECT_FALSE(intersectQuadric(rayFrom({mid, mid - r - 1, mid}, {kDirMax / 5, -kDirMax, kDirMax / 7}), sphereRecord(s)).hit) << r;
    const IsectResult in = intersectQuadric(rayFrom({mid + r - 1, mid, mid}, {-kDirMax, 0, 0}), sphereRecord(s));
    ASSERT_TRUE(in.hit) << r;
    EXPECT_EQ(in.uNum, 1u) << "the far side";
    EXPECT_TRUE(atDisplacement(in, 2 * r - 1)) << r;
  }
}

TEST(GoldenSphere, TinyAndHugeRadiiAndTheSceneBox) {
  // Radius 1 at a lattice corner, and a sphere filling the lattice cube.
  const QSphere tiny{5, {0, 0, 0}, 1};
  const IsectResult t = intersectQuadric(rayFrom({0, 0, 40}, {0, 0, -kDirMax}), sphereRecord(tiny));
  ASSERT_TRUE(t.hit);
  EXPECT_TRUE(atDisplacement(t, 39));
  const int64_t half = kPosMax / 2;
  const QSphere huge{6, {half, half, half}, half};
  const IsectResult h = intersectQuadric(rayFrom({0, half, half}, {kDirMax, 0, 0}), sphereRecord(huge));
  ASSERT_TRUE(h.hit) << "touching the scene box: the ray starts on the sphere and leaves through it";
  const IsectResult corner = intersectQuadric(rayFrom({0, 0, 0}, {kDirMax, kDirMax, kDirMax}), sphereRecord(huge));
  ASSERT_TRUE(corner.hit);
  EXPECT_EQ(corner.uNum, 0u);
}

// A sphere and a triangle on the same ray order by closerResult.
TEST(GoldenSphere, OrdersWithTrianglesByTheSameScale) {
  // At every width (N = 2^P): the ray from x = N/16, the sphere entered at
  // x = 3N/8 (displacement 5N/16), the triangle at x = 7N/16 (6N/16).
  const int64_t n = kPosMax + 1, mid = n / 2, e = n / 32;
  const QRay ray = rayFrom({n / 16, mid, mid}, {kDirMax, 0, 0});
  const QSphere s{9, {n / 2, mid, mid}, n / 8};
  QTriangle tri;
  tri.id = 10;
  tri.v = {{{7 * n / 16, mid - e, mid - e}, {7 * n / 16, mid + e, mid - e}, {7 * n / 16, mid, mid + e}}};
  const IsectResult a = intersectQuadric(ray, sphereRecord(s)), b = intersect(ray, tri);
  ASSERT_TRUE(a.hit && b.hit);
  EXPECT_TRUE(closerResult(a, b));
  EXPECT_FALSE(closerResult(b, a));
}

// A cone's constant is a product of up to 6P + 6 bits (150 at 24/24), scaled
// back below 2^63: the 256-bit product rounds as GMP's exact quotient does.
TEST(GoldenCone, ConstantsBeyond128BitsRoundExactly) {
  std::mt19937_64 rng(7);
  const auto toMpz = [](u128 v) -> mpz_class {
    mpz_class z(uint64_t(v >> 64));
    z <<= 64;
    return z + mpz_class(uint64_t(v));
  };
  for (int n = 0; n < 20000; ++n) {
    const int aBits = 1 + int(rng() % 60), bBits = 1 + int(rng() % 110);
    const u128 a = (u128(rng()) | u128(rng()) << 64) >> (128 - aBits);
    const u128 b = (u128(rng()) | u128(rng()) << 64) >> (128 - bBits);
    const mpz_class product = toMpz(a) * toMpz(b);
    // Every scale that leaves a quotient of at most 127 bits, and ties.
    const int least = std::max(0, int(mpz_sizeinbase(product.get_mpz_t(), 2)) - 127);
    for (const int e : {least, least + 1, least + int(rng() % 40)}) {
      mpz_class want = product;
      if (e > 0) {
        want += mpz_class(1) << (e - 1);
        want >>= e;
      }
      ASSERT_EQ(toMpz(roundShiftProduct(a, b, e)), want) << "a bits " << aBits << ", b bits " << bBits << ", e " << e;
    }
  }
  // A tie rounds away from zero: 3 / 2 -> 2, and 2^130 + 2^129 halves exactly.
  EXPECT_EQ(roundShiftProduct(3, 1, 1), u128(2));
  EXPECT_EQ(roundShiftProduct(u128(3) << 64, u128(1) << 65, 129), u128(3));
}

TEST(GoldenCone, RefusesWhatIsNoCone) {
  EXPECT_THROW(coneRecord(1, {{10, 10, 10}, {10, 10, 90}, 0, 0}), std::invalid_argument);
  EXPECT_THROW(coneRecord(1, {{10, 10, 10}, {10, 10, 10}, 5, 3}), std::invalid_argument);
  EXPECT_THROW(coneRecord(1, {{10, 10, 10}, {10, 10, 90}, -1, 3}), std::invalid_argument);
  EXPECT_THROW(coneRecord(1, {{10, 10, kPosMax + 1}, {10, 10, 90}, 1, 3}), std::invalid_argument);
  EXPECT_NO_THROW(coneRecord(1, {{10, 10, 10}, {10, 10, 90}, 5, 0}));  // pointed
  EXPECT_NO_THROW(coneRecord(1, {{10, 10, 10}, {10, 10, 90}, 0, 5}));
  // A small cone's quadric is the scene's exactly (no scale, no rounding).
  const QQuadric small = coneRecord(1, {{10, 10, 10}, {11, 10, 12}, 2, 1});
  EXPECT_EQ(small.scaleExp, 0);
  EXPECT_EQ(small.quadAt(0, 0), 25 - 6);  // W^2 - (W + dr^2) w_x^2, W = 5
}

// Random cones and rays, half aimed at the cone: every answer is the record's
// quadric's, computed again without widths (no overflow anywhere); it agrees
// with the exact root choice but where the floor of the square root moves a
// root across a boundary; the root is bracketed by the square root's floor and
// ceiling, within the relative bound 1 / |big|; and the hit lies on the scene's
// cone within the bound of the record's rounding.
TEST(GoldenCone, EveryAnswerAgreesWithExactArithmetic) {
  std::mt19937_64 rng(40);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  ExactCounts counts;
  int rounded = 0;
  Rational worstRadius2 = 0;
  for (uint32_t i = 0; i < 30000; ++i) {
    LatticeCone cone;
    cone.base = {pos(rng), pos(rng), pos(rng)};
    const int64_t len = 1 + int64_t(rng() % uint64_t(kPosMax >> (rng() % 10)));
    for (size_t k = 0; k < 3; ++k) cone.apex[k] = std::clamp<int64_t>(cone.base[k] + dir(rng) * len / kDirMax, 0, kPosMax);
    if (cone.apex == cone.base) cone.apex[0] = cone.base[0] == 0 ? 1 : cone.base[0] - 1;
    cone.baseRadius = int64_t(rng() % uint64_t(1 + (kPosMax >> (2 + rng() % 12))));
    cone.apexRadius = i % 4 == 0 ? cone.baseRadius : i % 4 == 1 ? 0 : int64_t(rng() % uint64_t(1 + (kPosMax >> (2 + rng() % 12))));
    if (cone.baseRadius == 0 && cone.apexRadius == 0) cone.baseRadius = 1;
    const QQuadric rec = coneRecord(i, cone);
    if (rec.scaleExp > 0) ++rounded;

    QRay ray = rayFrom({pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)});
    ray.dir[size_t(rng() % 3)] = rng() % 2 ? kDirMax : -kDirMax;
    if (i % 2) {
      // Toward a point near the cone's surface between its planes.
      const double f = double(rng() % 1001) / 1000, r = double(cone.baseRadius) + f * double(cone.apexRadius - cone.baseRadius);
      std::array<int64_t, 3> target{};
      for (size_t k = 0; k < 3; ++k)
        target[k] = cone.base[k] + int64_t(f * double(cone.apex[k] - cone.base[k]) + (double(rng() % 2001) / 1000 - 1) * r);
      ray.dir = test::latticeDirectionTo(ray.org, target);
    }
    if (i % 5 == 0) ray.tMax = rng() % (kSegEndNone / 2);
    ray.id = i;

    const IsectResult got = intersectQuadric(ray, rec);
    Rational v;
    checkAgainstExact(ray, rec, got, counts, v);
    ASSERT_FALSE(HasFatalFailure()) << "cone " << i;
    if (!got.hit) continue;
    // The hit on the scene's cone: |F_scene - 2^e F_record| <= 2^e (sum |q_i| + 1)^2 / 2.
    std::array<Rational, 3> x;
    Rational qSum = 0;
    for (size_t k = 0; k < 3; ++k) {
      x[k] = Rational(long(ray.org[k])) + v * Rational(long(ray.dir[k]));
      qSum += abs(2 * x[k] - Rational(long(rec.axisSum[k])));
    }
    const Rational scale = Rational(Z(1) << rec.scaleExp);
    const Rational scene = sceneQuadric(cone, x), record = recordQuadric(rec, x);
    ASSERT_LE(abs(scene - scale * record), scale * (qSum + 1) * (qSum + 1) / 2) << i;
    // The closed form of docs/quadrics.md: 2^e <= 2 W max(W, dr^2) / 2^K.
    const Z len2(long(rec.axisLen2)), slope2(long((cone.apexRadius - cone.baseRadius) * (cone.apexRadius - cone.baseRadius)));
    if (rec.scaleExp > 0) {
      ASSERT_LE(Z(Z(1) << (rec.scaleExp + kQuadricK)), 2 * len2 * (len2 > slope2 ? len2 : slope2)) << i;
    }
    // radial^2 - radius^2 at the hit, lattice units^2, on cones no flatter than 45 degrees.
    if (slope2 <= len2) worstRadius2 = std::max(worstRadius2, Rational(abs(scene) / (4 * len2 * len2)));
  }
  EXPECT_GT(counts.hits, 5000);
  EXPECT_GT(counts.inside, 500);
  EXPECT_GT(rounded, 10000);
  EXPECT_LT(counts.boundary, 30);
  RecordProperty("worst_radius2_error", worstRadius2.get_d());
  std::printf("cone: %d hits, %d leaving, %d with A = 0, %d boundary cases, %d rounded records, worst |radial^2 - radius^2| %.3g (|r1 - r0| <= length)\n",
              counts.hits, counts.inside, counts.linear, counts.boundary, rounded, worstRadius2.get_d());
}

// Sizes that fit every lattice: N = 2^P.
constexpr int64_t kN = kPosMax + 1, kMid = kN / 2;
// A cylinder along x of power-of-two length and radius: its record is exact.
constexpr int64_t kLen = kN / 8, kX0 = kN / 4, kX1 = kX0 + kLen, kR = kN / 32;
const LatticeCone kCylinderX{{kX0, kMid, kMid}, {kX1, kMid, kMid}, kR, kR};

TEST(GoldenCone, RaysAlongACylindersAxisNeverCrossIt) {
  const QQuadric cyl = coneRecord(1, kCylinderX);
  ASSERT_GT(cyl.scaleExp, 0);
  EXPECT_EQ(cyl.quadAt(0, 0), 0) << "exact: no curvature along the axis";
  for (const int64_t dx : {kDirMax, -kDirMax}) {
    for (const int64_t x : {kX0 - 10, kX0 + kLen / 2, kX1 + 10}) {
      EXPECT_FALSE(intersectQuadric(rayFrom({x, kMid, kMid}, {dx, 0, 0}), cyl).hit) << "on the axis";
      EXPECT_FALSE(intersectQuadric(rayFrom({x, kMid + kR / 2, kMid}, {dx, 0, 0}), cyl).hit) << "inside";
      EXPECT_FALSE(intersectQuadric(rayFrom({x, kMid + kR, kMid}, {dx, 0, 0}), cyl).hit) << "in the surface";
      EXPECT_FALSE(intersectQuadric(rayFrom({x, kMid + 2 * kR, kMid}, {dx, 0, 0}), cyl).hit) << "outside";
    }
  }
}

TEST(GoldenCone, TangentRaysAndRims) {
  const QQuadric cyl = coneRecord(2, kCylinderX);
  // Tangent: along z at distance exactly r from the axis, one root.
  const IsectResult t = intersectQuadric(rayFrom({kX0 + kLen / 2, kMid + kR, kMid - 3 * kR}, {0, 0, kDirMax}), cyl);
  ASSERT_TRUE(t.hit);
  EXPECT_EQ(t.uNum, 0u);
  EXPECT_TRUE(atDisplacement(t, 3 * kR));
  EXPECT_FALSE(intersectQuadric(rayFrom({kX0 + kLen / 2, kMid + kR + 1, kMid - 3 * kR}, {0, 0, kDirMax}), cyl).hit);
  // Grazing the rims: in the end planes the circle counts, one unit beyond it does not.
  for (const int64_t x : {kX0, kX1}) {
    const IsectResult rim = intersectQuadric(rayFrom({x, kMid - 3 * kR, kMid}, {0, kDirMax, 0}), cyl);
    ASSERT_TRUE(rim.hit) << x;
    EXPECT_EQ(rim.uNum, 0u);
    EXPECT_TRUE(atDisplacement(rim, 2 * kR));
    // Tangent to the rim circle itself.
    EXPECT_TRUE(intersectQuadric(rayFrom({x, kMid + kR, kMid - 3 * kR}, {0, 0, kDirMax}), cyl).hit) << x;
  }
  EXPECT_FALSE(intersectQuadric(rayFrom({kX0 - 1, kMid - 3 * kR, kMid}, {0, kDirMax, 0}), cyl).hit);
  EXPECT_FALSE(intersectQuadric(rayFrom({kX1 + 1, kMid - 3 * kR, kMid}, {0, kDirMax, 0}), cyl).hit);
}

TEST(GoldenCone, ThroughTheOpenEndTheInsideIsHit) {
  const QQuadric cyl = coneRecord(3, kCylinderX);
  // From before the base, into the open end: the entering root lies before
  // the base plane (cut away); the leaving root, on the inside wall, is taken.
  const int64_t dy = kDirMax / 4;
  const IsectResult in = intersectQuadric(rayFrom({kX0 - kR, kMid, kMid}, {kDirMax, dy, 0}), cyl);
  ASSERT_TRUE(in.hit);
  EXPECT_EQ(in.uNum, 1u);
  EXPECT_EQ(in.tNum * u128(dy), u128(kR) * u128(kDirMax) * in.det) << "displacement r kDirMax / dy";
  // The same ray segment ending before the wall: a miss.
  QRay seg = rayFrom({kX0 - kR, kMid, kMid}, {kDirMax, dy, 0});
  seg.tMax = uint64_t(2 * kR) << kSegFracBits;
  EXPECT_FALSE(intersectQuadric(seg, cyl).hit);
  // Out through the other open end without touching the wall: a miss.
  EXPECT_FALSE(intersectQuadric(rayFrom({kX0 - 1, kMid, kMid}, {kDirMax, kDirMax / 64, 0}), cyl).hit);
}

// A cone along y, radii 3r/2 and r/2 (radius r at mid-height): exact record.
const LatticeCone kConeY{{kMid, kMid - kLen / 2, kMid}, {kMid, kMid + kLen / 2, kMid}, 3 * kR / 2, kR / 2};

TEST(GoldenCone, SecondaryRaysLeavingTheSurfaceDoNotHitItAgain) {
  for (const LatticeCone& shape : {kCylinderX, kConeY}) {
    const QQuadric rec = coneRecord(4, shape);
    const bool alongX = shape.apex[0] != shape.base[0];
    const std::array<int64_t, 3> middle{alongX ? kX0 + kLen / 2 : kMid, kMid, kMid};
    // Across the axis, one unit off the surface at radius r.
    const auto at = [&](int64_t offset) { return std::array<int64_t, 3>{middle[0], middle[1], middle[2] + offset}; };
    EXPECT_FALSE(intersectQuadric(rayFrom(at(kR + 1), {0, kDirMax / 3, kDirMax}), rec).hit) << "outwards";
    EXPECT_FALSE(intersectQuadric(rayFrom(at(kR + 1), {kDirMax / 5, -kDirMax / 7, kDirMax}), rec).hit) << "outwards";
    EXPECT_FALSE(intersectQuadric(rayFrom(at(-kR - 1), {0, 0, -kDirMax}), rec).hit) << "outwards";
    const IsectResult in = intersectQuadric(rayFrom(at(kR - 1), {0, 0, -kDirMax}), rec);
    ASSERT_TRUE(in.hit);
    EXPECT_EQ(in.uNum, 1u) << "the far side";
    EXPECT_TRUE(atDisplacement(in, 2 * kR - 1));
  }
}

TEST(GoldenCone, PointedTinyHugeAndTheSceneBox) {
  // A pointed cone along y: radius r at the base, 0 at the apex.
  const LatticeCone pointed{{kMid, kMid - kLen / 2, kMid}, {kMid, kMid + kLen / 2, kMid}, kR, 0};
  const QQuadric p = coneRecord(5, pointed);
  const IsectResult half = intersectQuadric(rayFrom({kMid - 2 * kR, kMid, kMid}, {kDirMax, 0, 0}), p);
  ASSERT_TRUE(half.hit);
  EXPECT_EQ(half.uNum, 0u);
  EXPECT_TRUE(atDisplacement(half, 2 * kR - kR / 2)) << "radius r/2 at mid-height";
  EXPECT_FALSE(intersectQuadric(rayFrom({kMid - 2 * kR, kMid + kLen / 2 + 1, kMid}, {kDirMax, 0, 0}), p).hit) << "above the apex";
  // A thin cylinder of radius 1 at the lattice's corner.
  const QQuadric tiny = coneRecord(6, {{1, 1, 0}, {1, 1, kLen}, 1, 1});
  const IsectResult t = intersectQuadric(rayFrom({10, 1, kLen / 2}, {-kDirMax, 0, 0}), tiny);
  ASSERT_TRUE(t.hit);
  EXPECT_TRUE(atDisplacement(t, 8));
  EXPECT_FALSE(intersectQuadric(rayFrom({10, 3, kLen / 2}, {-kDirMax, 0, 0}), tiny).hit);
  // A cylinder and a cone as wide as the lattice, touching the scene box.
  const int64_t half2 = kPosMax / 2;
  const QQuadric huge = coneRecord(7, {{0, half2, half2}, {kPosMax, half2, half2}, half2, half2});
  const IsectResult h = intersectQuadric(rayFrom({kPosMax / 3, 0, half2}, {0, kDirMax, 0}), huge);
  ASSERT_TRUE(h.hit) << "from the box's face, on the surface: it meets the far side";
  const IsectResult corner = intersectQuadric(rayFrom({0, 0, 0}, {kDirMax, kDirMax, kDirMax}), huge);
  ASSERT_TRUE(corner.hit);
  EXPECT_EQ(corner.uNum, 0u);
  const QQuadric wide = coneRecord(8, {{0, half2, half2}, {kPosMax, half2, half2}, half2, 0});
  const IsectResult w = intersectQuadric(rayFrom({1, half2, half2}, {0, kDirMax, 0}), wide);
  ASSERT_TRUE(w.hit);
  EXPECT_EQ(w.uNum, 1u) << "from the axis, the inside";
}

// A cone, a sphere and a triangle on the same ray order by closerResult.
TEST(GoldenCone, OrdersWithSpheresAndTrianglesByTheSameScale) {
  const int64_t mid = kPosMax / 2;
  const QRay ray = rayFrom({100, mid, mid}, {kDirMax, 0, 0});
  const QQuadric cone = coneRecord(11, {{300, mid, mid - 100}, {300, mid, mid + 100}, 50, 50});  // entered at x = 250: 150
  const QSphere s{9, {700, mid, mid}, 200};                                                     // entered at x = 500: 400
  QTriangle tri;
  tri.id = 10;
  tri.v = {{{800, mid - 50, mid - 50}, {800, mid + 50, mid - 50}, {800, mid, mid + 80}}};  // x = 800: 700
  const IsectResult c = intersectQuadric(ray, cone), a = intersectQuadric(ray, sphereRecord(s)), b = intersect(ray, tri);
  ASSERT_TRUE(c.hit && a.hit && b.hit);
  // Exact at 16/16; at narrower widths the record is rounded (K bits), the hit within a unit.
  EXPECT_NEAR(double(c.tNum) / double(c.det), 150.0, 1.0);
  EXPECT_TRUE(closerResult(c, a));
  EXPECT_TRUE(closerResult(a, b));
  EXPECT_TRUE(closerResult(c, b));
  EXPECT_FALSE(closerResult(b, c));
}

}  // namespace
}  // namespace lancer::fx
