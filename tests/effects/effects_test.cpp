// The effects of issue 12 (sw/effects/): the plan a scene calls for, the SPD's
// Whitted loop rule by rule on small NFF scenes of our own (tests/data/), the
// wave contract every WaveTracer sees, the float reference tracer's secondary
// origins, corner sampling, and Lancer's SPD tetra against the SPD's table.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "common/error.h"
#include "effects/plan.h"
#include "effects/ref_tracer.h"
#include "effects/surface.h"
#include "effects/whitted.h"
#include "ref/bvh.h"
#include "scene/camera.h"
#include "scene/nff.h"
#include "scene/spd.h"
#include "support/mixed_scenes.h"

namespace lancer {
namespace {

const std::string kData = LANCER_TEST_DATA;

Scene load(const std::string& name) { return loadScene(kData + "/" + name); }

// Wraps the reference tracer and keeps every wave it was given, with its answers.
class RecordingTracer final : public WaveTracer {
 public:
  RecordingTracer(const Scene& scene) : bvh_(scene, AccelOptions{}), ref_(scene, bvh_) {}
  void trace(int generation, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) override {
    EXPECT_EQ(size_t(generation), waves.size());
    ref_.trace(generation, rays, hits);
    waves.emplace_back(rays.begin(), rays.end());
    answers.push_back(hits);
  }
  const RefWaveTracer& ref() const { return ref_; }
  std::vector<std::vector<WaveRay>> waves;
  std::vector<std::vector<std::optional<Hit>>> answers;

