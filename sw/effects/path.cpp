#include "effects/path.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "effects/lights.h"
#include "effects/sampler.h"
#include "effects/surface.h"

namespace lancer {

nlohmann::json PathOptions::toJson() const {
  return {{"spp", spp}, {"max_depth", maxDepth}, {"rr_depth", rrDepth}, {"seed", seed}};
}

void checkPathOptions(const PathOptions& o) {
  if (o.spp < 1 || o.spp > kMaxSpp) throw InputError(fmt::format("--spp {}: must lie in 1..{}", o.spp, kMaxSpp));
  if (o.maxDepth < 1 || o.maxDepth > kMaxPathDepth) {
    throw InputError(fmt::format("--max-depth {}: must lie in 1..{} for the path integrator", o.maxDepth, kMaxPathDepth));
  }
  if (o.rrDepth < 1) throw InputError(fmt::format("--rr-depth {}: must be 1 or more", o.rrDepth));
}

namespace {

constexpr float kTwoPi = 6.28318530717958647692f;
constexpr float kInvPi = 0.31830988618379067154f;
// Rays in one wave (a WaveRay is 80 bytes): the camera wave is samples x spp.
constexpr uint64_t kMaxWaveRays = uint64_t(1) << 24;

float largest(const glm::vec3& v) { return std::max({v.x, v.y, v.z}); }

// The integrator's state across waves: the scene's lights and the sampler.
class PathLoop {
 public:
  PathLoop(const Scene& scene, const PathOptions& options, IntegratorResult& out, uint32_t firstSample)
      : scene_(scene), options_(options), out_(out), sampler_(options.seed), emitters_(emittersOf(scene)),
        firstSample_(firstSample) {}

  // Something lights the scene: a light, an emitter, or the background.
  bool lit() const { return lightCount() != 0 || scene_.background != glm::vec3(0.0f); }

  void answer(const WaveRay& r, const std::optional<Hit>& h, uint32_t k, std::vector<WaveRay>& next) {
    if (r.cls == RayClass::Shadow) {
      if (!h) out_.samples[r.sample] += r.weight;  // the light arrives
      return;
    }
    if (!h) {
      out_.samples[r.sample] += r.weight * scene_.background;
      return;
    }
    const SurfacePoint s = surfaceAt(scene_, r.ray, *h);
    // Emission counts where no light sample could have taken it: seen from the
    // camera, or through a mirror or glass.
    if (s.front && (fromCamera(r.cls) || r.specular)) out_.samples[r.sample] += r.weight * s.material.emission;
    const uint32_t bounce = r.depth - 1;  // the camera ray's hit is bounce 0's
    const uint32_t sample = firstSample_ + r.sample;  // the frame's, whatever the shard
    const std::array<float, 4> u0 = sampler_.uniform4(sample, r.pass, bounce, 0);  // light, its point, lobe
    const std::array<float, 4> u1 = sampler_.uniform4(sample, r.pass, bounce, 1);  // direction, roulette
    sampleLight(r, s, *h, k, {u0[0], u0[1], u0[2]}, next);
    if (int(r.depth) < options_.maxDepth) continuePath(r, s, *h, k, u0[3], {u1[0], u1[1]}, u1[2], next);
  }

 private:
  size_t lightCount() const { return scene_.lights.size() + emitters_.size(); }

  // The lobes a light sample can meet (diffuse, glossy) at wi, times pi: the
  // response to a light of unit colour from wi, cos excluded.
  glm::vec3 response(const SurfacePoint& s, const glm::vec3& wi) const {
    const Material& m = s.material;
    glm::vec3 f = m.kd * m.diffuse;
    if (m.ks > 0.0f && m.shine < kMirrorShine) {
      const float cosAlpha = glm::dot(glm::reflect(s.dir, s.normal), wi);
      if (cosAlpha > 0.0f) f += glm::vec3(m.ks * 0.5f * (m.shine + 2.0f) * std::pow(cosAlpha, m.shine));
    }
    return f;
  }

  bool hasSmoothLobes(const Material& m) const { return m.kd > 0.0f || (m.ks > 0.0f && m.shine < kMirrorShine); }

  WaveRay child(const WaveRay& r, const SurfacePoint& s, const Hit& h, uint32_t k, RayClass cls, const Ray& ray,
                const glm::vec3& weight) const {
    WaveRay c;
    c.ray = ray;
    c.cls = cls;
    c.depth = r.depth + 1;
    c.sample = r.sample;
    c.pass = r.pass;
    c.weight = weight;
    c.parent = k;
    c.originPrim = h.prim;
    c.side = s.sideOf(ray.dir);
    c.intoSolid = s.intoSolid(ray.dir);
    return c;
  }

  // Next-event estimation: one light, chosen uniformly, through a shadow ray
  // carrying its contribution (divided by the choice's probability).
  void sampleLight(const WaveRay& r, const SurfacePoint& s, const Hit& h, uint32_t k, glm::vec3 u,
                   std::vector<WaveRay>& next) const {
    const size_t n = lightCount();
    if (n == 0 || !hasSmoothLobes(s.material)) return;
    const size_t pick = std::min(n - 1, size_t(u.x * float(n)));
    glm::vec3 dir, contribution;
    float distance;
    uint32_t target = UINT32_MAX;
    if (pick < scene_.lights.size()) {
      const std::optional<LightPath> p = pathToLight(scene_.lights[pick], s.point);
      if (!p) return;
      const float cosine = glm::dot(s.normal, p->dir);
      if (!(cosine > 0.0f)) return;
      dir = p->dir;
      distance = p->distance;
      contribution = p->color * response(s, dir) * cosine;
    } else {
      const Emitter& e = emitters_[pick - scene_.lights.size()];
      if (e.prim == h.prim) return;  // a lamp does not light itself
      const glm::vec3 toLight = pointOnTriangle(scene_.triangles[e.prim], {u.y, u.z}) - s.point;
      const float d = glm::length(toLight);
      if (!(d > 0.0f)) return;
      dir = toLight / d;
      const float cosine = glm::dot(s.normal, dir), cosEmitter = -glm::dot(e.normal, dir);
      if (!(cosine > 0.0f) || !(cosEmitter > 0.0f)) return;
      distance = d * (1.0f - 1e-4f);  // short of the lamp: its own triangle is no blocker
      target = e.prim;
      contribution = e.emission * response(s, dir) * kInvPi * cosine * cosEmitter * e.area / (d * d);
    }
    WaveRay shadow = child(r, s, h, k, RayClass::Shadow, Ray{s.point, dir, distance},
                           r.weight * contribution * float(n));
    shadow.anyHit = true;
    shadow.targetPrim = target;
    next.push_back(shadow);
  }

