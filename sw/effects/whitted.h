#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "common/png.h"
#include "effects/plan.h"
#include "effects/ray_class.h"
#include "common/ray.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace lancer {

// One ray of a wave, with what the loop needs to continue from its answer.
struct WaveRay {
  Ray ray;                         // scene space; shadow: tMax at the light (units of |dir|), else infinity
  RayClass cls = RayClass::Primary;
  bool anyHit = false;             // shadow rays: any hit on the segment answers
  uint32_t depth = 1;              // 1 = eye ray (SPD rule 7)
  uint32_t sample = 0;             // the camera sample (pixel or pixel corner) it contributes to
  glm::vec3 weight{1.0f};          // colour weight of its contribution
  // All but primary rays: the index of the ray in the previous wave whose hit spawned it, the
  // primitive it leaves, and the side of that primitive's geometric normal it leaves on (+1 front,
  // -1 back; a quadric's is effectsGeometricNormal(), effects/surface.h).
  uint32_t parent = UINT32_MAX;
  uint32_t originPrim = UINT32_MAX;
  int8_t side = 0;
  // The ray leaves a quadric into its solid (a refraction into a glass sphere, a reflection inside
  // it): the quadric's far side, a leaving hit (u = 1) on originPrim, is an answer, not a self-hit.
  bool intoSolid = false;
  // Shadow rays to an area light: the emitting triangle the segment ends on (else UINT32_MAX).
  uint32_t targetPrim = UINT32_MAX;
  // The path integrator: the ray's pass (--spp) of its camera sample, and
  // whether it left a mirror or glass (its hit's emission then counts: no
  // light sample could have found that light).
  uint32_t pass = 0;
  bool specular = false;
};

// The class a ray is counted under: bounces by their number (depth - 1).
inline ClassKey keyOf(const WaveRay& r) {
  return r.cls == RayClass::Bounce ? ClassKey(r.cls, uint16_t(r.depth - 1)) : ClassKey(r.cls);
}

// What traces a wave: the float reference (effects/ref_tracer.h) or a model of the hardware.
// Secondary rays start exactly on the surface they leave (origin = the hit point); keeping them
// from hitting it again (offset, t_min, exclusion of originPrim) is the tracer's business.
class WaveTracer {
 public:
  virtual ~WaveTracer() = default;
  // hits[k] answers rays[k]: closest hit, or for anyHit rays some hit on the segment (nullopt: none).
  // generation 0 is the primary wave; every ray of generation g+1 has its parent in generation g.
  virtual void trace(int generation, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) = 0;
};

// The counts of a Whitted run. The SPD counts (Readme.txt, "Database Analysis")
// are kept under their names there.
struct WhittedResult {
  struct ClassCounts {
    uint64_t rays = 0;
    uint64_t hits = 0;
  };
  std::array<ClassCounts, kWhittedClassCount> classes;
  uint64_t eyeHitRays = 0;          // primary rays that hit an object
  uint64_t reflectRays = 0;         // reflection rays spawned, those of total internal reflection included
  uint64_t refractRays = 0;         // SPD's count: refraction rays traced plus total internal reflections
  uint64_t refractionsTraced = 0;   // refraction rays spawned
  uint64_t totalInternalReflections = 0;
  uint64_t shadowRays = 0;
  uint64_t shadowRaysBlocked = 0;
  uint64_t selfHits = 0;            // secondary or shadow hits on their own originPrim but a quadric's
                                    // far side (must be 0)
  uint64_t opaqueBackHits = 0;      // hits on the back of an opaque triangle (shaded two-sided)
  std::vector<uint64_t> waveRays;   // rays of each generation
  std::vector<glm::vec3> samples;   // the colour of every camera sample, by sample id

  nlohmann::json toJson() const;
};

// The shading constants of the loop (NFF's Phong model; docs/effects.md).
struct WhittedShading {
  // Relative intensity of each light and of the ambient term, the SPD's
  // sqrt(n) / (2 n) for n lights (point, spot, directional and emissive triangles).
  static float lightIntensity(size_t lights);
};

// Called after each wave with its generation and size.
using WaveProgress = std::function<void(int generation, size_t rays)>;

// The classical Whitted loop of the SPD's Testing Procedures (docs/effects.md):
// `cameraSamples[s]` is the eye ray of sample s. Waves: the primary rays, then
// each generation's shadow and secondary rays together. Throws InputError if a
// camera ray is not finite or has a zero direction, or if the shadow rays of one
// wave could exceed 2^28 (camera samples x (lights + emissive triangles x light samples)).
WhittedResult traceWhitted(const Scene& scene, const EffectsPlan& plan, std::span<const Ray> cameraSamples,
                           WaveTracer& tracer, const WaveProgress& progress = {});

// The pixels of a run's samples, linear: Centers, one sample a pixel;
// Corners, (width + 1) x (height + 1) samples, each pixel the mean of its four
// corners. samplesToImage encodes them for the PNG.
std::vector<glm::vec3> samplesToPixels(std::span<const glm::vec3> samples, int width, int height, Sampling sampling);
Image samplesToImage(std::span<const glm::vec3> samples, int width, int height, Sampling sampling);

}  // namespace lancer
