#include "effects/ref_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "effects/surface.h"

namespace lancer {

RefWaveTracer::RefWaveTracer(const Scene& scene, const Accel& accel) : scene_(scene), accel_(accel) {
  const glm::vec3 lo = glm::abs(scene.bounds.lo), hi = glm::abs(scene.bounds.hi);
  const float largest = std::max({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z});
  offset_ = std::max(1e-5f * glm::length(scene.bounds.diagonal()), 4e-6f * largest);
  if (!(offset_ > 0.0f)) offset_ = 1e-6f;
  normals_.reserve(scene.size());
  for (const Triangle& t : scene.triangles) {
    const glm::vec3 c = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
    const float l = glm::length(c);
    normals_.push_back(l > 0.0f ? c / l : glm::vec3(0.0f));
  }
}

std::optional<Hit> RefWaveTracer::traceOne(const WaveRay& wr) {
  TraversalStats& stats = stats_[size_t(wr.cls)];
  Ray ray = wr.ray;
  if (wr.originPrim >= scene_.primitiveCount()) return accel_.intersect(ray, &stats);
  const glm::vec3 dir = glm::normalize(ray.dir);
  // A quadric's normal at the origin, the point the ray leaves (its surface to rounding).
  const glm::vec3 normal = scene_.isQuadric(wr.originPrim) ? effectsGeometricNormal(scene_, wr.originPrim, ray.origin)
                                                           : normals_[wr.originPrim];
  const glm::vec3 shift = float(wr.side) * offset_ * normal;
  ray.origin += shift;
  // tMax is in units of |dir|; the start moved dot(shift, dir) along the ray.
  if (std::isfinite(ray.tMax)) ray.tMax -= glm::dot(shift, dir) / glm::length(ray.dir);
  if (!(ray.tMax > 0.0f)) return std::nullopt;
  if (wr.anyHit && !accel_.intersectP(ray)) return std::nullopt;
  // A closest hit on the primitive the ray leaves is excluded by starting again
  // past it; but a ray into a quadric's solid has its far side (a leaving hit) ahead.
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::optional<Hit> hit = accel_.intersect(ray, &stats);
    if (!hit || hit->prim != wr.originPrim || (wr.intoSolid && hit->u == 1.0f)) return hit;
    ++excluded_;
    const float skip = hit->t + offset_ / glm::length(ray.dir);
    ray.origin += skip * ray.dir;
    if (std::isfinite(ray.tMax)) {
      ray.tMax -= skip;
      if (!(ray.tMax > 0.0f)) return std::nullopt;
    }
  }
  return std::nullopt;
}

void RefWaveTracer::trace(int, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) {
  hits.assign(rays.size(), std::nullopt);
  // Rays of one class run together so each class's seconds are its own.
  for (int cls = 0; cls < kRayClassCount; ++cls) {
    const auto start = std::chrono::steady_clock::now();
    bool any = false;
    for (size_t k = 0; k < rays.size(); ++k) {
      if (int(rays[k].cls) != cls) continue;
      any = true;
      hits[k] = traceOne(rays[k]);
    }
    if (any) seconds_[size_t(cls)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

}  // namespace lancer
