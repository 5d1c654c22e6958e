#include "effects/integrator.h"

#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

nlohmann::json IntegratorResult::toJson() const {
  nlohmann::json cls = nlohmann::json::object();
  for (const auto& [key, counts] : classes) cls[toString(key)] = {{"rays", counts.rays}, {"hits", counts.hits}};
  return {{"classes", cls}, {"wave_rays", waveRays}, {"self_hits", selfHits}};
}

std::vector<WaveRay> cameraWave(std::span<const Ray> cameraSamples, RayClass cls) {
  std::vector<WaveRay> wave(cameraSamples.size());
  for (size_t s = 0; s < cameraSamples.size(); ++s) {
    const Ray& ray = cameraSamples[s];
    if (!allFinite(ray.origin) || !allFinite(ray.dir)) {
      throw InputError(fmt::format("camera ray {}: NaN or infinite origin or direction", s));
    }
    if (ray.dir == glm::vec3(0.0f)) throw InputError(fmt::format("camera ray {}: zero direction", s));
    wave[s].ray = Ray{ray.origin, ray.dir, kInfinity};
    wave[s].cls = cls;
    wave[s].sample = uint32_t(s);
  }
  return wave;
}

void traceWaves(std::vector<WaveRay> wave, WaveTracer& tracer, IntegratorResult& out, const WaveAnswer& answer,
                const WaveProgress& progress) {
  std::vector<std::optional<Hit>> hits;
  std::vector<WaveRay> next;
  for (int generation = 0; !wave.empty(); ++generation) {
    hits.assign(wave.size(), std::nullopt);
    tracer.trace(generation, wave, hits);
    if (hits.size() != wave.size()) {
      throw std::logic_error(fmt::format("wave tracer answered {} of the {} rays of generation {}", hits.size(),
                                         wave.size(), generation));
    }
    out.waveRays.push_back(wave.size());
    next.clear();
    for (uint32_t k = 0; k < wave.size(); ++k) {
      const WaveRay& r = wave[k];
      const std::optional<Hit>& h = hits[k];
      IntegratorResult::ClassCounts& counts = out.classes[keyOf(r)];
      ++counts.rays;
      if (h) {
        ++counts.hits;
        if (!fromCamera(r.cls) && h->prim == r.originPrim && !(r.intoSolid && h->u == 1.0f)) ++out.selfHits;
      }
      answer(r, h, k, next);
    }
    if (progress) progress(generation, wave.size());
    wave.swap(next);
  }
}

double relativeMse(std::span<const glm::vec3> image, std::span<const glm::vec3> reference) {
  if (image.size() != reference.size()) {
    throw std::logic_error(fmt::format("relativeMse: {} samples against {}", image.size(), reference.size()));
  }
  double error = 0.0, energy = 0.0;
  for (size_t i = 0; i < image.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(image[i]) - glm::dvec3(reference[i]);
    error += glm::dot(d, d);
    energy += glm::dot(glm::dvec3(reference[i]), glm::dvec3(reference[i]));
  }
  return energy > 0.0 ? error / energy : error;
}

}  // namespace lancer
