#pragma once

// The placements of a stress case (docs/stability.md, "Scale and placement"):
// the same scene and rays scaled by a power of two, translated far from the
// origin, or stretched along x. A power-of-two scale changes no bit of the
// lattice image (every float of the scene and of the rays scales exactly, and so
// does the quantizer), so the hardware's answers must be identical bit for bit;
// a translation or a stretch rounds the floats, and its answers are held to
// the lattice's error bound against exact arithmetic.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/quantize.h"
#include "stress/cases.h"

namespace lancer::stress {

struct Variant {
  enum class Kind { Base, Scale, Translate, Stretch };
  Kind kind = Kind::Base;
  double amount = 0;  // Scale: the exponent k of 2^k; Translate: the offset in scene sizes; Stretch: the x factor

  std::string name() const;  // "base", "scale 2^-60", "translate 1000x", "stretch 10000:1"
  // Whether the lattice image is the base case's bit for bit.
  bool latticeExact() const { return kind == Kind::Base || kind == Kind::Scale; }
};

// Base first, then the scales, translations and stretches given. Throws
// InputError for a translation or stretch that is not positive and finite, or
// a scale exponent outside -149..127.
std::vector<Variant> makeVariants(const std::vector<int>& scaleExponents, const std::vector<double>& translations,
                                  const std::vector<double>& stretches);

// `base` placed by `v`. Throws InputError naming the case, the variant and the
// vertex or ray when a coordinate leaves float range (overflows, or a non-zero
// one becomes zero or subnormal), a ray is not valid, or a ray's t across the
// scene leaves float range (a hit's t is a float).
StressCase place(const StressCase& base, const Variant& v);

// How well one uniform lattice holds a placed scene: the shortest extent of the
// scene in lattice units, and the spacing of float32 values at its farthest
// coordinate in lattice units (above about 1 the floats, not the lattice, limit
// the shape). `warning` is empty, or says which limit is near and by how much.
struct LatticeFit {
  double shortestExtentUnits = 0;
  double floatSpacingUnits = 0;
  std::string warning;
  nlohmann::json toJson() const;
  static LatticeFit fromJson(const nlohmann::json& j);  // toJson's object back
};
LatticeFit latticeFit(const Scene& scene, const Quantizer& quantizer);

}  // namespace lancer::stress