 private:
  Bvh bvh_;
  RefWaveTracer ref_;
};

struct WhittedRun {
  EffectsPlan plan;
  WhittedResult result;
};

// The scene's own camera at its own resolution.
std::vector<Ray> cameraRays(const Scene& scene, Sampling sampling = Sampling::Centers) {
  CameraOptions options;
  options.width = scene.view && scene.view->width ? scene.view->width : 16;
  options.height = scene.view && scene.view->height ? scene.view->height : 16;
  return frameScene(scene, options).generateRays(sampling);
}

WhittedRun runWhitted(const Scene& scene, RecordingTracer& tracer, const EffectsOptions& options = {},
               std::span<const Ray> rays = {}) {
  WhittedRun run{planEffects(scene, options), {}};
  const std::vector<Ray> camera = rays.empty() ? cameraRays(scene) : std::vector<Ray>(rays.begin(), rays.end());
  run.result = traceWhitted(scene, run.plan, camera, tracer);
  return run;
}

const WhittedResult::ClassCounts& counts(const WhittedResult& r, RayClass c) { return r.classes[size_t(c)]; }

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// ---- The plan ------------------------------------------------------------------------

TEST(EffectsPlan, SpheresCallForEveryClassAndSayWhy) {
  const Scene scene = load("spheres.nff");
  const EffectsPlan plan = planEffects(scene, {});
  for (const RayClass c : {RayClass::Primary, RayClass::Shadow, RayClass::Reflection, RayClass::Refraction}) {
    EXPECT_TRUE(plan.has(c)) << toString(c);
  }
  const auto& shadow = plan.classes[size_t(RayClass::Shadow)].reasons;
  ASSERT_EQ(shadow.size(), 2u);
  EXPECT_NE(shadow[0].find("point light l@"), std::string::npos) << shadow[0];
  const auto& reflection = plan.classes[size_t(RayClass::Reflection)].reasons;
  ASSERT_EQ(reflection.size(), 2u);  // the mirror's Ks and the glass's Ks (the glass reflects anyway)
  EXPECT_NE(reflection[0].find("Ks 0.7"), std::string::npos) << reflection[0];
  const auto& refraction = plan.classes[size_t(RayClass::Refraction)].reasons;
  ASSERT_EQ(refraction.size(), 1u);
  EXPECT_NE(refraction[0].find("T 0.9, index of refraction 1.5"), std::string::npos) << refraction[0];
  const std::string text = plan.describe();
  EXPECT_NE(text.find("refraction yes"), std::string::npos) << text;
  const nlohmann::json j = plan.toJson();
  EXPECT_EQ(j["max_depth"], 5);
  EXPECT_EQ(j["classes"]["refraction"]["enabled"], true);
  EXPECT_EQ(j["lights"], 2);
}

TEST(EffectsPlan, TransmitterWithoutKsStillCallsForReflection) {
  std::istringstream in("l 0 5 0\nf 1 1 1 0.5 0 0 0.8 1.4\ns 0 0 0 1\n");
  const EffectsPlan plan = planEffects(readNff(in, "t.nff"), {});
  EXPECT_TRUE(plan.has(RayClass::Reflection));
  EXPECT_NE(plan.classes[size_t(RayClass::Reflection)].reasons[0].find("transmitters reflect"), std::string::npos);
}

TEST(EffectsPlan, OnlyWhatTheSceneHas) {
  const EffectsPlan tetra = planEffects(makeSpdScene("tetra"), {});
  EXPECT_TRUE(tetra.has(RayClass::Primary));
  EXPECT_TRUE(tetra.has(RayClass::Shadow));
  EXPECT_FALSE(tetra.has(RayClass::Reflection));
  EXPECT_FALSE(tetra.has(RayClass::Refraction));
  EXPECT_NE(tetra.describe().find("no material has Ks > 0 or T > 0"), std::string::npos);

  const EffectsPlan dark = planEffects(load("spheres_no_lights.nff"), {});
  EXPECT_FALSE(dark.has(RayClass::Shadow));
  EXPECT_TRUE(dark.has(RayClass::Reflection));

  // The Cornell box's lamp is an area light (beside its point light).
  const EffectsPlan cornell = planEffects(loadScene("builtin:cornell"), {{}, 5, 3});
  EXPECT_TRUE(cornell.has(RayClass::Shadow));
  EXPECT_EQ(cornell.emissiveTriangles, 2u);
  const std::vector<std::string>& cornellShadow = cornell.classes[size_t(RayClass::Shadow)].reasons;
  EXPECT_TRUE(std::any_of(cornellShadow.begin(), cornellShadow.end(),
                          [](const std::string& r) { return r.find("2 emissive triangles") != std::string::npos; }))
      << cornell.describe();
}

TEST(EffectsPlan, RestrictionAndDepth) {
  const Scene scene = load("spheres.nff");
  const EffectsPlan shadowOnly = planEffects(scene, {{"shadow"}, 5, 1});
  EXPECT_TRUE(shadowOnly.has(RayClass::Primary));  // always
  EXPECT_TRUE(shadowOnly.has(RayClass::Shadow));
  EXPECT_FALSE(shadowOnly.has(RayClass::Reflection));
  EXPECT_TRUE(shadowOnly.classes[size_t(RayClass::Reflection)].calledFor);
  EXPECT_NE(shadowOnly.describe().find("[off: not in --effects]"), std::string::npos);

  const EffectsPlan eyeOnly = planEffects(scene, {{}, 1, 1});
  EXPECT_FALSE(eyeOnly.has(RayClass::Reflection));
  EXPECT_FALSE(eyeOnly.has(RayClass::Refraction));
  EXPECT_TRUE(eyeOnly.has(RayClass::Shadow));
}

TEST(EffectsPlan, BadOptionsNameTheOption) {
  const Scene scene = load("spheres.nff");
  EXPECT_NE(errorOf([&] { planEffects(scene, {{"shadow", "glow"}, 5, 1}); }).find("--effects: unknown effect 'glow'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { planEffects(scene, {{}, 0, 1}); }).find("--max-depth 0 must be >= 1"), std::string::npos);
  EXPECT_NE(errorOf([&] { planEffects(scene, {{}, 5, 0}); }).find("--light-samples 0 must be >= 1"),
            std::string::npos);
  EXPECT_NE(errorOf([] { parseSampling("diagonal"); }).find("--sampling diagonal"), std::string::npos);
}

// ---- The loop, rule by rule ----------------------------------------------------------------

// Every ray of wave g+1 names its parent in wave g, the primitive that parent hit,
// and the side of its geometric normal it leaves on (a quadric's:
// effectsGeometricNormal, and whether it goes into its solid); the counts add up.
void expectContract(const Scene& scene, const RecordingTracer& t, const WhittedResult& r, int maxDepth) {
  uint64_t byClass[kWhittedClassCount] = {};
  for (size_t g = 0; g < t.waves.size(); ++g) {
    for (size_t k = 0; k < t.waves[g].size(); ++k) {
      const WaveRay& w = t.waves[g][k];
      ++byClass[size_t(w.cls)];
      EXPECT_LE(w.depth, uint32_t(maxDepth + 1));
      if (g == 0) {
        EXPECT_EQ(w.cls, RayClass::Primary);
        EXPECT_EQ(w.parent, UINT32_MAX);
        EXPECT_EQ(w.depth, 1u);
        continue;
      }
      EXPECT_NE(w.cls, RayClass::Primary);
      ASSERT_LT(w.parent, t.waves[g - 1].size());
      const WaveRay& parent = t.waves[g - 1][w.parent];
      const auto& parentHit = t.answers[g - 1][w.parent];
      ASSERT_TRUE(parentHit.has_value());
      EXPECT_NE(parent.cls, RayClass::Shadow);
      EXPECT_EQ(w.originPrim, parentHit->prim);
      EXPECT_EQ(w.sample, parent.sample);
      EXPECT_EQ(w.depth, parent.depth + 1);
      EXPECT_EQ(w.anyHit, w.cls == RayClass::Shadow);
      float s = 0.0f;
      if (scene.isQuadric(w.originPrim)) {
        s = glm::dot(effectsGeometricNormal(scene, w.originPrim, w.ray.origin), w.ray.dir);
        const bool inside = scene.quadricOf(w.originPrim).insideVisible();
        EXPECT_EQ(w.intoSolid, inside ? s > 0.0f : s < 0.0f);
      } else {
        const Triangle& tri = scene.triangles[w.originPrim];
        s = glm::dot(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0), w.ray.dir);
        EXPECT_FALSE(w.intoSolid);
      }
      if (s != 0.0f) {
        EXPECT_EQ(w.side, s > 0 ? 1 : -1);
      }
      if (w.cls == RayClass::Shadow) {
        EXPECT_TRUE(std::isfinite(w.ray.tMax));
      } else {
        EXPECT_EQ(w.ray.tMax, kInfinity);
        EXPECT_LT(parent.depth, uint32_t(maxDepth));
      }
    }
  }
  EXPECT_EQ(r.selfHits, 0u);
  EXPECT_EQ(byClass[size_t(RayClass::Shadow)], r.shadowRays);
  EXPECT_EQ(byClass[size_t(RayClass::Reflection)], r.reflectRays);
  EXPECT_EQ(byClass[size_t(RayClass::Refraction)], r.refractionsTraced);
  EXPECT_EQ(r.refractRays, r.refractionsTraced + r.totalInternalReflections);
  EXPECT_EQ(counts(r, RayClass::Shadow).hits, r.shadowRaysBlocked);
  EXPECT_EQ(counts(r, RayClass::Primary).hits, r.eyeHitRays);
  EXPECT_EQ(r.waveRays.size(), t.waves.size());
}

TEST(Whitted, SpheresSpawnEveryClassByTheContract) {
  const Scene scene = load("spheres.nff");
  RecordingTracer tracer(scene);
  const WhittedRun run = runWhitted(scene, tracer);
  const WhittedResult& r = run.result;
  expectContract(scene, tracer, r, 5);
  EXPECT_EQ(r.eyeHitRays + counts(r, RayClass::Primary).rays - counts(r, RayClass::Primary).hits, 48u * 48u);
  EXPECT_GT(r.shadowRays, 0u);
  EXPECT_GT(r.shadowRaysBlocked, 0u);  // the spheres shadow the floor
  EXPECT_GT(r.reflectRays, 0u);
  EXPECT_GT(r.refractionsTraced, 0u);
  EXPECT_GT(r.totalInternalReflections, 0u);  // grazing rays inside the glass sphere
  EXPECT_EQ(tracer.waves.size(), 6u);         // depths 1..5, then the last hits' shadow rays
  // Shadow rays end at their light.
  for (const WaveRay& w : tracer.waves[1]) {
    if (w.cls != RayClass::Shadow) continue;
    const glm::vec3 end = w.ray.origin + w.ray.tMax * w.ray.dir;
    const float toA = glm::length(end - scene.lights[0].position), toB = glm::length(end - scene.lights[1].position);
    EXPECT_LT(std::min(toA, toB), 1e-4f);
  }
}

TEST(Whitted, NoLightsNoShadowRays) {
  const Scene scene = load("spheres_no_lights.nff");
  RecordingTracer tracer(scene);
  const WhittedRun run = runWhitted(scene, tracer);
  expectContract(scene, tracer, run.result, 5);
  EXPECT_EQ(run.result.shadowRays, 0u);
  EXPECT_EQ(counts(run.result, RayClass::Shadow).rays, 0u);
  EXPECT_GT(run.result.reflectRays, 0u);
}

TEST(Whitted, NoKsNoTNoSecondaryRays) {
  const Scene scene = load("sierpinski.nff");
  ASSERT_EQ(scene.size(), 16u + 2u);
  RecordingTracer tracer(scene);
  const WhittedRun run = runWhitted(scene, tracer);
  expectContract(scene, tracer, run.result, 5);
  EXPECT_EQ(run.result.reflectRays, 0u);
  EXPECT_EQ(run.result.refractRays, 0u);
  EXPECT_GT(run.result.shadowRays, 0u);
  EXPECT_GT(run.result.shadowRaysBlocked, 0u);  // the pyramid shadows the floor
  EXPECT_EQ(tracer.waves.size(), 2u);            // eye rays, then their shadow rays
  // One shadow ray per eye hit facing the light (closed pyramid: no eye ray meets a back).
  EXPECT_LE(run.result.shadowRays, run.result.eyeHitRays);
  EXPECT_EQ(run.result.opaqueBackHits, 0u);
}

TEST(Whitted, DepthLimitStopsTheMirrors) {
  const Scene scene = load("mirrors.nff");
  for (const int depth : {1, 2, 3, 5, 7}) {
    RecordingTracer tracer(scene);
    const WhittedRun run = runWhitted(scene, tracer, {{}, depth, 1});
    expectContract(scene, tracer, run.result, depth);
    EXPECT_EQ(run.result.eyeHitRays, 64u);
    EXPECT_EQ(run.result.reflectRays, uint64_t(depth - 1) * 64u) << "max depth " << depth;
    EXPECT_EQ(tracer.waves.size(), size_t(depth)) << "max depth " << depth;
    EXPECT_EQ(counts(run.result, RayClass::Reflection).hits, run.result.reflectRays);
  }
}

TEST(Whitted, BackFacingLightSpawnsNoShadowRayEvenOnATransmitter) {
  const Scene scene = load("backlight.nff");
  RecordingTracer tracer(scene);
  const WhittedRun run = runWhitted(scene, tracer);
  expectContract(scene, tracer, run.result, 5);
  EXPECT_TRUE(run.plan.has(RayClass::Shadow));
  EXPECT_GT(run.result.eyeHitRays, 0u);
  EXPECT_EQ(run.result.shadowRays, 0u);
  EXPECT_GT(run.result.refractionsTraced, 0u);  // the glass tile refracts the eye rays down
}

TEST(Whitted, OpaqueBackIsShadedTwoSided) {
  // From below, onto the back of the opaque tile, the light below too: the hit
  // counts as a back hit and is lit from its back side.
  const Scene scene = load("backlight.nff");
  RecordingTracer tracer(scene);
  const std::vector<Ray> rays = {Ray{{-1.5f, -2.0f, 0.0f}, {0.0f, 1.0f, 0.0f}}};
  const WhittedRun run = runWhitted(scene, tracer, {}, rays);
  EXPECT_EQ(run.result.eyeHitRays, 1u);
  EXPECT_EQ(run.result.opaqueBackHits, 1u);
  EXPECT_EQ(run.result.shadowRays, 1u);
  ASSERT_EQ(tracer.waves.size(), 2u);
  EXPECT_EQ(tracer.waves[1][0].side, -1);
  EXPECT_FALSE(tracer.answers[1][0].has_value());  // nothing between it and the light
}

TEST(Whitted, ShadowTestUsesTheShadingNormal) {
  // One triangle in y = 0 facing +y, the light above; its vertex normals either
  // agree with it or point down, away from the light.
  const auto scene = [](const char* normal) {
    std::istringstream in(std::string("v\nfrom 0 5 0.01\nat 0 0 0\nup 0 1 0\nangle 20\nhither 1\nresolution 4 4\n"
                                      "l 0 5 0\nf 1 1 1 1 0 0 0 1\npp 3\n") +
                          "-5 0 5 " + normal + "\n5 0 5 " + normal + "\n0 0 -5 " + normal + "\n");
    return readNff(in, "pp.nff");
  };
  for (const auto& [normal, expected] : {std::pair{"0 1 0", true}, std::pair{"0 -1 0", false}}) {
    const Scene s = scene(normal);
    RecordingTracer tracer(s);
    const WhittedRun run = runWhitted(s, tracer);
    EXPECT_EQ(run.result.eyeHitRays, 16u);
    EXPECT_EQ(run.result.shadowRays, expected ? 16u : 0u) << normal;
  }
}

TEST(Whitted, EffectsRestrictionDropsClasses) {
  const Scene scene = load("spheres.nff");
  RecordingTracer all(scene), shadowOnly(scene), noShadow(scene);
  const WhittedRun full = runWhitted(scene, all);
  const WhittedRun s = runWhitted(scene, shadowOnly, {{"primary", "shadow"}, 5, 1});
  EXPECT_EQ(s.result.reflectRays, 0u);
  EXPECT_EQ(s.result.refractRays, 0u);
  EXPECT_EQ(shadowOnly.waves.size(), 2u);
  EXPECT_EQ(s.result.eyeHitRays, full.result.eyeHitRays);
  const WhittedRun n = runWhitted(scene, noShadow, {{"reflection", "refraction"}, 5, 1});
  EXPECT_EQ(n.result.shadowRays, 0u);
  EXPECT_EQ(n.result.reflectRays, full.result.reflectRays);
  EXPECT_EQ(n.result.refractRays, full.result.refractRays);
  // Without shadow rays the lights reach every surface facing them: never darker.
  for (size_t i = 0; i < full.result.samples.size(); ++i) {
    EXPECT_GE(n.result.samples[i].r + 1e-5f, full.result.samples[i].r) << "sample " << i;
  }
}

// One ray traced into (or from inside) the glass cube.
struct CubeRun {
  std::unique_ptr<RecordingTracer> tracer;
  WhittedResult result;
};
CubeRun throughCube(const Ray& ray, int depth) {
  static const Scene scene = load("glass_cube.nff");
  CubeRun run{std::make_unique<RecordingTracer>(scene), {}};
  const std::vector<Ray> rays = {ray};
  run.result = runWhitted(scene, *run.tracer, {{}, depth, 1}, rays).result;
  return run;
}

TEST(Whitted, TotalInternalReflectionSpawnsOnlyTheReflection) {
  // Meets the x = +1 face from inside at 60 degrees, beyond the critical angle 41.8.
  const CubeRun run = throughCube(Ray{{0.8f, 0.0f, 0.0f}, glm::normalize(glm::vec3(0.5f, 0.0f, 0.8660254f))}, 2);
  const WhittedResult& r = run.result;
  const RecordingTracer* t = run.tracer.get();
  EXPECT_EQ(r.totalInternalReflections, 1u);
  EXPECT_EQ(r.refractionsTraced, 0u);
  EXPECT_EQ(r.refractRays, 1u);  // the SPD counts it among refractions
  EXPECT_EQ(r.reflectRays, 1u);
  ASSERT_EQ(t->waves.size(), 2u);
  ASSERT_EQ(t->waves[1].size(), 1u);
  const WaveRay& reflected = t->waves[1][0];
  EXPECT_EQ(reflected.cls, RayClass::Reflection);
  EXPECT_EQ(reflected.side, -1);  // back inside
  EXPECT_NEAR(reflected.ray.dir.x, -0.5f, 1e-5f);
  EXPECT_NEAR(reflected.ray.dir.z, 0.8660254f, 1e-5f);
  EXPECT_NEAR(reflected.weight.x, 0.1f + 0.9f, 1e-6f);  // Ks plus the T it could not transmit
}

TEST(Whitted, SnellsLawEnteringAndLeaving) {
  // Straight out through x = +1: refraction along the ray, and the reflection back.
  const CubeRun a = throughCube(Ray{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}}, 2);
  const WhittedResult& out = a.result;
  const RecordingTracer* t = a.tracer.get();
  EXPECT_EQ(out.refractionsTraced, 1u);
  EXPECT_EQ(out.reflectRays, 1u);
  EXPECT_EQ(out.totalInternalReflections, 0u);
  for (const WaveRay& w : t->waves[1]) {
    if (w.cls == RayClass::Refraction) {
      EXPECT_NEAR(w.ray.dir.x, 1.0f, 1e-6f);
      EXPECT_EQ(w.side, 1);
    }
  }
  // From outside onto the top face at 45 degrees: sin t = sin 45 / 1.5.
  const CubeRun b = throughCube(Ray{{-0.5f, 1.5f, 0.0f}, glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f))}, 2);
  const WhittedResult& in = b.result;
  t = b.tracer.get();
  EXPECT_EQ(in.refractionsTraced, 1u);
  bool seen = false;
  for (const WaveRay& w : t->waves[1]) {
    if (w.cls != RayClass::Refraction) continue;
    seen = true;
    EXPECT_NEAR(w.ray.dir.x, std::sqrt(0.5f) / 1.5f, 1e-5f);
    EXPECT_LT(w.ray.dir.y, 0.0f);
    EXPECT_EQ(w.side, -1);  // into the cube, behind the top face
  }
  EXPECT_TRUE(seen);
}

