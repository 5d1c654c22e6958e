#include "effects/ao.h"

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "effects/sampler.h"
#include "effects/surface.h"

namespace lancer {

float AoOptions::distanceFor(const Scene& scene) const {
  return distance > 0.0f ? distance : 0.1f * glm::length(scene.bounds.diagonal());
}

nlohmann::json AoOptions::toJson(const Scene& scene) const {
  return {{"ao_rays", rays}, {"ao_distance", distanceFor(scene)}, {"seed", seed}};
}

void checkAoOptions(const AoOptions& options) {
  if (options.rays < 1 || options.rays > kMaxAoRays) {
    throw InputError(fmt::format("--ao-rays {}: must lie in 1..{}", options.rays, kMaxAoRays));
  }
  if (!std::isfinite(options.distance) || options.distance < 0.0f) {
    throw InputError(fmt::format("--ao-distance {}: must be a finite length >= 0 (0: a tenth of the scene's diagonal)",
                                 options.distance));
  }
}

IntegratorResult traceAo(const Scene& scene, const AoOptions& options, std::span<const Ray> cameraSamples,
                         WaveTracer& tracer, const WaveProgress& progress, uint32_t firstSample) {
  checkAoOptions(options);
  const Sampler sampler(options.seed);
  const float distance = options.distanceFor(scene);
  const glm::vec3 share(1.0f / float(options.rays));
  IntegratorResult out;
  out.samples.assign(cameraSamples.size(), glm::vec3(0.0f));
  const auto answer = [&](const WaveRay& r, const std::optional<Hit>& h, uint32_t k, std::vector<WaveRay>& next) {
    if (r.cls == RayClass::Ao) {
      if (!h) out.samples[r.sample] += r.weight;  // the segment reached its end
      return;
    }
    if (!h) {
      out.samples[r.sample] = glm::vec3(1.0f);  // the open sky occludes nothing
      return;
    }
    const SurfacePoint s = surfaceAt(scene, r.ray, *h);
    std::array<float, 4> draws{};  // one Philox evaluation serves two rays (dimensions 2i, 2i + 1)
    for (int i = 0; i < options.rays; ++i) {
      if (i % 2 == 0) draws = sampler.uniform4(firstSample + r.sample, /*pass=*/0, /*bounce=*/0, uint32_t(i / 2));
      const glm::vec2 u = i % 2 == 0 ? glm::vec2(draws[0], draws[1]) : glm::vec2(draws[2], draws[3]);
      const glm::vec3 dir = glm::normalize(aboutNormal(s.normal, cosineHemisphere(u)));
      WaveRay ao;
      ao.ray = Ray{s.point, dir, distance};
      ao.cls = RayClass::Ao;
      ao.anyHit = true;
      ao.depth = r.depth + 1;
      ao.sample = r.sample;
      ao.weight = share;
      ao.parent = k;
      ao.originPrim = h->prim;
      ao.side = s.sideOf(dir);
      ao.intoSolid = s.intoSolid(dir);
      next.push_back(ao);
    }
  };
  traceWaves(cameraWave(cameraSamples, RayClass::Camera), tracer, out, answer, progress);
  return out;
}

}  // namespace lancer
