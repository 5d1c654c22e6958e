#include "golden/dual.h"

#include <algorithm>
#include <array>

#include "golden/isect.h"

namespace lancer::fx {

namespace {

// A closed interval of integers; every value the dropped bits allow lies in it.
struct Interval {
  i128 lo = 0, hi = 0;
};

Interval operator+(Interval a, Interval b) { return {a.lo + b.lo, a.hi + b.hi}; }
Interval operator-(Interval a, Interval b) { return {a.lo - b.hi, a.hi - b.lo}; }
Interval operator-(Interval a) { return {-a.hi, -a.lo}; }
Interval operator*(Interval a, Interval b) {
  const std::array<i128, 4> p = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p.begin(), p.end()), *std::max_element(p.begin(), p.end())};
}

// What the narrow unit knows of `value` with its low `drop` bits gone:
// floor(value / 2^drop) * 2^drop plus anything below 2^drop.
Interval truncated(int64_t value, int drop) {
  const i128 base = i128(value >> drop) * (i128(1) << drop);
  return {base, base + (i128(1) << drop) - 1};
}

}  // namespace

bool narrowRejects(const QRay& ray, const QTriangle& tri, int narrowBits) {
  const int dropPos = std::max(0, kPosBits - narrowBits), dropDir = std::max(0, kDirBits - narrowBits);
  // The dominant axis is the full-width ray's: its component is +-kDirMax by
  // construction, so the narrow unit gets it with the ray.
  const int kz = dominantAxis(ray.dir);
  const int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  const Interval dx = truncated(ray.dir[kx], dropDir), dy = truncated(ray.dir[ky], dropDir);
  const Interval dz = truncated(ray.dir[kz], dropDir);
  std::array<Interval, 3> sx, sy, sz;
  for (int k = 0; k < 3; ++k) {
    const auto rel = [&](int axis) { return truncated(tri.v[k][axis], dropPos) - truncated(ray.org[axis], dropPos); };
    const Interval rx = rel(kx), ry = rel(ky), rz = rel(kz);
    sx[k] = dz * rx - dx * rz;
    sy[k] = dz * ry - dy * rz;
    sz[k] = rz;
  }
  const Interval u = sx[2] * sy[1] - sy[2] * sx[1];
  const Interval v = sx[0] * sy[2] - sy[0] * sx[2];
  const Interval w = sx[1] * sy[0] - sy[1] * sx[0];
  // Step 5: one edge surely negative and another surely positive.
  const bool someNegative = u.hi < 0 || v.hi < 0 || w.hi < 0;
  const bool somePositive = u.lo > 0 || v.lo > 0 || w.lo > 0;
  if (someNegative && somePositive) return true;
  // Step 7: t surely <= 0, where the signs of det and d[kz] are sure.
  const Interval det = u + v + w;
  const bool detSure = det.lo > 0 || det.hi < 0, dzSure = dz.lo > 0 || dz.hi < 0;
  if (!detSure || !dzSure) return false;
  const Interval t = u * sz[0] + v * sz[1] + w * sz[2];
  const bool flip = (det.hi < 0) != (dz.hi < 0);
  return (flip ? -t : t).hi <= 0;
}

}  // namespace lancer::fx