TEST(Whitted, AreaLightSamplesAreStratifiedAndDeterministic) {
  // The lamp alone, from the primary hits only: the box's point light and the
  // mirror's and glass's secondary hits would blur the counts.
  Scene scene = loadScene("builtin:cornell");
  scene.lights.clear();
  CameraOptions options;
  options.width = options.height = 12;
  const std::vector<Ray> rays = frameScene(scene, options).generateRays();
  RecordingTracer a(scene), b(scene), four(scene);
  const WhittedRun one = runWhitted(scene, a, {{"shadow"}, 2, 1}, rays);
  const WhittedRun again = runWhitted(scene, b, {{"shadow"}, 2, 1}, rays);
  const WhittedRun many = runWhitted(scene, four, {{"shadow"}, 2, 4}, rays);
  EXPECT_EQ(one.result.shadowRays, again.result.shadowRays);
  EXPECT_EQ(one.result.samples, again.result.samples);
  EXPECT_GT(one.result.shadowRays, 0u);
  EXPECT_EQ(one.result.selfHits, 0u);
  EXPECT_EQ(many.result.selfHits, 0u);
  // Each stratum of the lamp sees the same facing tests: about four times the rays.
  EXPECT_GT(many.result.shadowRays, 3 * one.result.shadowRays);
  EXPECT_LE(many.result.shadowRays, 4 * one.result.shadowRays);
  for (const WaveRay& w : four.waves[1]) {
    if (w.cls != RayClass::Shadow) continue;
    const glm::vec3 end = w.ray.origin + w.ray.tMax * w.ray.dir;
    EXPECT_LT(end.y, 548.3f);  // short of the lamp's plane
    EXPECT_GT(end.y, 548.2f);
    EXPECT_GE(end.x, 212.9f);
    EXPECT_LE(end.x, 343.1f);
  }
}

