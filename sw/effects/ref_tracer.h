#pragma once

#include <array>
#include <vector>

#include "effects/whitted.h"
#include "ref/accel.h"

namespace lancer {

// The float reference WaveTracer: every wave through one reference structure
// (any Accel; the CLI uses the BVH by default), closest hit for primary,
// reflection and refraction rays, any-hit for shadow rays.
//
// Secondary origins (docs/effects.md): a ray leaving triangle `originPrim`
// starts `offset()` along that triangle's unit geometric normal, on the side it
// leaves on (WaveRay::side), and a shadow ray's tMax shrinks by the distance
// the start moved along the ray; a ray leaving a quadric, along its normal at
// the origin (effectsGeometricNormal), the same way. The offset is relative to
// the scene: 1e-5 of its bounding diagonal, and never below 4e-6 of its largest
// coordinate (about 32 float ulps there). Behind the offset, a hit on
// originPrim is excluded: the ray is traced again from just beyond that hit
// (counted in excludedOriginHits()); but a ray into a quadric's solid
// (WaveRay::intoSolid) keeps a leaving hit on it, the quadric's far side. So
// the reference never reports a self-hit.
class RefWaveTracer final : public WaveTracer {
 public:
  // `scene` and `accel` must outlive the tracer.
  RefWaveTracer(const Scene& scene, const Accel& accel);

  void trace(int generation, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) override;

  float offset() const { return offset_; }
  // Traversal counters and host seconds of each ray class.
  const TraversalStats& stats(RayClass cls) const { return stats_[size_t(cls)]; }
  double seconds(RayClass cls) const { return seconds_[size_t(cls)]; }
  uint64_t excludedOriginHits() const { return excluded_; }

 private:
  std::optional<Hit> traceOne(const WaveRay& ray);

  const Scene& scene_;
  const Accel& accel_;
  float offset_;
  std::vector<glm::vec3> normals_;  // unit geometric normal of every triangle
  std::array<TraversalStats, kRayClassCount> stats_{};
  std::array<double, kRayClassCount> seconds_{};
  uint64_t excluded_ = 0;
};

}  // namespace lancer
