// libFuzzer target: the quantizer (sw/driver/quantize), the boundary between
// scene floats and the hardware's lattice. The input is floats, bit for bit:
// the scene bounds (lo, hi), a triangle (v0, v1, v2) and a ray (origin, dir,
// tMax). Every call returns or throws InputError (no crash, no UBSan report),
// and what it returns is in range:
//   - bounds that are finite and not empty make a Quantizer;
//   - a triangle inside those bounds quantizes, to lattice points within half
//     a unit of its vertices;
//   - a valid ray (validateRay) that quantizes has its origin on the lattice
//     cube, near the ray's entry point, a direction whose dominant component
//     is exactly +-kDirMax, and a finite t mapping inside [0, tMax].

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "driver/quantize.h"
#include "fuzz_support.h"
#include "scene/rays_file.h"

using namespace lancer;

namespace {

glm::vec3 takeVec(fuzz::Bytes& in) {
  const float x = in.take<float>(), y = in.take<float>(), z = in.take<float>();
  return {x, y, z};
}

bool finiteBox(const Aabb& b) { return allFinite(b.lo) && allFinite(b.hi) && !b.empty(); }

bool insideBox(const Aabb& b, const glm::vec3& p) {
  return glm::all(glm::greaterThanEqual(p, b.lo)) && glm::all(glm::lessThanEqual(p, b.hi));
}

void checkTriangle(const Quantizer& quantizer, const Aabb& bounds, const Triangle& tri) {
  const bool inside = finiteBox(bounds) && insideBox(bounds, tri.v0) && insideBox(bounds, tri.v1) &&
                      insideBox(bounds, tri.v2);
  fx::QTriangle q;
  try {
    q = quantizer.quantize(tri, 7);
  } catch (const InputError&) {
    FUZZ_CHECK(!inside, "a triangle inside the scene bounds was refused");
    return;
  }
  FUZZ_CHECK(q.id == 7, "triangle id {}", q.id);
  const glm::vec3* vertices[3] = {&tri.v0, &tri.v1, &tri.v2};
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      const int64_t c = q.v[k][axis];
      FUZZ_CHECK(c >= 0 && c <= fx::kPosMax, "vertex {} axis {}: lattice {} outside [0, {}]", k, axis, c,
                 fx::kPosMax);
      const double exact = (double((*vertices[k])[axis]) - quantizer.latticeOrigin()[axis]) / quantizer.unit();
      FUZZ_CHECK(std::abs(double(c) - exact) <= 0.5 + 1e-9 * std::max(1.0, std::abs(exact)),
                 "vertex {} axis {}: lattice {} for {}", k, axis, c, exact);
    }
  }
}

void checkRay(const Quantizer& quantizer, const Ray& ray) {
  try {
    validateRay(ray, 0, "fuzz");
  } catch (const InputError&) {
    return;  // the quantizer's contract starts at a valid ray
  }
  const std::optional<QuantizedRay> q = quantizer.quantize(ray, 3);
  if (!q) return;
  FUZZ_CHECK(q->q.id == 3, "ray id {}", q->q.id);
  int64_t dominant = 0;
  for (int axis = 0; axis < 3; ++axis) {
    FUZZ_CHECK(q->q.org[axis] >= 0 && q->q.org[axis] <= fx::kPosMax, "origin axis {}: {}", axis, q->q.org[axis]);
    FUZZ_CHECK(std::abs(q->q.dir[axis]) <= fx::kDirMax, "direction axis {}: {}", axis, q->q.dir[axis]);
    dominant = std::max(dominant, std::abs(q->q.dir[axis]));
  }
  FUZZ_CHECK(dominant == fx::kDirMax, "dominant direction component {} (not {})", dominant, fx::kDirMax);
  FUZZ_CHECK(std::isfinite(q->tEnter) && q->tEnter >= 0 && q->tEnter <= double(ray.tMax), "tEnter {} (tMax {})",
             q->tEnter, ray.tMax);
  FUZZ_CHECK(std::isfinite(q->tScale) && q->tScale > 0, "tScale {}", q->tScale);
  // The quantized origin is the entry point rounded to the lattice: within half
  // a unit, plus the rounding of computing the entry point in double.
  const double unit = quantizer.unit();
  const glm::dvec3 o(ray.origin), d(ray.dir);
  // Grouped as the quantizer does: the origin relative to the lattice first
  // (o + t d alone would absorb t d into a far-away o).
  const glm::dvec3 entry = ((o - quantizer.latticeOrigin()) + q->tEnter * d) / unit;
  const glm::dvec3 slack = 8e-16 * (glm::abs(o - quantizer.latticeOrigin()) + glm::abs(q->tEnter * d)) / unit;
  for (int axis = 0; axis < 3; ++axis) {
    const double exact = std::clamp(entry[axis], 0.0, double(fx::kPosMax));
    FUZZ_CHECK(std::abs(double(q->q.org[axis]) - exact) <= 0.5 + 1e-9 + slack[axis],
               "origin axis {}: lattice {} for the entry point {}", axis, q->q.org[axis], entry[axis]);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fuzz::Bytes in(data, size);
  Aabb bounds;
  bounds.lo = takeVec(in);
  bounds.hi = takeVec(in);
  const Triangle tri{takeVec(in), takeVec(in), takeVec(in)};
  Ray ray;
  ray.origin = takeVec(in);
  ray.dir = takeVec(in);
  // A segment end when the input gives a positive one (NaN and <= 0 are not
  // segments a caller can ask for), else the default infinite ray.
  if (const float tMax = in.take<float>(); tMax > 0) ray.tMax = tMax;

  std::optional<Quantizer> quantizer;
  try {
    quantizer.emplace(bounds);
  } catch (const InputError&) {
    FUZZ_CHECK(!finiteBox(bounds), "finite, non-empty bounds were refused");
    return 0;
  }
  checkTriangle(*quantizer, bounds, tri);
  checkRay(*quantizer, ray);
  return 0;
}
