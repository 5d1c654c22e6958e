#pragma once

#include <cstdint>
#include <span>

#include <nlohmann/json.hpp>

#include "effects/integrator.h"
#include "scene/scene.h"

namespace lancer {

// A unidirectional path tracer on the hardware's hits (lancer run
// --integrator path; docs/incoherent.md). Every camera sample traces `spp`
// paths; at each hit, next-event estimation sends one shadow ray to a light
// chosen uniformly (a point, spot or directional light, or a point of an
// emissive triangle), and the path goes on along a direction drawn from the
// material: cosine-weighted diffuse (kd), a modified-Phong glossy lobe about
// the mirror direction (ks, shine; a perfect mirror from shine >= 1000), or
// glass (T: Snell's law, total internal reflection as a mirror). From bounce
// `rrDepth` on, Russian roulette ends a path with probability 1 - min(0.95,
// its largest throughput channel). Every number comes from the counter-based
// sampler (effects/sampler.h) keyed by the camera sample, the pass, the
// bounce and the dimension: the same paths whatever the tracer, given the
// same hits. The scene's background is its environment light: a camera or
// bounce ray that meets nothing adds it (times the path's throughput).
// Lights (point, spot, directional) answer as the Whitted loop's do, without
// falloff; emissive triangles are radiance, sampled by area.
struct PathOptions {
  int spp = 1;        // paths a camera sample
  int maxDepth = 5;   // the camera ray has depth 1
  int rrDepth = 3;    // the first bounce Russian roulette may end a path at
  uint64_t seed = 1;  // the sampler's key

  nlohmann::json toJson() const;
};

inline constexpr int kMaxSpp = 65536;
inline constexpr int kMaxPathDepth = 64;
inline constexpr float kMirrorShine = 1000.0f;  // a Phong exponent this sharp is a mirror

// Throws InputError naming the option for --spp outside 1..kMaxSpp,
// --max-depth outside 1..kMaxPathDepth or --rr-depth below 1.
void checkPathOptions(const PathOptions& options);

// Waves: the camera rays of every pass (class Camera), then each bounce's
// shadow rays (Shadow) and continuation rays (Bounce, numbered by bounce),
// until no path goes on. A sample's colour is the mean of its paths'. Throws
// InputError for a scene nothing lights (no light, no emitter, a black
// background), or a camera wave of more than 2^24 rays.
// `cameraSamples` are the frame's samples from number `firstSample` on (a
// shard of it: lancer run --shard).
IntegratorResult tracePath(const Scene& scene, const PathOptions& options, std::span<const Ray> cameraSamples,
                           WaveTracer& tracer, const WaveProgress& progress = {}, uint32_t firstSample = 0);

}  // namespace lancer
