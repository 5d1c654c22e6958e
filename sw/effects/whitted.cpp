#include "effects/whitted.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "effects/integrator.h"
#include "effects/lights.h"
#include "effects/surface.h"

namespace lancer {

float WhittedShading::lightIntensity(size_t lights) {
  // The SPD's suggestion; with no light at all the ambient term keeps one light's share.
  const double n = double(lights ? lights : 1);
  return float(std::sqrt(n) / (2.0 * n));
}

namespace {

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Two uniform numbers in [0, 1) from a key: the stratified jitter of one area-light sample.
glm::vec2 jitter(uint64_t key) {
  const uint64_t h = splitmix64(key);
  return {float(h >> 40) * 0x1.0p-24f, float((h >> 16) & 0xFFFFFF) * 0x1.0p-24f};
}

class Loop {
 public:
  Loop(const Scene& scene, const EffectsPlan& plan, WhittedResult& result)
      : scene_(scene), plan_(plan), out_(result), emitters_(emittersOf(scene)) {
    intensity_ = WhittedShading::lightIntensity(scene.lights.size() + emitters_.size());
  }

  // Spawns into `next` what the hit of ray `k` of the current wave calls for, and adds its local colour.
  void shade(const WaveRay& r, const Hit& h, uint32_t k, std::vector<WaveRay>& next);

 private:
  // A hit as shading sees it: the point and the normals, the ray and its wave index.
  struct Surface : SurfacePoint {
    const WaveRay& ray;
    const Hit& hit;
    uint32_t index;  // of the ray in its wave
  };
  Surface surfaceAt(const WaveRay& r, const Hit& h, uint32_t k) const;
  void addLocalTerms(const Surface& s);
  void lightByLights(const Surface& s, std::vector<WaveRay>& next);
  void lightByEmitters(const Surface& s, std::vector<WaveRay>& next);
  void spawnSecondary(const Surface& s, std::vector<WaveRay>& next);
  // A ray spawned from this hit, with what every child of it shares.
  WaveRay child(const Surface& s, RayClass cls, const Ray& ray, const glm::vec3& weight) const;
  // A light's contribution from direction `dir`: a shadow ray to it, or the
  // light itself where the plan has no shadows.
  void light(const Surface& s, const glm::vec3& contribution, const glm::vec3& dir, float tMax, uint32_t emitter,
             std::vector<WaveRay>& next);
  glm::vec3 phong(const Material& m, const glm::vec3& n, const glm::vec3& toLight, const glm::vec3& toEye,
                  float cosine) const {
    glm::vec3 c = m.kd * m.diffuse * cosine;
    if (m.ks > 0.0f) {  // SPD rule 4: highlights on surfaces with a reflective component
      const glm::vec3 mirror = glm::reflect(-toLight, n);
      const float rv = std::max(0.0f, glm::dot(mirror, toEye));
      c += glm::vec3(m.ks * std::pow(rv, m.shine));
    }
    return c;
  }

