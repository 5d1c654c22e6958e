#pragma once

// What the traversal units share about the position lattice: its side, a
// triangle's integer bounding box, and the mirrored ray of the parametric
// walks (the octree unit's and the BVH unit's; docs/octree-unit.md,
// docs/bvh-unit.md).

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "golden/records.h"

namespace lancer::fx {

// The lattice cube [0, 2^P] on every axis: positions are 0 .. kPosMax, and a
// mirrored coordinate is kLatticeSide - p.
inline constexpr int64_t kLatticeSide = int64_t(1) << kPosBits;

// An integer box, closed: [lo, hi] on each axis.
struct LatticeBox {
  std::array<int64_t, 3> lo{}, hi{};
  bool operator==(const LatticeBox&) const = default;
};

// The triangle's bounding box on the lattice (exact: vertices are lattice points).
LatticeBox latticeBounds(const QTriangle& triangle);

// The per-ray setup of the parametric walks, multiplications only: every axis
// with a negative direction component mirrored (o' = 2^P - o, so every |d| is
// positive), and the scale of the plane parameters: on an axis the ray
// crosses, a plane's parameter is T = (plane' - o') * pair[a], so that
// t = T / common on every axis alike and parameters of different axes
// compare directly.
struct MirroredRay {
  std::array<int64_t, 3> origin{};  // o', the mirrored origin
  std::array<bool, 3> active{};     // the ray crosses planes of this axis (d != 0)
  std::array<i128, 3> pair{};       // prod |d_b| over the active axes b != a (1 if none)
  int mirror = 0;                   // the mirrored axes, a = 4 sx + 2 sy + sz
  u128 common = 1;                  // prod |d_a| over the active axes
  u128 dominant = 1;                // |d[kz]|, the pipeline's t scale
  bool mirrored(int axis) const { return (mirror >> (2 - axis)) & 1; }
  static MirroredRay of(const QRay& ray);
};

// The parametric walks scale by the dominant |d|: InputError naming the first
// ray with a zero direction (the quantizer never makes one) and `unit`.
void checkNonZeroDirections(std::span<const QRay> rays, std::string_view unit);

}  // namespace lancer::fx
