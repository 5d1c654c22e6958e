#include "golden/quadric.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "golden/isect.h"

namespace lancer::fx {

u128 isqrt(u128 v) {
  // The largest power of four not above v, then one result bit a step.
  u128 bit = u128(1) << 126;
  while (bit > v) bit >>= 2;
  u128 root = 0;
  while (bit != 0) {
    if (v >= root + bit) {
      v -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

namespace {

// A root of a quadric along the ray: lambda = num / den (den > 0; den = 0: no
// such root), and whether the ray leaves the quadric's inside there.
struct Root {
  i128 num = 0;
  u128 den = 0;
  bool leaving = false;
  bool ahead() const { return den > 0 && num > 0; }
};

// No hit of the ray on the primitive.
IsectResult missOf(const QRay& ray, uint32_t primId) {
  IsectResult res;
  res.rayId = ray.id;
  res.primId = primId;
  return res;
}

// The test's last step: the nearer root if it is ahead of the origin and
// `onSurface` (between the planes) keeps its point, else the farther one if so; the hit
// on the triangles' scale (t_num = num |d_dom|, det = den: a displacement along
// the dominant axis) and within the segment (t_num 2^F <= t_max det).
template <class OnSurface>
IsectResult quadricHit(const QRay& ray, uint32_t primId, const Root& nearer, const Root& farther, OnSurface onSurface) {
  IsectResult res = missOf(ray, primId);
  const Root* chosen = nullptr;
  for (const Root* root : {&nearer, &farther}) {
    if (root->ahead() && onSurface(*root)) {
      chosen = root;
      break;
    }
  }
  if (chosen == nullptr) return res;
  const int64_t dz = ray.dir[size_t(dominantAxis(ray.dir))];
  const u128 tNum = u128(chosen->num) * u128(dz < 0 ? -dz : dz);
  if (mul256(u128(ray.tMax), chosen->den) < mul256(tNum, u128(1) << kSegFracBits)) return res;
  res.hit = true;
  res.tNum = tNum;
  res.det = chosen->den;
  res.uNum = chosen->leaving ? 1 : 0;
  res.vNum = 0;
  return res;
}

// num / den with den made positive.
Root rootOf(i128 num, i128 den, bool leaving) {
  return den < 0 ? Root{-num, u128(-den), leaving} : Root{num, u128(den), leaving};
}

int bitLength(u128 v) {
  int n = 0;
  for (; v != 0; v >>= 1) ++n;
  return n;
}

// v / 2^e rounded to nearest, ties away from zero.
i128 roundShift(i128 v, int e) {
  if (e == 0) return v;
  const u128 mag = (u128(v < 0 ? -v : v) + (u128(1) << (e - 1))) >> e;
  return v < 0 ? -i128(mag) : i128(mag);
}

}  // namespace

u128 roundShiftProduct(u128 a, u128 b, int e) {
  // The product in four 64-bit limbs, least significant first (schoolbook).
  std::array<uint64_t, 4> limbs{};
  const uint64_t x[2] = {uint64_t(a), uint64_t(a >> 64)}, y[2] = {uint64_t(b), uint64_t(b >> 64)};
  for (size_t i = 0; i < 2; ++i) {
    u128 carry = 0;
    for (size_t j = 0; j < 2; ++j) {
      const u128 t = u128(x[i]) * y[j] + limbs[i + j] + carry;
      limbs[i + j] = uint64_t(t);
      carry = t >> 64;
    }
    limbs[i + 2] = uint64_t(carry);
  }
  if (e == 0) return u128(limbs[0]) | u128(limbs[1]) << 64;
  // Half a unit of the result, then the bits from e up.
  u128 carry = u128(1) << ((e - 1) % 64);
  for (size_t i = size_t((e - 1) / 64); i < 4 && carry; ++i) {
    const u128 t = u128(limbs[i]) + carry;
    limbs[i] = uint64_t(t);
    carry = t >> 64;
  }
  const auto limb = [&](int i) { return i < 4 ? limbs[size_t(i)] : uint64_t(0); };
  const int k = e / 64, s = e % 64;
  u128 out = (u128(limb(k)) | u128(limb(k + 1)) << 64) >> s;
  if (s) out |= u128(limb(k + 2)) << (128 - s);
  return out;
}

namespace {

// The box of a cone's end discs, each radius widened by the rounding of a
// record at scale 2^e (sqrt of the bound above: (R + delta)^2 >= R^2 + delta^2),
// and one unit for the doubles and the root's rounding (a hit the pipeline
// computes lies in the box: the structures list the cone wherever it may hit). A disc of radius R about axis w reaches
// R sqrt(1 - w_a^2 / W) along axis a.
LatticeBox coneBounds(const LatticeCone& cone, int scaleExp) {
  double len2 = 0;
  for (size_t k = 0; k < 3; ++k) len2 += double(cone.apex[k] - cone.base[k]) * double(cone.apex[k] - cone.base[k]);
  double radius = double(std::max(cone.baseRadius, cone.apexRadius));
  if (scaleExp > 0) {
    const double slope = double(cone.apexRadius - cone.baseRadius);
    const double sum = 3.0 * std::ldexp(1.0, kPosBits + 1) + 1.0;
    radius += std::sqrt(std::max(1.0, slope * slope / len2) * sum * sum / std::ldexp(1.0, kQuadricK + 2));
  }
  LatticeBox box;
  for (size_t k = 0; k < 3; ++k) {
    const double along = double(cone.apex[k] - cone.base[k]);
    const int64_t reach = int64_t(std::ceil(radius * std::sqrt(std::max(0.0, 1.0 - along * along / len2)))) + 1;
    box.lo[k] = std::max<int64_t>(0, std::min(cone.base[k], cone.apex[k]) - reach);
    box.hi[k] = std::min(kPosMax, std::max(cone.base[k], cone.apex[k]) + reach);
  }
  return box;
}

}  // namespace

QQuadric sphereRecord(const QSphere& sphere) {
  for (size_t k = 0; k < 3; ++k) {
    if (sphere.center[k] < 0 || sphere.center[k] > kPosMax) throw std::invalid_argument("sphere: center off the lattice");
  }
  if (sphere.radius < 1 || sphere.radius > kPosMax) throw std::invalid_argument("sphere: radius outside 1 .. 2^P - 1 units");
  QQuadric rec;
  rec.id = sphere.id;
  for (size_t k = 0; k < 3; ++k) rec.axisSum[k] = 2 * sphere.center[k];
  rec.quad = {1, 1, 1, 0, 0, 0};
  rec.constant = -4 * sphere.radius * sphere.radius;
  for (size_t k = 0; k < 3; ++k) {
    rec.bounds.lo[k] = std::max<int64_t>(0, sphere.center[k] - sphere.radius - 1);
    rec.bounds.hi[k] = std::min(kPosMax, sphere.center[k] + sphere.radius + 1);
  }
  return rec;
}

QQuadric coneRecord(uint32_t id, const LatticeCone& cone) {
  for (size_t k = 0; k < 3; ++k) {
    if (cone.base[k] < 0 || cone.base[k] > kPosMax || cone.apex[k] < 0 || cone.apex[k] > kPosMax)
      throw std::invalid_argument("cone: base or apex off the lattice");
  }
  if (cone.baseRadius < 0 || cone.baseRadius > kPosMax || cone.apexRadius < 0 || cone.apexRadius > kPosMax)
    throw std::invalid_argument("cone: a radius off the lattice (0 .. 2^P - 1 units)");
  if (cone.baseRadius == 0 && cone.apexRadius == 0) throw std::invalid_argument("cone: both radii are 0");
  if (cone.base == cone.apex) throw std::invalid_argument("cone: zero length (base = apex)");

  QQuadric rec;
  rec.id = id;
  std::array<i128, 3> w{};
  for (size_t k = 0; k < 3; ++k) {
    rec.axisSum[k] = cone.apex[k] + cone.base[k];
    rec.axis[k] = cone.apex[k] - cone.base[k];
    w[k] = rec.axis[k];
    rec.axisLen2 += rec.axis[k] * rec.axis[k];
  }
  const i128 len2 = rec.axisLen2, slope = cone.apexRadius - cone.baseRadius, radii = cone.baseRadius + cone.apexRadius;
  // The exact quadric F(q) = W^2 |q|^2 - W (q.w)^2 - ((r0 + r1) W + (r1 - r0) q.w)^2.
  std::array<i128, 6> quad{};
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  u128 largest = 0;
  for (size_t p = 0; p < 6; ++p) {
    const size_t i = size_t(pairs[p][0]), j = size_t(pairs[p][1]);
    quad[p] = (i == j ? len2 * len2 : 0) - (len2 + slope * slope) * w[i] * w[j];
    largest = std::max(largest, u128(quad[p] < 0 ? -quad[p] : quad[p]));
  }
  // The common scale: the largest entry below 2^K (small cones stay exact).
  rec.scaleExp = std::max(0, bitLength(largest) - kQuadricK);
  for (size_t p = 0; p < 6; ++p) rec.quad[p] = int64_t(roundShift(quad[p], rec.scaleExp));
  for (size_t k = 0; k < 3; ++k) rec.lin[k] = int64_t(roundShift(-radii * len2 * slope * w[k], rec.scaleExp));
  rec.constant = -int64_t(roundShiftProduct(u128(radii * radii), u128(len2 * len2), rec.scaleExp));
  rec.bounds = coneBounds(cone, rec.scaleExp);
  return rec;
}

IsectResult intersectQuadric(const QRay& ray, const QQuadric& cone) {
  // The origin in the record's frame, and the ray's and the origin's heights
  // along the axis (times |w|, doubled for the origin; 0 for a sphere).
  std::array<i128, 3> q{}, d{};
  i128 originHeight = 0, dirHeight = 0;
  for (size_t k = 0; k < 3; ++k) {
    q[k] = 2 * i128(ray.org[k]) - cone.axisSum[k];
    d[k] = ray.dir[k];
    originHeight += q[k] * cone.axis[k];
    dirHeight += d[k] * cone.axis[k];
  }
  // F(q + 2 lambda d) = 4A lambda^2 + 4B lambda + C.
  i128 a = 0, b = 0, c = 0;
  for (int i = 0; i < 3; ++i) {
    i128 qRow = 0, dRow = 0;  // (Qq)_i, (Qd)_i
    for (int j = 0; j < 3; ++j) {
      qRow += cone.quadAt(i, j) * q[size_t(j)];
      dRow += cone.quadAt(i, j) * d[size_t(j)];
    }
    a += dRow * d[size_t(i)];
    b += (qRow + cone.lin[size_t(i)]) * d[size_t(i)];
    c += (qRow + 2 * cone.lin[size_t(i)]) * q[size_t(i)];
  }
  c += cone.constant;
  const i128 disc = b * b - a * c;
  if (disc < 0) return missOf(ray, cone.id);
  const i128 s = i128(isqrt(u128(disc)));
  // The root where 2A lambda + B = -sgn(B) sqrt(disc) and its conjugate, each
  // without cancellation. F falls through 0 (the ray enters) where 2A lambda +
  // B < 0; a tangent (disc = 0) counts as entering.
  const i128 big = b < 0 ? -b + s : -b - s;
  Root first = rootOf(big, 2 * a, b < 0 && disc > 0);
  Root second = rootOf(c, 2 * big, b >= 0 && disc > 0);
  // Which is nearer, without dividing: first - second = (big^2 - AC) / 2A big
  // and big^2 - AC = disc + 2|B|s + s^2, > 0 when disc > 0; so the second is
  // the nearer exactly when disc > 0 and A and big have one sign (equal roots
  // at disc = 0 keep their order).
  if (first.ahead() && second.ahead() && disc > 0 && (a < 0) == (big < 0)) std::swap(first, second);
  const auto betweenPlanes = [&](const Root& r) {
    // |q.w + 2 lambda d.w| <= W at lambda = num / den, cross-multiplied.
    const i128 height = originHeight * i128(r.den) + 2 * r.num * dirHeight;
    return (height < 0 ? -height : height) <= cone.axisLen2 * i128(r.den);
  };
  return quadricHit(ray, cone.id, first, second, betweenPlanes);
}

std::array<u128, kIsectQuadricValues> fieldArray(const QQuadric& q) {
  std::array<u128, kIsectQuadricValues> v{};
  size_t n = 0;
  const auto put = [&](int64_t x) { v[n++] = u128(i128(x)); };
  put(q.id);
  for (int64_t x : q.axisSum) put(x);
  for (int64_t x : q.axis) put(x);
  put(q.axisLen2);
  for (int64_t x : q.quad) put(x);
  for (int64_t x : q.lin) put(x);
  put(q.constant);
  return v;
}

void packWire(const QQuadric& quadric, std::span<uint32_t> wire) {
  const auto values = fieldArray(quadric);
  packFields(kIsectQuadricFields, values, wire);
}

QQuadric unpackQuadric(std::span<const uint32_t> wire) {
  std::array<u128, kIsectQuadricValues> v{};
  unpackFields(kIsectQuadricFields, wire, v);
  QQuadric q;
  size_t n = 0;
  const auto get = [&] { return int64_t(v[n++]); };  // signed fields come sign-extended
  q.id = uint32_t(get());
  for (int64_t& x : q.axisSum) x = get();
  for (int64_t& x : q.axis) x = get();
  q.axisLen2 = get();
  for (int64_t& x : q.quad) x = get();
  for (int64_t& x : q.lin) x = get();
  q.constant = get();
  return q;
}

}  // namespace lancer::fx
