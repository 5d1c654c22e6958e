#include "driver/quantize.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/isect.h"

namespace lancer {

Quantizer::Quantizer(const Aabb& bounds, int64_t marginUnits) {
  if (marginUnits < 0 || 4 * marginUnits > fx::kPosMax) {
    throw InputError(fmt::format("lattice margin {} must lie in 0..{} units (a quarter of the {}-bit lattice)",
                                 marginUnits, fx::kPosMax / 4, fx::kPosBits));
  }
  // An empty box (no triangles) or a non-finite one has no lattice: every ray
  // would quantize from a NaN origin (found by tests/fuzz/fuzz_quantize).
  if (bounds.empty() || !allFinite(bounds.lo) || !allFinite(bounds.hi)) {
    throw InputError(fmt::format("scene bounds ({}, {}, {}) .. ({}, {}, {}) are empty or not finite: no lattice to quantize to",
                                 bounds.lo.x, bounds.lo.y, bounds.lo.z, bounds.hi.x, bounds.hi.y, bounds.hi.z));
  }
  const glm::dvec3 lo(bounds.lo), hi(bounds.hi);
  double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  if (!(side > 0.0) || !std::isfinite(side)) side = 1.0;  // a point-like scene still gets a lattice
  // The bounds fill the lattice but for a margin on every side, so the scene's
  // own faces lie strictly inside the cube (see kLatticeMarginUnits). Every
  // step is a product or quotient of the bounds, so scaling the scene by a
  // power of two scales lo_ and 1 / scale_ by the same power exactly.
  scale_ = double(fx::kPosMax - 2 * marginUnits) / side;
  lo_ = 0.5 * (lo + hi) - glm::dvec3(0.5 * double(fx::kPosMax) / scale_);
}

std::array<int64_t, 3> Quantizer::latticePoint(const glm::vec3& point, const std::string& what) const {
  std::array<int64_t, 3> q{};
  for (int axis = 0; axis < 3; ++axis) {
    const double x = (double(point[axis]) - lo_[axis]) * scale_;
    if (!(x >= -0.5 && x <= double(fx::kPosMax) + 0.5)) {
      throw InputError(fmt::format("{}: coordinate {} is outside the {}-bit position format's range "
                                   "(lattice {:.3f} not in [0, {}])",
                                   what, point[axis], fx::kPosBits, x, fx::kPosMax));
    }
    // Round half to even (the current FP rounding mode), then clamp the half unit of slack.
    q[size_t(axis)] = std::clamp<int64_t>(std::llrint(x), 0, fx::kPosMax);
  }
  return q;
}

fx::QTriangle Quantizer::quantize(const Triangle& tri, uint32_t id) const {
  fx::QTriangle q;
  q.id = id;
  const glm::vec3* vertices[3] = {&tri.v0, &tri.v1, &tri.v2};
  for (int k = 0; k < 3; ++k) q.v[size_t(k)] = latticePoint(*vertices[k], fmt::format("triangle {} vertex {}", id, k));
  return q;
}

std::vector<fx::QTriangle> Quantizer::quantize(const Scene& scene) const {
  scene.requireTrianglesOnly("the lattice quantizer");
  return quantizeTriangles(scene);
}

std::vector<fx::QTriangle> Quantizer::quantizeTriangles(const Scene& scene) const {
  std::vector<fx::QTriangle> triangles(scene.size());
  for (uint32_t i = 0; i < scene.size(); ++i) triangles[i] = quantize(scene.triangles[i], i);
  return triangles;
}

fx::QQuadric Quantizer::quantize(const Quadric& quadric, uint32_t id) const {
  // |r| in lattice units, to the nearest unit (half to even), within the lattice.
  const auto units = [&](float radius) {
    return std::clamp<int64_t>(std::llrint(std::abs(double(radius)) * scale_), 0, fx::kPosMax);
  };
  if (quadric.kind == Quadric::Kind::Sphere) {
    fx::QSphere s;
    s.id = id;
    s.center = latticePoint(quadric.center(), fmt::format("sphere {} center", id));
    s.radius = std::max<int64_t>(1, units(quadric.radius()));
    return fx::sphereRecord(s);
  }
  fx::LatticeCone c;
  c.base = latticePoint(quadric.base, fmt::format("cone {} base", id));
  c.apex = latticePoint(quadric.apex, fmt::format("cone {} apex", id));
  c.baseRadius = units(quadric.baseRadius);
  c.apexRadius = units(quadric.apexRadius);
  if (c.baseRadius == 0 && c.apexRadius == 0) {
    (std::abs(quadric.baseRadius) >= std::abs(quadric.apexRadius) ? c.baseRadius : c.apexRadius) = 1;
  }
  if (c.base == c.apex) {
    // Shorter than a unit: one unit along the axis' dominant direction, away
    // from the lattice's nearer face.
    const glm::dvec3 w = glm::dvec3(quadric.apex) - glm::dvec3(quadric.base);
    const int axis = std::abs(w.x) >= std::abs(w.y) && std::abs(w.x) >= std::abs(w.z) ? 0
                     : std::abs(w.y) >= std::abs(w.z)                                ? 1
                                                                                      : 2;
    int64_t& end = c.apex[size_t(axis)];
    end += (w[axis] >= 0.0 ? end < fx::kPosMax : end == 0) ? 1 : -1;
  }
  return fx::coneRecord(id, c);
}

std::vector<fx::QQuadric> Quantizer::quantizeQuadrics(const Scene& scene) const {
  std::vector<fx::QQuadric> quadrics(scene.quadrics.size());
  for (size_t i = 0; i < quadrics.size(); ++i) quadrics[i] = quantize(scene.quadrics[i], uint32_t(scene.size() + i));
  return quadrics;
}

std::optional<QuantizedRay> Quantizer::quantize(const Ray& ray, uint32_t id) const {
  const glm::dvec3 o = (glm::dvec3(ray.origin) - lo_) * scale_;
  const glm::dvec3 d = glm::dvec3(ray.dir) * scale_;
  // Clip to the cube [0, kPosMax]^3; a zero component never bounds t.
  double tEnter = 0.0, tExit = double(ray.tMax);
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0.0) {
      if (o[axis] < 0.0 || o[axis] > double(fx::kPosMax)) return std::nullopt;
      continue;
    }
    double t0 = (0.0 - o[axis]) / d[axis];
    double t1 = (double(fx::kPosMax) - o[axis]) / d[axis];
    if (t0 > t1) std::swap(t0, t1);
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
  }
  if (tEnter > tExit) return std::nullopt;

  QuantizedRay out;
  out.q.id = id;
  out.tEnter = tEnter;
  const glm::dvec3 entry = o + tEnter * d;
  for (int axis = 0; axis < 3; ++axis) {
    out.q.org[axis] = std::clamp<int64_t>(std::llrint(entry[axis]), 0, fx::kPosMax);
  }
  finish(out, o, d, double(ray.tMax));
  return out;
}

