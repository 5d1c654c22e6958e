#include "golden/lattice.h"

#include <algorithm>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/isect.h"

namespace lancer::fx {

LatticeBox latticeBounds(const QTriangle& t) {
  LatticeBox b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min({t.v[0][a], t.v[1][a], t.v[2][a]});
    b.hi[a] = std::max({t.v[0][a], t.v[1][a], t.v[2][a]});
  }
  return b;
}

MirroredRay MirroredRay::of(const QRay& ray) {
  MirroredRay s;
  std::array<u128, 3> absD{};
  for (int a = 0; a < 3; ++a) {
    const bool mirrored = ray.dir[a] < 0;
    if (mirrored) s.mirror |= 4 >> a;
    s.origin[a] = mirrored ? kLatticeSide - ray.org[a] : ray.org[a];  // min + max - o
    absD[a] = u128(mirrored ? -ray.dir[a] : ray.dir[a]);
    s.active[a] = absD[a] != 0;
    if (s.active[a]) s.common *= absD[a];
  }
  for (int a = 0; a < 3; ++a) {
    s.pair[a] = 1;
    for (int b = 0; b < 3; ++b) {
      if (b != a && s.active[b]) s.pair[a] *= i128(absD[b]);
    }
  }
  s.dominant = absD[dominantAxis(ray.dir)];
  return s;
}

void checkNonZeroDirections(std::span<const QRay> rays, std::string_view unit) {
  for (const QRay& ray : rays) {
    if (ray.dir[0] == 0 && ray.dir[1] == 0 && ray.dir[2] == 0) {
      throw InputError(fmt::format("ray {} has a zero direction: the {} unit needs a non-zero component", ray.id, unit));
    }
  }
}

}  // namespace lancer::fx
