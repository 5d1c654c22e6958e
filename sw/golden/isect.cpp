#include "golden/isect.h"

#include <cstdlib>

#include "golden/wide.h"

namespace lancer::fx {

int dominantAxis(const std::array<int64_t, 3>& dir) {
  const int64_t x = std::llabs(dir[0]), y = std::llabs(dir[1]), z = std::llabs(dir[2]);
  if (x >= y && x >= z) return 0;
  return y >= z ? 1 : 2;
}

IsectResult intersect(const QRay& ray, const QTriangle& tri) {
  IsectResult res;
  res.rayId = ray.id;
  res.primId = tri.id;
  // Step 1.
  const int kz = dominantAxis(ray.dir);
  const int kx = (kz + 1) % 3;
  const int ky = (kx + 1) % 3;
  const int64_t dx = ray.dir[kx], dy = ray.dir[ky], dz = ray.dir[kz];
  // Steps 2 and 3: |a| < 2^P and |d| < 2^(D-1), so each product fits P+D-1 bits.
  std::array<int64_t, 3> sx{}, sy{}, sz{};
  for (int k = 0; k < 3; ++k) {
    const int64_t rx = tri.v[k][kx] - ray.org[kx];
    const int64_t ry = tri.v[k][ky] - ray.org[ky];
    const int64_t rz = tri.v[k][kz] - ray.org[kz];
    sx[k] = dz * rx - dx * rz;
    sy[k] = dz * ry - dy * rz;
    sz[k] = rz;
  }
  // Step 4.
  const i128 u = i128(sx[2]) * sy[1] - i128(sy[2]) * sx[1];
  const i128 v = i128(sx[0]) * sy[2] - i128(sy[0]) * sx[2];
  const i128 w = i128(sx[1]) * sy[0] - i128(sy[1]) * sx[0];
  // Step 5.
  const bool anyNegative = u < 0 || v < 0 || w < 0;
  const bool anyPositive = u > 0 || v > 0 || w > 0;
  const i128 det = u + v + w;
  if ((anyNegative && anyPositive) || det == 0) return res;
  // Step 6.
  const i128 t = u * sz[0] + v * sz[1] + w * sz[2];
  // Step 7: t > 0 iff T and d[kz]*det have the same sign.
  const bool flip = (det < 0) != (dz < 0);
  const i128 tSigned = flip ? -t : t;
  if (tSigned <= 0) return res;
  // Step 8: within the segment, t_num * 2^F <= t_max * det (formats.h).
  const bool negDet = det < 0;
  const u128 absDet = u128(negDet ? -det : det);
  if (mul256(u128(ray.tMax), absDet) < mul256(u128(tSigned), u128(1) << kSegFracBits)) return res;
  res.hit = true;
  res.tNum = u128(tSigned);
  res.det = absDet;
  res.uNum = u128(negDet ? -v : v);
  res.vNum = u128(negDet ? -w : w);
  return res;
}

bool closerResult(const IsectResult& a, const IsectResult& b) {
  const U256 ta = mul256(a.tNum, b.det);
  const U256 tb = mul256(b.tNum, a.det);
  return ta < tb || (ta == tb && a.primId < b.primId);
}

IsectResult segmentEndBound(const QRay& ray) {
  IsectResult end;
  end.rayId = ray.id;
  end.tNum = ray.tMax;
  end.det = u128(1) << kSegFracBits;
  return end;
}

std::optional<IsectResult> walkBound(const QRay& ray, const std::optional<IsectResult>& closest) {
  if (closest) return closest;
  if (ray.bounded()) return segmentEndBound(ray);
  return std::nullopt;
}

double tOf(const IsectResult& res, const QRay& ray) {
  const double dz = double(std::llabs(ray.dir[dominantAxis(ray.dir)]));
  return double(res.tNum) / (dz * double(res.det));
}
double uOf(const IsectResult& res) { return double(res.uNum) / double(res.det); }
double vOf(const IsectResult& res) { return double(res.vNum) / double(res.det); }

}  // namespace lancer::fx