TEST(Whitted, BadCameraRayNamesIt) {
  const Scene scene = load("sierpinski.nff");
  RecordingTracer tracer(scene);
  const std::vector<Ray> rays = {Ray{{0, 0, 5}, {0, 0, -1}}, Ray{{0, 0, 5}, {NAN, 0, -1}}};
  EXPECT_NE(errorOf([&] { runWhitted(scene, tracer, {}, rays); }).find("camera ray 1: NaN"), std::string::npos);
  const std::vector<Ray> zero = {Ray{{0, 0, 5}, {0, 0, 0}}};
  RecordingTracer t2(scene);
  EXPECT_NE(errorOf([&] { runWhitted(scene, t2, {}, zero); }).find("camera ray 0: zero direction"), std::string::npos);
}

TEST(Whitted, BadNffNamesFileAndLine) {
  EXPECT_NE(errorOf([] { load("bad_ior.nff"); }).find("bad_ior.nff:3: index of refraction 0 must be > 0"),
            std::string::npos);
  EXPECT_NE(errorOf([] { load("bad_transmittance.nff"); }).find("bad_transmittance.nff:3: transmittance T = -0.5"),
            std::string::npos);
  EXPECT_NE(errorOf([] { load("bad_line.nff"); }).find("bad_line.nff:4: expected a finite number, got 'zero'"),
            std::string::npos);
}

