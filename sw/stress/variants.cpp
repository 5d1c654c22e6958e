#include "stress/variants.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/formats.h"
#include "scene/rays_file.h"

namespace lancer::stress {

namespace {

// Below 2^-126 a float is subnormal (fewer bits) or zero: the scale lost the shape.
bool representable(float original, float placed) {
  if (!std::isfinite(placed)) return false;
  return original == 0.0f || std::fabs(placed) >= std::numeric_limits<float>::min();
}

// A far-off direction that is no axis (so every coordinate moves).
const glm::dvec3 kTranslationAxis = glm::normalize(glm::dvec3(1.0, 0.618, 0.382));

}  // namespace

std::string Variant::name() const {
  switch (kind) {
    case Kind::Base: return "base";
    case Kind::Scale: return fmt::format("scale 2^{}", int(amount));
    case Kind::Translate: return fmt::format("translate {:g}x", amount);
    case Kind::Stretch: return fmt::format("stretch {:g}:1", amount);
  }
  return "?";
}

std::vector<Variant> makeVariants(const std::vector<int>& scaleExponents, const std::vector<double>& translations,
                                  const std::vector<double>& stretches) {
  std::vector<Variant> out{{Variant::Kind::Base, 0}};
  for (const int k : scaleExponents) {
    if (k < -149 || k > 127) {
      throw InputError(fmt::format("--scales {}: 2^{} lies beyond float range (exponents -149..127)", k, k));
    }
    if (k != 0) out.push_back({Variant::Kind::Scale, double(k)});
  }
  for (const double f : translations) {
    if (!(f > 0.0) || !std::isfinite(f)) throw InputError(fmt::format("--translations {}: must be positive", f));
    out.push_back({Variant::Kind::Translate, f});
  }
  for (const double a : stretches) {
    if (!(a > 0.0) || !std::isfinite(a)) throw InputError(fmt::format("--stretches {}: must be positive", a));
    out.push_back({Variant::Kind::Stretch, a});
  }
  return out;
}

StressCase place(const StressCase& base, const Variant& v) {
  StressCase out = base;
  const std::string where = fmt::format("stress case {}, {}", base.name, v.name());
  const glm::vec3 size = base.scene.bounds.diagonal();
  const glm::dvec3 offset = v.amount * double(std::max({size.x, size.y, size.z})) * kTranslationAxis;
  // One point (a vertex or a ray origin); directions move only under a stretch.
  const auto movePoint = [&](const glm::vec3& p) {
    glm::vec3 q = p;
    switch (v.kind) {
      case Variant::Kind::Base: break;
      case Variant::Kind::Scale:
        for (int a = 0; a < 3; ++a) q[a] = std::ldexp(p[a], int(v.amount));
        break;
      case Variant::Kind::Translate: q = glm::vec3(glm::dvec3(p) + offset); break;
      case Variant::Kind::Stretch: q.x = float(double(p.x) * v.amount); break;
    }
    return q;
  };
  const auto check = [&](const glm::vec3& before, const glm::vec3& after, const std::string& what) {
    for (int a = 0; a < 3; ++a) {
      if (!representable(before[a], after[a])) {
        throw InputError(fmt::format("{}: {} coordinate {} becomes {} (beyond float range)", where, what, before[a],
                                     after[a]));
      }
    }
  };
  // A scene read from text is scaled as text and read again: the reader's rounding is what is placed.
  const bool reread = v.kind == Variant::Kind::Scale && base.readScaled;
  if (reread) out.scene = base.readScaled(int(v.amount));
  for (size_t i = 0; i < out.scene.triangles.size(); ++i) {
    Triangle& t = out.scene.triangles[i];
    const Triangle before = base.scene.triangles[i];
    if (!reread) t = {movePoint(t.v0), movePoint(t.v1), movePoint(t.v2)};
    check(before.v0, t.v0, fmt::format("triangle {} vertex 0", i));
    check(before.v1, t.v1, fmt::format("triangle {} vertex 1", i));
    check(before.v2, t.v2, fmt::format("triangle {} vertex 2", i));
  }
  for (size_t i = 0; i < out.rays.size(); ++i) {
    Ray& r = out.rays[i];
    const Ray before = r;
    r.origin = movePoint(r.origin);
    check(before.origin, r.origin, fmt::format("ray {} origin", i));
    if (v.kind == Variant::Kind::Stretch) r.dir.x = float(double(r.dir.x) * v.amount);
    if (v.kind == Variant::Kind::Scale) r.tMax = std::ldexp(r.tMax, int(v.amount));
    validateRay(r, i, where);
  }
  out.scene.computeBounds();
  // A hit's t is a float: a ray whose t across the scene leaves float range
  // would come back at t = inf (a huge scene, a tiny direction).
  const Aabb& b = out.scene.bounds;
  for (size_t i = 0; i < out.rays.size(); ++i) {
    const glm::dvec3 o(out.rays[i].origin);
    const glm::dvec3 farthest = glm::max(glm::abs(glm::dvec3(b.lo) - o), glm::abs(glm::dvec3(b.hi) - o));
    const double tFar = glm::length(farthest) / glm::length(glm::dvec3(out.rays[i].dir));
    if (!(tFar <= double(std::numeric_limits<float>::max()))) {
      throw InputError(fmt::format("{}: ray {} reaches the far side of the scene at t = {:.3g}, beyond float range",
                                   where, i, tFar));
    }
  }
  out.scene.name = fmt::format("{} ({})", base.scene.name, v.name());
  return out;
}

nlohmann::json LatticeFit::toJson() const {
  nlohmann::json j = {{"shortest_extent_lattice_units", shortestExtentUnits},
                      {"float_spacing_lattice_units", floatSpacingUnits}};
  if (!warning.empty()) j["warning"] = warning;
  return j;
}

LatticeFit LatticeFit::fromJson(const nlohmann::json& j) {
  return {j.at("shortest_extent_lattice_units").get<double>(), j.at("float_spacing_lattice_units").get<double>(),
          j.value("warning", "")};
}

LatticeFit latticeFit(const Scene& scene, const Quantizer& quantizer) {
  LatticeFit fit;
  const glm::vec3 extent = scene.bounds.diagonal();
  fit.shortestExtentUnits = double(std::min({extent.x, extent.y, extent.z})) / quantizer.unit();
  float farthest = 0;
  for (int a = 0; a < 3; ++a) farthest = std::max({farthest, std::fabs(scene.bounds.lo[a]), std::fabs(scene.bounds.hi[a])});
  fit.floatSpacingUnits = double(std::nextafter(farthest, kInfinity) - farthest) / quantizer.unit();
  // Thresholds: a shape a few hundred lattice units thin has lost the bits
  // that its other extents keep; float input coarser than half a lattice unit
  // means the lattice quantizes values already rounded more coarsely.
  constexpr double kThinUnits = 256, kCoarseFloatUnits = 0.5;
  if (fit.shortestExtentUnits < kThinUnits) {
    fit.warning = fmt::format("the scene's shortest extent spans only {:.1f} of the lattice's {} units: one uniform "
                              "lattice over a long, thin scene keeps few bits across it",
                              fit.shortestExtentUnits, fx::kPosMax + 1);
  } else if (fit.floatSpacingUnits > kCoarseFloatUnits) {
    fit.warning = fmt::format("float32 coordinates this far from the origin are {:.2f} lattice units apart: the "
                              "input, not the lattice, limits the shape",
                              fit.floatSpacingUnits);
  }
  return fit;
}

}  // namespace lancer::stress
