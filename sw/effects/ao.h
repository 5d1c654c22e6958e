#pragma once

#include <cstdint>
#include <span>

#include <nlohmann/json.hpp>

#include "effects/integrator.h"
#include "scene/scene.h"

namespace lancer {

// Ambient occlusion (lancer run --integrator ao; docs/incoherent.md): from
// every camera ray's hit, `rays` occlusion segments of length `distance`
// (scene units), cosine-distributed about the shading normal, traced as
// any-hit rays; a sample's value is the share of them that reach their end
// unblocked (a camera ray that meets nothing: 1, the open sky).
struct AoOptions {
  int rays = 16;
  float distance = 0.0f;  // 0: a tenth of the scene's bounding-box diagonal
  uint64_t seed = 1;      // the sampler's key

  // The segment length for `scene`: `distance`, or its default.
  float distanceFor(const Scene& scene) const;
  nlohmann::json toJson(const Scene& scene) const;
};

inline constexpr int kMaxAoRays = 4096;

// Throws InputError naming the option for --ao-rays outside 1..kMaxAoRays or a
// negative or non-finite --ao-distance.
void checkAoOptions(const AoOptions& options);

// Two waves: the camera rays (class Camera), then the occlusion rays of
// their hits (class Ao), drawn from the counter-based sampler (effects/sampler.h)
// keyed by the camera sample and the ray's index: the same rays whatever the
// tracer, given the same hits. `cameraSamples` are the frame's samples from
// number `firstSample` on (a shard of it: lancer run --shard).
IntegratorResult traceAo(const Scene& scene, const AoOptions& options, std::span<const Ray> cameraSamples,
                         WaveTracer& tracer, const WaveProgress& progress = {}, uint32_t firstSample = 0);

}  // namespace lancer
