#pragma once

// What the integrators other than Whitted's share (docs/incoherent.md): their
// counts, the wave loop that feeds a WaveTracer, and the error of an image
// against its float reference.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "effects/whitted.h"

namespace lancer {

// The counts of a run: per class (bounces by number) the rays and their hits,
// the rays of every wave, the colour of every camera sample.
struct IntegratorResult {
  struct ClassCounts {
    uint64_t rays = 0;
    uint64_t hits = 0;
  };
  std::map<ClassKey, ClassCounts> classes;
  std::vector<uint64_t> waveRays;
  std::vector<glm::vec3> samples;
  uint64_t selfHits = 0;  // rays whose hit is the primitive they leave, but a quadric's far side (must be 0)

  nlohmann::json toJson() const;
};

// The first wave: every camera sample's ray, of class `cls`. Throws
// InputError naming the sample for a ray that is not finite or has no direction.
std::vector<WaveRay> cameraWave(std::span<const Ray> cameraSamples, RayClass cls);

// Called for every ray of a wave with its answer (nullopt: a miss) and its
// index in the wave; appends the rays it spawns to `next`.
using WaveAnswer = std::function<void(const WaveRay& ray, const std::optional<Hit>& hit, uint32_t index,
                                      std::vector<WaveRay>& next)>;

// The wave loop: traces `wave`, counts each ray under its class, hands each
// ray and its answer to `answer`, and goes on with what that spawned, until a
// wave spawns nothing. `progress` hears of every wave.
void traceWaves(std::vector<WaveRay> wave, WaveTracer& tracer, IntegratorResult& out, const WaveAnswer& answer,
                const WaveProgress& progress = {});

// The relative mean squared error of an image against its reference, over
// the samples' colours: sum |a - b|^2 / sum |b|^2 (0 for two black images).
double relativeMse(std::span<const glm::vec3> image, std::span<const glm::vec3> reference);

}  // namespace lancer