// ---- Camera samples and images ---------------------------------------------------------------

TEST(EffectsCamera, CornersSpanTheImageEdges) {
  View view;
  view.eye = {0, 0, 5};
  view.target = {0, 0, 0};
  view.fovYDegrees = 90.0f;
  const PinholeCamera camera(view, 4, 2);
  EXPECT_EQ(camera.sampleCount(Sampling::Corners), 15u);
  EXPECT_EQ(camera.sampleCount(Sampling::Centers), 8u);
  const std::vector<Ray> corners = camera.generateRays(Sampling::Corners);
  ASSERT_EQ(corners.size(), 15u);
  EXPECT_EQ(corners[1 * 5 + 3].dir, camera.generateCornerRay(3, 1).dir);
  // The top-left corner: half the field of view up, twice that aspect to the left.
  const glm::vec3 d = corners[0].dir / -corners[0].dir.z;
  EXPECT_NEAR(d.y, 1.0f, 1e-5f);
  EXPECT_NEAR(d.x, -2.0f, 1e-5f);
  // A pixel centre lies midway between its corners.
  const glm::vec3 c = camera.generateRay(1, 0).dir;
  const glm::vec3 mid = (corners[1].dir / -corners[1].dir.z + corners[5 + 2].dir / -corners[5 + 2].dir.z) * 0.5f;
  EXPECT_NEAR(c.x / -c.z, mid.x, 1e-5f);
  EXPECT_NEAR(c.y / -c.z, mid.y, 1e-5f);
}

TEST(EffectsCamera, CornerSamplesAverageFourToAPixel) {
  // 2 x 1 pixels: 3 x 2 corners.
  const std::vector<glm::vec3> s = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}};
  const Image image = samplesToImage(s, 2, 1, Sampling::Corners);
  Image expected(2, 1);
  expected.set(0, 0.5f, 0.5f, 0.0f);   // corners 0, 1, 3, 4
  expected.set(1, 0.5f, 0.25f, 0.5f);  // corners 1, 2, 4, 5
  EXPECT_EQ(image.rgb, expected.rgb);
  EXPECT_THROW(samplesToImage(s, 2, 2, Sampling::Corners), std::logic_error);
}

// ---- The SPD ---------------------------------------------------------------------------------

