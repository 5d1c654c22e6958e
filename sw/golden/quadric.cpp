#include "golden/quadric.h"

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

IsectResult intersectSphere(const QRay& ray, const QSphere& sphere) {
  IsectResult res;
  res.rayId = ray.id;
  res.primId = sphere.id;
  i128 a = 0, b = 0, c = 0;
  for (int k = 0; k < 3; ++k) {
    const i128 m = i128(ray.org[size_t(k)] - sphere.center[size_t(k)]);
    const i128 d = i128(ray.dir[size_t(k)]);
    a += d * d;
    b += m * d;
    c += m * m;
  }
  c -= i128(sphere.radius) * sphere.radius;
  const i128 disc = b * b - a * c;
  if (disc < 0 || a == 0) return res;
  const i128 s = i128(isqrt(u128(disc)));
  const i128 entering = -b - s, leaving = -b + s;
  const i128 n = entering > 0 ? entering : leaving;
  if (n <= 0) return res;
  const int64_t dz = ray.dir[size_t(dominantAxis(ray.dir))];
  const u128 tNum = u128(n) * u128(dz < 0 ? -dz : dz);
  const u128 det = u128(a);
  if (mul256(u128(ray.tMax), det) < mul256(tNum, u128(1) << kSegFracBits)) return res;
  res.hit = true;
  res.tNum = tNum;
  res.det = det;
  res.uNum = entering > 0 ? 0 : 1;
  res.vNum = 0;
  return res;
}

}  // namespace lancer::fx