  // The continuation: a lobe chosen by its weight, a direction from it, the
  // throughput's update, Russian roulette.
  void continuePath(const WaveRay& r, const SurfacePoint& s, const Hit& h, uint32_t k, float uLobe, glm::vec2 uDir,
                    float uRoulette, std::vector<WaveRay>& next) const {
    const Material& m = s.material;
    const float meanDiffuse = (m.diffuse.x + m.diffuse.y + m.diffuse.z) / 3.0f;
    const float pd = m.kd * meanDiffuse, ps = m.ks, pt = m.transmittance;
    const float total = pd + ps + pt;
    if (!(total > 0.0f)) return;
    const float pick = uLobe * total;
    glm::vec3 dir, factor;
    bool specular = false;
    if (pick < pd) {
      dir = aboutNormal(s.normal, cosineHemisphere(uDir));
      factor = m.kd * m.diffuse * (total / pd);  // f cos / pdf = kd * diffuse
    } else if (pick < pd + ps) {
      const glm::vec3 mirror = glm::reflect(s.dir, s.normal);
      if (m.shine >= kMirrorShine) {
        dir = mirror;
        specular = true;
      } else {  // cos^shine about the mirror direction
        const float cosAlpha = std::pow(uDir.x, 1.0f / (m.shine + 1.0f));
        const float sinAlpha = std::sqrt(std::max(0.0f, 1.0f - cosAlpha * cosAlpha));
        const float phi = kTwoPi * uDir.y;
        dir = aboutNormal(mirror, {sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha});
      }
      const float cosine = glm::dot(dir, s.normal);
      if (!(cosine > 0.0f)) return;  // the lobe dips below the surface: absorbed
      factor = glm::vec3(specular ? total : (m.shine + 2.0f) / (m.shine + 1.0f) * cosine * total);
    } else {  // glass: Snell's law, entering through the front
      const float eta = s.front ? 1.0f / m.ior : m.ior;
      const float cosIn = glm::dot(-s.dir, s.normal);
      const float k2 = 1.0f - eta * eta * (1.0f - cosIn * cosIn);
      dir = k2 < 0.0f ? glm::reflect(s.dir, s.normal) : eta * s.dir + (eta * cosIn - std::sqrt(k2)) * s.normal;
      specular = true;
      factor = glm::vec3(total);
    }
    glm::vec3 weight = r.weight * factor;
    if (int(r.depth) >= options_.rrDepth) {  // the new ray is bounce r.depth
      const float survive = std::min(0.95f, largest(weight) * float(options_.spp));
      if (!(uRoulette < survive)) return;
      weight /= survive;
    }
    WaveRay c = child(r, s, h, k, RayClass::Bounce, Ray{s.point, glm::normalize(dir), kInfinity}, weight);
    c.specular = specular;
    next.push_back(c);
  }

  const Scene& scene_;
  const PathOptions& options_;
  IntegratorResult& out_;
  Sampler sampler_;
  std::vector<Emitter> emitters_;
  uint32_t firstSample_;
};

}  // namespace

IntegratorResult tracePath(const Scene& scene, const PathOptions& options, std::span<const Ray> cameraSamples,
                           WaveTracer& tracer, const WaveProgress& progress, uint32_t firstSample) {
  checkPathOptions(options);
  IntegratorResult out;
  PathLoop loop(scene, options, out, firstSample);
  if (!loop.lit()) {
    throw InputError(fmt::format("{}: nothing lights the scene for the path integrator (no lights, no emissive "
                                 "triangles and a black background, which is its environment light)",
                                 scene.name));
  }
  if (uint64_t(cameraSamples.size()) * uint64_t(options.spp) > kMaxWaveRays) {
    throw InputError(fmt::format("--spp {}: {} camera samples x {} paths is more than {} rays a wave: lower --spp or "
                                 "the resolution",
                                 options.spp, cameraSamples.size(), options.spp, kMaxWaveRays));
  }
  out.samples.assign(cameraSamples.size(), glm::vec3(0.0f));
  const std::vector<WaveRay> camera = cameraWave(cameraSamples, RayClass::Camera);
  std::vector<WaveRay> wave;
  wave.reserve(camera.size() * size_t(options.spp));
  for (int pass = 0; pass < options.spp; ++pass) {
    for (WaveRay r : camera) {
      r.pass = uint32_t(pass);
      r.weight = glm::vec3(1.0f / float(options.spp));
      wave.push_back(r);
    }
  }
  traceWaves(std::move(wave), tracer, out,
             [&](const WaveRay& r, const std::optional<Hit>& h, uint32_t k, std::vector<WaveRay>& next) {
               loop.answer(r, h, k, next);
             },
             progress);
  return out;
}

}  // namespace lancer