TEST(EffectsSpd, TetraIsTheRecursivePyramid) {
  const Scene tetra = loadScene("builtin:spd-tetra");
  ASSERT_EQ(tetra.size(), 4096u);
  EXPECT_EQ(tetra.bounds.lo, glm::vec3(-1.0f));
  EXPECT_EQ(tetra.bounds.hi, glm::vec3(1.0f));
  ASSERT_EQ(tetra.lights.size(), 1u);
  EXPECT_EQ(tetra.lights[0].position, glm::vec3(2, -18, -5));
  EXPECT_EQ(tetra.background, glm::vec3(0.078f, 0.361f, 0.753f));
  ASSERT_TRUE(tetra.view.has_value());
  EXPECT_EQ(tetra.view->width, 512);
  // Four faces a tetrahedron, each wound outwards; the smallest are 1/32 of the whole.
  for (size_t t = 0; t < tetra.size(); t += 4) {
    glm::dvec3 center(0.0);
    for (size_t f = 0; f < 4; ++f) {
      const Triangle& tri = tetra.triangles[t + f];
      center += (glm::dvec3(tri.v0) + glm::dvec3(tri.v1) + glm::dvec3(tri.v2)) / 12.0;
    }
    for (size_t f = 0; f < 4; ++f) {
      const Triangle& tri = tetra.triangles[t + f];
      const glm::dvec3 n = glm::cross(glm::dvec3(tri.v1 - tri.v0), glm::dvec3(tri.v2 - tri.v0));
      EXPECT_GT(glm::dot(n, glm::dvec3(tri.v0) - center), 0.0) << "triangle " << t + f;
      EXPECT_FLOAT_EQ(glm::length(tri.v1 - tri.v0), std::sqrt(8.0f) / 32.0f);
    }
  }
  EXPECT_EQ(makeSpdScene("tetra", 3).size(), 64u);
  EXPECT_NE(errorOf([] { generateSpdNff("tetra", 11); }).find("size factor 11 out of range"), std::string::npos);
  EXPECT_NE(errorOf([] { generateSpdNff("teapot"); }).find("unknown SPD scene 'teapot'"), std::string::npos);
  EXPECT_NE(errorOf([] { loadScene("builtin:spd-teapot"); }).find("unknown SPD scene 'teapot'"), std::string::npos);
}

// The SPD's table (Readme.txt): tetra at 513 x 513 corner rays has 49788 eye
// hit rays and 46112 shadow rays; "should be the same for all users". Within 1%.
TEST(EffectsSpd, TetraCountsAgreeWithTheSpdTable) {
  const Scene tetra = loadScene("builtin:spd-tetra");
  const PinholeCamera camera = frameScene(tetra, CameraOptions{});
  ASSERT_EQ(camera.width(), 512);
  const std::vector<Ray> rays = camera.generateRays(Sampling::Corners);
  ASSERT_EQ(rays.size(), 513u * 513u);
  const Bvh bvh(tetra, AccelOptions{});
  RefWaveTracer tracer(tetra, bvh);
  const WhittedResult r = traceWhitted(tetra, planEffects(tetra, {}), rays, tracer);
  EXPECT_NEAR(double(r.eyeHitRays), 49788.0, 0.01 * 49788.0);
  EXPECT_NEAR(double(r.shadowRays), 46112.0, 0.01 * 46112.0);
  EXPECT_EQ(r.reflectRays, 0u);
  EXPECT_EQ(r.refractRays, 0u);
  EXPECT_EQ(r.selfHits, 0u);
  EXPECT_EQ(r.opaqueBackHits, 0u);
  EXPECT_EQ(tracer.excludedOriginHits(), 0u);  // the offset alone keeps every ray off its own triangle
}

TEST(EffectsSpd, GearsAreMeshedConcaveGears) {
  const Scene gears = loadScene("builtin:spd-gears");
  // The ground's 2 triangles, 64 gears of two 144-vertex faces (142 triangles
  // each by ear clipping) and 144 rectangles (2 triangles each).
  EXPECT_EQ(gears.size(), 2u + 64u * (2u * 142u + 144u * 2u));
  EXPECT_EQ(gears.lights.size(), 5u);
  size_t transmitters = 0, reflectors = 0;
  for (const Material& m : gears.materials) {
    transmitters += m.transmittance > 0.0f;
    reflectors += m.ks > 0.0f;
    if (m.transmittance > 0.0f) {
      EXPECT_FLOAT_EQ(m.ior, 1.1f);
    }
  }
  EXPECT_EQ(reflectors, 1u);  // the ground
  EXPECT_EQ(transmitters, 13u);  // (4 ix + 2 iy + iz) mod 5 == 0 for 13 of the 64 gears
  EXPECT_EQ(makeSpdScene("gears", 1).size(), 2u + 2u * 142u + 144u * 2u);
}

// The SPD's table for gears: 245086 eye hit rays, 304643 reflection rays,
// 207564 refraction rays (total internal reflections included), 2246955 shadow rays.
TEST(EffectsSpd, GearsCountsAgreeWithTheSpdTable) {
  const Scene gears = loadScene("builtin:spd-gears");
  const std::vector<Ray> rays = frameScene(gears, CameraOptions{}).generateRays(Sampling::Corners);
  const Bvh bvh(gears, AccelOptions{});
  RefWaveTracer tracer(gears, bvh);
  const WhittedResult r = traceWhitted(gears, planEffects(gears, {}), rays, tracer);
  EXPECT_NEAR(double(r.eyeHitRays), 245086.0, 0.01 * 245086.0);
  EXPECT_NEAR(double(r.reflectRays), 304643.0, 0.01 * 304643.0);
  EXPECT_NEAR(double(r.refractRays), 207564.0, 0.01 * 207564.0);
  EXPECT_NEAR(double(r.shadowRays), 2246955.0, 0.01 * 2246955.0);
  EXPECT_GT(r.totalInternalReflections, 0u);
  EXPECT_EQ(r.selfHits, 0u);
}

// ---- Native quadrics (issue #40) ------------------------------------------------------------

Scene loadNative(const std::string& name) {
  NffOptions options;
  options.quadrics = QuadricForm::Native;
  return loadNff(kData + "/" + name, options);
}