std::optional<QuantizedRay> Quantizer::quantizeFrom(const glm::dvec3& latticeOrigin, const Ray& ray,
                                                    uint32_t id) const {
  QuantizedRay out;
  out.q.id = id;
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t c = std::llrint(latticeOrigin[axis]);
    if (!(c >= 0 && c <= fx::kPosMax)) return std::nullopt;
    out.q.org[axis] = c;
  }
  const glm::dvec3 o = toLattice(glm::dvec3(ray.origin));
  const glm::dvec3 d = glm::dvec3(ray.dir) * scale_;
  // The scene t of the lattice origin, projected on the ray.
  const glm::dvec3 org(double(out.q.org[0]), double(out.q.org[1]), double(out.q.org[2]));
  out.tEnter = glm::dot(org - o, d) / glm::dot(d, d);
  finish(out, o, d, double(ray.tMax));
  return out;
}

void Quantizer::finish(QuantizedRay& out, const glm::dvec3& o, const glm::dvec3& d, double tMax) const {
  // Direction: the dominant component becomes exactly +-kDirMax, the others round.
  const double magnitude = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  const double toDir = double(fx::kDirMax) / magnitude;
  for (int axis = 0; axis < 3; ++axis) out.q.dir[axis] = std::llrint(d[axis] * toDir);
  // A lattice-t unit moves the ray by q = d * toDir lattice units: t_scene = t_lattice * toDir.
  out.tScale = toDir;
  // Segment end: the end point's displacement from the lattice origin along the
  // dominant axis, rounded down to 2^-F units; none if the end is outside the cube.
  out.q.tMax = fx::kSegEndNone;
  if (!std::isfinite(tMax)) return;
  const glm::dvec3 end = o + tMax * d;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(end[axis] >= 0.0 && end[axis] <= double(fx::kPosMax))) return;
  }
  const int k = fx::dominantAxis(out.q.dir);
  const double along = (end[k] - double(out.q.org[k])) * (out.q.dir[k] > 0 ? 1.0 : -1.0);
  const double code = std::floor(std::max(along, 0.0) * double(uint64_t(1) << fx::kSegFracBits));
  out.q.tMax = uint64_t(std::min(code, double(fx::kSegEndNone - 1)));
}

glm::dvec3 Quantizer::sceneOrigin(const fx::QRay& q) const {
  return lo_ + glm::dvec3(double(q.org[0]), double(q.org[1]), double(q.org[2])) / scale_;
}

glm::dvec3 Quantizer::sceneDirection(const fx::QRay& q) const {
  return glm::dvec3(double(q.dir[0]), double(q.dir[1]), double(q.dir[2])) / scale_;
}

}  // namespace lancer