  const Scene& scene_;
  const EffectsPlan& plan_;
  WhittedResult& out_;
  std::vector<Emitter> emitters_;
  float intensity_ = 0.5f;
};

void Loop::shade(const WaveRay& r, const Hit& h, uint32_t k, std::vector<WaveRay>& next) {
  const Surface s = surfaceAt(r, h, k);
  addLocalTerms(s);
  lightByLights(s, next);
  lightByEmitters(s, next);
  // Secondary rays (SPD rules 7 to 9): none from a ray already at the depth limit.
  if (int(r.depth) < plan_.maxDepth) spawnSecondary(s, next);
}

Loop::Surface Loop::surfaceAt(const WaveRay& r, const Hit& h, uint32_t k) const {
  // An opaque triangle hit from behind is shaded as if two-sided: SPD rule 2
  // allows one-sided opaque primitives, and in its closed scenes no eye ray meets a back.
  return {lancer::surfaceAt(scene_, r.ray, h), r, h, k};
}

// Ambient for every object (as the SPD suggests), and emission seen from the front.
void Loop::addLocalTerms(const Surface& s) {
  const Material& m = s.material;
  if (!s.front && !(m.transmittance > 0.0f)) ++out_.opaqueBackHits;
  glm::vec3 local = intensity_ * m.kd * m.diffuse;
  if (s.front) local += m.emission;
  out_.samples[s.ray.sample] += s.ray.weight * local;
}

WaveRay Loop::child(const Surface& s, RayClass cls, const Ray& ray, const glm::vec3& weight) const {
  WaveRay c;
  c.ray = ray;
  c.cls = cls;
  c.depth = s.ray.depth + 1;
  c.sample = s.ray.sample;
  c.weight = s.ray.weight * weight;
  c.parent = s.index;
  c.originPrim = s.hit.prim;
  c.side = s.sideOf(ray.dir);
  c.intoSolid = s.intoSolid(ray.dir);
  return c;
}

void Loop::light(const Surface& s, const glm::vec3& contribution, const glm::vec3& dir, float tMax, uint32_t emitter,
                 std::vector<WaveRay>& next) {
  if (!plan_.has(RayClass::Shadow)) {  // --effects without shadow: the light reaches every surface facing it
    out_.samples[s.ray.sample] += s.ray.weight * contribution;
    return;
  }
  WaveRay shadow = child(s, RayClass::Shadow, Ray{s.point, dir, tMax}, contribution);
  shadow.anyHit = true;
  shadow.targetPrim = emitter;
  next.push_back(shadow);
  ++out_.shadowRays;
}

// Point, spot and directional lights: one shadow ray each, none when the
// shading normal faces away from the light (SPD rule 10, transmitters too).
void Loop::lightByLights(const Surface& s, std::vector<WaveRay>& next) {
  for (const Light& l : scene_.lights) {
    const std::optional<LightPath> p = pathToLight(l, s.point);  // none outside a spot's cone: no ray
    if (!p) continue;
    const float cosine = glm::dot(s.normal, p->dir);
    if (!(cosine > 0.0f)) continue;
    light(s, intensity_ * p->color * phong(s.material, s.normal, p->dir, -s.dir, cosine), p->dir, p->distance,
          UINT32_MAX, next);
  }
}

// Area lights: --light-samples rays per emissive triangle, stratified over
// it and jittered by a hash of (sample, wave index, emitter, stratum).
void Loop::lightByEmitters(const Surface& s, std::vector<WaveRay>& next) {
  const int samples = plan_.lightSamples;
  const int cols = int(std::ceil(std::sqrt(double(samples))));
  const int rows = (samples + cols - 1) / cols;
  for (const Emitter& e : emitters_) {
    if (e.prim == s.hit.prim) continue;  // a lamp does not light itself
    const Triangle& et = scene_.triangles[e.prim];
    for (int i = 0; i < samples; ++i) {
      const uint64_t key =
          splitmix64((uint64_t(s.ray.sample) << 32) ^ s.index) ^ (uint64_t(e.prim) << 20) ^ uint64_t(i);
      const glm::vec2 xi = jitter(key);
      const float a = (float(i % cols) + xi.x) / float(cols), b = (float(i / cols) + xi.y) / float(rows);
      const glm::vec3 q = pointOnTriangle(et, {a, b});
      const glm::vec3 toLight = q - s.point;
      const float dist = glm::length(toLight);
      if (!(dist > 0.0f)) continue;
      const glm::vec3 dir = toLight / dist;
      const float cosine = glm::dot(s.normal, dir);
      const float cosEmitter = -glm::dot(e.normal, dir);
      if (!(cosine > 0.0f) || !(cosEmitter > 0.0f)) continue;  // facing away, or behind the lamp
      const float solid = cosEmitter * e.area / (dist * dist * float(samples));
      // Stop just short of the lamp so its own triangle does not count as a blocker.
      light(s, intensity_ * solid * e.emission * phong(s.material, s.normal, dir, -s.dir, cosine), dir,
            dist * (1.0f - 1e-4f), e.prim, next);
    }
  }
}

// Refraction (Snell's law) and reflection, as the plan has them.
void Loop::spawnSecondary(const Surface& s, std::vector<WaveRay>& next) {
  const Material& m = s.material;
  const glm::vec3& n = s.normal;
  const auto spawn = [&](RayClass cls, const glm::vec3& dir, const glm::vec3& weight) {
    next.push_back(child(s, cls, Ray{s.point, glm::normalize(dir), kInfinity}, weight));
  };
  const bool transmitter = m.transmittance > 0.0f;
  const float cosIn = glm::dot(-s.dir, n);
  bool totalInternal = false;
  if (transmitter && plan_.has(RayClass::Refraction)) {
    // Entering through the front, leaving through the back.
    const float eta = s.front ? 1.0f / m.ior : m.ior;
    const float k2 = 1.0f - eta * eta * (1.0f - cosIn * cosIn);
    ++out_.refractRays;  // the SPD counts total internal reflections among refractions
    if (k2 < 0.0f) {
      totalInternal = true;
      ++out_.totalInternalReflections;
    } else {
      spawn(RayClass::Refraction, eta * s.dir + (eta * cosIn - std::sqrt(k2)) * n, glm::vec3(m.transmittance));
      ++out_.refractionsTraced;
    }
  }
  if ((m.ks > 0.0f || transmitter) && plan_.has(RayClass::Reflection)) {
    // Every reflective surface and every transmitter reflects (rule 8); under
    // total internal reflection the transmitted share is reflected too.
    spawn(RayClass::Reflection, s.dir + 2.0f * cosIn * n, glm::vec3(m.ks + (totalInternal ? m.transmittance : 0.0f)));
    ++out_.reflectRays;
  }
}

}  // namespace

WhittedResult traceWhitted(const Scene& scene, const EffectsPlan& plan, std::span<const Ray> cameraSamples,
                           WaveTracer& tracer, const WaveProgress& progress) {
  // Every hit may spawn a shadow ray per light and per area-light sample: refuse
  // a run whose waves could outgrow memory rather than fail in the middle of it.
  constexpr uint64_t kMaxWaveRays = uint64_t(1) << 28;
  const uint64_t perHit = scene.lights.size() + uint64_t(plan.emissiveTriangles) * uint64_t(plan.lightSamples);
  if (plan.has(RayClass::Shadow) && perHit > kMaxWaveRays / std::max<uint64_t>(cameraSamples.size(), 1)) {
    throw InputError(fmt::format(
        "{} camera samples x {} shadow rays a hit ({} lights, {} emissive triangles x --light-samples {}) could "
        "make a wave of more than {} rays: lower --light-samples or the resolution, or leave shadows out with --effects",
        cameraSamples.size(), perHit, scene.lights.size(), plan.emissiveTriangles, plan.lightSamples, kMaxWaveRays));
  }
  WhittedResult out;
  out.samples.assign(cameraSamples.size(), glm::vec3(0.0f));
  Loop loop(scene, plan, out);
  IntegratorResult waves;
  const auto answer = [&](const WaveRay& r, const std::optional<Hit>& h, uint32_t k, std::vector<WaveRay>& next) {
    if (!h) {
      out.samples[r.sample] += r.cls == RayClass::Shadow ? r.weight : r.weight * scene.background;  // a light seen
      return;
    }
    if (h->prim >= scene.primitiveCount()) {
      throw std::logic_error(
          fmt::format("wave tracer: ray {} hit primitive {} of {}", k, h->prim, scene.primitiveCount()));
    }
    if (r.cls == RayClass::Shadow) {
      ++out.shadowRaysBlocked;
      return;
    }
    if (r.cls == RayClass::Primary) ++out.eyeHitRays;
    loop.shade(r, *h, k, next);
  };
  traceWaves(cameraWave(cameraSamples, RayClass::Primary), tracer, waves, answer, progress);
  for (const auto& [key, counts] : waves.classes) out.classes[size_t(key.cls)] = {counts.rays, counts.hits};
  out.waveRays = std::move(waves.waveRays);
  out.selfHits = waves.selfHits;
  return out;
}

std::vector<glm::vec3> samplesToPixels(std::span<const glm::vec3> samples, int width, int height, Sampling sampling) {
  const size_t expected = sampling == Sampling::Centers ? size_t(width) * size_t(height)
                                                        : size_t(width + 1) * size_t(height + 1);
  if (samples.size() != expected) {
    throw std::logic_error(fmt::format("{} samples for a {}x{} image sampled at {}", samples.size(), width, height,
                                       toString(sampling)));
  }
  if (sampling == Sampling::Centers) return {samples.begin(), samples.end()};
  std::vector<glm::vec3> pixels(size_t(width) * size_t(height));
  const size_t row = size_t(width) + 1;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t at = size_t(y) * row + size_t(x);
      pixels[size_t(y) * size_t(width) + size_t(x)] =
          0.25f * (samples[at] + samples[at + 1] + samples[at + row] + samples[at + row + 1]);
    }
  }
  return pixels;
}

Image samplesToImage(std::span<const glm::vec3> samples, int width, int height, Sampling sampling) {
  const std::vector<glm::vec3> pixels = samplesToPixels(samples, width, height, sampling);
  Image image(width, height);
  for (size_t p = 0; p < pixels.size(); ++p) image.set(p, pixels[p].r, pixels[p].g, pixels[p].b);
  return image;
}

nlohmann::json WhittedResult::toJson() const {
  nlohmann::json cls = nlohmann::json::object();
  for (int c = 0; c < kWhittedClassCount; ++c) {
    cls[std::string(toString(RayClass(c)))] = {{"rays", classes[c].rays}, {"hits", classes[c].hits}};
  }
  return {{"classes", cls},
          {"eye_hit_rays", eyeHitRays},
          {"reflect_rays", reflectRays},
          {"refract_rays", refractRays},
          {"refraction_rays_traced", refractionsTraced},
          {"total_internal_reflections", totalInternalReflections},
          {"shadow_rays", shadowRays},
          {"shadow_rays_blocked", shadowRaysBlocked},
          {"self_hits", selfHits},
          {"opaque_back_hits", opaqueBackHits},
          {"wave_rays", waveRays}};
}

}  // namespace lancer