// A quadric's hit: the point on the ray at t, the outward normal (inward on an
// inside-visible quadric, as its tessellation is wound), the shading normal
// the geometric one turned to the ray; front as the tessellation has it.
TEST(WhittedQuadrics, SurfaceOfASphereFromOutsideAndInside) {
  const auto sceneOf = [](float radius, QuadricForm quadrics) {
    std::istringstream in(fmt::format("f 1 1 1 1 0 0 0 1\ns 0 0 0 {}\n", radius));
    NffOptions options;
    options.quadrics = quadrics;
    return readNff(in, "sphere.nff", options);
  };
  const Ray outside{{0, 0, -4}, {0, 0, 2}}, inside{{0.3f, 0, 0}, {0, 0, 1}};
  for (const float radius : {2.0f, -2.0f}) {
    const Scene native = sceneOf(radius, QuadricForm::Native), tessellated = sceneOf(radius, QuadricForm::Tessellate);
    const Bvh nativeBvh(native, {}), tessellatedBvh(tessellated, {});
    for (const bool fromOutside : {true, false}) {
      const Ray& ray = fromOutside ? outside : inside;
      const auto hit = nativeBvh.intersect(ray);
      ASSERT_TRUE(hit);
      ASSERT_TRUE(native.isQuadric(hit->prim));
      const SurfacePoint s = surfaceAt(native, ray, *hit);
      EXPECT_NEAR(glm::length(s.point), 2.0f, 1e-5f);
      const glm::vec3 outward = glm::normalize(s.point);
      EXPECT_NEAR(glm::dot(s.outward, outward), 1.0f, 1e-6f);
      EXPECT_NEAR(glm::dot(s.geometric, radius < 0 ? -outward : outward), 1.0f, 1e-6f);
      EXPECT_EQ(s.front, fromOutside == (radius > 0)) << radius;
      EXPECT_LT(glm::dot(s.normal, s.dir), 0.0f);  // turned to the ray
      EXPECT_NEAR(glm::dot(s.normal, s.front ? s.geometric : -s.geometric), 1.0f, 1e-6f);
      // The same side as the tessellation's triangle.
      const auto flat = tessellatedBvh.intersect(ray);
      ASSERT_TRUE(flat);
      EXPECT_EQ(surfaceAt(tessellated, ray, *flat).front, s.front) << radius;
      // Leaving inwards goes into the solid, whichever side is visible.
      EXPECT_TRUE(s.intoSolid(-outward));
      EXPECT_FALSE(s.intoSolid(outward));
    }
  }
}

// The ids of a native scene's quadrics by material: the mirror, the glass, the cone.
struct QuadricIds {
  uint32_t mirror = UINT32_MAX, glass = UINT32_MAX, cone = UINT32_MAX;
  explicit QuadricIds(const Scene& scene) {
    for (uint32_t p = uint32_t(scene.size()); p < scene.primitiveCount(); ++p) {
      const Material& m = scene.materials[scene.materialOf[p]];
      (m.transmittance > 0.0f ? glass : m.ks > 0.0f ? mirror : cone) = p;
    }
  }
};

TEST(WhittedQuadrics, MirrorGlassAndConeSpawnEveryClassOffTheRightPrimitives) {
  const Scene scene = loadNative("quadrics.nff");
  ASSERT_EQ(scene.quadrics.size(), 3u);
  const QuadricIds id(scene);
  ASSERT_NE(id.cone, UINT32_MAX);
  RecordingTracer tracer(scene);
  CameraOptions camera;
  camera.width = camera.height = 64;
  const WhittedRun run = runWhitted(scene, tracer, {}, frameScene(scene, camera).generateRays(Sampling::Centers));
  const WhittedResult& r = run.result;
  expectContract(scene, tracer, r, 5);
  EXPECT_EQ(tracer.ref().excludedOriginHits(), 0u);  // the offset alone keeps rays off their own surface
  EXPECT_EQ(r.opaqueBackHits, 0u);
  // Counts by what each ray left and what it hit.
  std::map<std::pair<uint32_t, uint32_t>, int> shadowBlockers, reflected, refractedIn, refractedOut;
  std::set<uint32_t> eyeHit;
  uint64_t mirrorOrGlassHits = 0, glassHits = 0;  // hits that reflect or refract (below the depth limit)
  // The floor's two triangles count as one primitive, 0.
  const auto at = [&](auto& counts, uint32_t from, uint32_t to) -> int& {
    const auto floor = [&](uint32_t p) { return p < scene.size() ? 0u : p; };
    return counts[std::make_pair(floor(from), floor(to))];
  };
  for (size_t g = 0; g < tracer.waves.size(); ++g) {
    for (size_t k = 0; k < tracer.waves[g].size(); ++k) {
      const WaveRay& w = tracer.waves[g][k];
      const auto& h = tracer.answers[g][k];
      const uint32_t hit = h ? h->prim : UINT32_MAX;
      if (w.cls != RayClass::Shadow && w.depth < 5) {
        mirrorOrGlassHits += hit == id.mirror || hit == id.glass;
        glassHits += hit == id.glass;
      }
      switch (w.cls) {
        case RayClass::Primary: eyeHit.insert(hit); break;
        case RayClass::Shadow:
          if (h) ++at(shadowBlockers, w.originPrim, hit);
          break;
        case RayClass::Reflection:
          ++at(reflected, w.originPrim, hit);
          // Off the mirror (outside a convex solid) nothing of the mirror is met again.
          if (w.originPrim == id.mirror) {
            EXPECT_NE(hit, id.mirror);
          }
          break;
        case RayClass::Refraction:
          ASSERT_EQ(w.originPrim, id.glass);
          if (w.intoSolid) {
            // Into the glass: its far side, leaving, always.
            ++at(refractedIn, w.originPrim, hit);
            ASSERT_TRUE(h);
            EXPECT_EQ(hit, id.glass);
            EXPECT_EQ(h->u, 1.0f);
          } else {
            ++at(refractedOut, w.originPrim, hit);
            EXPECT_NE(hit, id.glass);
          }
          break;
        default: break;
      }
    }
  }
  for (const uint32_t q : {id.mirror, id.glass, id.cone}) EXPECT_TRUE(eyeHit.count(q)) << q;
  EXPECT_TRUE(eyeHit.count(0) || eyeHit.count(1));  // the floor
  // The floor's shadow rays meet each quadric; a shadow ray from inside the glass meets the glass.
  for (const uint32_t q : {id.mirror, id.glass, id.cone}) EXPECT_GT(at(shadowBlockers, 0u, q), 0) << q;
  EXPECT_GT(at(shadowBlockers, id.glass, id.glass), 0);
  EXPECT_GT(at(reflected, id.mirror, 0u), 0);   // the mirror sees the floor
  EXPECT_GT(at(reflected, id.mirror, UINT32_MAX), 0);  // and the sky
  EXPECT_GT(at(reflected, id.glass, id.glass), 0);  // internal reflection inside the glass
  EXPECT_GT(at(refractedIn, id.glass, id.glass), 0);
  int out = 0;
  for (const auto& [key, n] : refractedOut) out += n;
  EXPECT_GT(out, 0);
  // Every mirror and glass hit reflects, every glass hit refracts (or reflects
  // totally): the counts of the plan's classes.
  EXPECT_EQ(r.reflectRays, mirrorOrGlassHits);
  EXPECT_EQ(r.refractRays, glassHits);
  EXPECT_GT(r.refractRays, 500u);
  // (A ray refracted into a sphere always leaves it: no total internal
  // reflection but after internal reflections, rare at this size.)
  EXPECT_EQ(r.refractionsTraced, uint64_t(out) + uint64_t(at(refractedIn, id.glass, id.glass)));
}

// The counts of a Whitted run of `scene` at `size` x `size` centre samples
// (a tessellated sphere's smooth normals may send a reflection through its
// own triangles' backs; a native one's may not).
WhittedResult whittedCounts(const Scene& scene, int size) {
  CameraOptions options;
  options.width = options.height = size;
  const std::vector<Ray> rays = frameScene(scene, options).generateRays(Sampling::Centers);
  const Bvh bvh(scene, AccelOptions{});
  RefWaveTracer tracer(scene, bvh);
  WhittedResult r = traceWhitted(scene, planEffects(scene, {}), rays, tracer);
  EXPECT_EQ(r.selfHits, 0u) << scene.name;
  if (!scene.quadrics.empty()) {
    EXPECT_EQ(r.opaqueBackHits, 0u) << scene.name;
    EXPECT_EQ(tracer.excludedOriginHits(), 0u) << scene.name;
  }
  return r;
}

// Native quadrics and their tessellation (768 triangles a sphere, 32 slices a
// cone) give the same picture to within the tessellation's silhouettes.
void expectCountsAgree(const WhittedResult& native, const WhittedResult& flat, double within) {
  const auto near = [&](uint64_t a, uint64_t b, const char* what) {
    EXPECT_NEAR(double(a), double(b), within * double(std::max<uint64_t>(b, 1)) + 2.0) << what;
  };
  near(native.eyeHitRays, flat.eyeHitRays, "eye hit rays");
  near(native.shadowRays, flat.shadowRays, "shadow rays");
  // Blockers differ more: a shadow ray grazing a sphere meets its polygon or not.
  EXPECT_NEAR(double(native.shadowRaysBlocked), double(flat.shadowRaysBlocked),
              2.0 * within * double(flat.shadowRaysBlocked) + 2.0);
  near(native.reflectRays, flat.reflectRays, "reflect rays");
  near(native.refractRays, flat.refractRays, "refract rays");
}

TEST(WhittedQuadrics, NativeAndTessellatedQuadricsGiveTheSameCounts) {
  const WhittedResult native = whittedCounts(loadNative("quadrics.nff"), 64);
  const WhittedResult flat = whittedCounts(load("quadrics.nff"), 64);
  EXPECT_GT(native.refractRays, 100u);
  expectCountsAgree(native, flat, 0.03);
}

// The SPD's sphereflake (balls) and mountain with its four glass spheres
// (mount) at size factor 1, native and tessellated, on a small image.
TEST(WhittedQuadrics, SpdBallsAndMountNativeAgreeWithTheirTessellation) {
  for (const char* name : {"balls", "mount"}) {
    SCOPED_TRACE(name);
    const std::string nff = generateSpdNff(name, 1);
    NffOptions options;
    options.quadrics = QuadricForm::Native;
    std::istringstream nativeText(nff), flatText(nff);
    const Scene native = readNff(nativeText, name, options), flat = readNff(flatText, name);
    EXPECT_EQ(native.quadrics.size(), std::string(name) == "balls" ? 10u : 4u);
    const WhittedResult n = whittedCounts(native, 96), f = whittedCounts(flat, 96);
    EXPECT_GT(n.reflectRays, 500u);
    if (std::string(name) == "mount") {
      EXPECT_GT(n.refractRays, 100u);
    }
    expectCountsAgree(n, f, 0.03);
  }
}

// An emissive quadric glows where it is seen but is no area light: only
// triangles are sampled by shadow rays.
TEST(WhittedQuadrics, AnEmissiveQuadricIsNoAreaLight) {
  Scene scene = test::mixedScene({{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}, {Quadric::sphere({0, 0, 3}, 1)});
  scene.materials.push_back(Material{"lamp", glm::vec3(1.0f), glm::vec3(2.0f)});
  scene.materialOf[1] = 1;
  const EffectsPlan plan = planEffects(scene, {});
  EXPECT_EQ(plan.emissiveTriangles, 0u);
  EXPECT_FALSE(plan.has(RayClass::Shadow));
}

}  // namespace
}  // namespace lancer
