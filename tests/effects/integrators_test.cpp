// The integrators on the float reference: their counter-based sampler
// (effects/sampler.h: Philox4x32-10 against the Random123 library's known
// answers, the directions it draws); ambient occlusion (effects/ao.h) and the
// path tracer (effects/path.h): their waves and classes, determinism,
// convergence, and bad options.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "common/error.h"
#include "common/philox.h"
#include "effects/ao.h"
#include "effects/path.h"
#include "effects/ref_tracer.h"
#include "effects/sampler.h"
#include "ref/bvh.h"
#include "scene/camera.h"

namespace lancer {
namespace {

// Random123's kat_vectors, the three "philox4x32 10" lines.
TEST(Philox, MatchesTheRandom123KnownAnswers) {
  EXPECT_EQ(philox4x32_10({0, 0, 0, 0}, {0, 0}), (PhiloxCounter{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}));
  EXPECT_EQ(philox4x32_10({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff}),
            (PhiloxCounter{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}));
  EXPECT_EQ(philox4x32_10({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0}),
            (PhiloxCounter{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}));
}

TEST(Sampler, IsAFunctionOfItsCounterAndKey) {
  const Sampler a(7), b(7), other(8);
  EXPECT_EQ(a.uniform4(3, 1, 2, 5), b.uniform4(3, 1, 2, 5));
  EXPECT_NE(a.uniform4(3, 1, 2, 5), other.uniform4(3, 1, 2, 5));
  // Every field of the counter changes the numbers.
  std::set<std::array<float, 4>> seen;
  for (const auto& c : {std::array<uint32_t, 4>{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}) {
    seen.insert(a.uniform4(c[0], c[1], c[2], c[3]));
  }
  EXPECT_EQ(seen.size(), 5u);
  // uniform2's pairs are the halves of uniform4's groups.
  const std::array<float, 4> g = a.uniform4(9, 0, 0, 1);
  EXPECT_EQ(a.uniform2(9, 0, 0, 2), glm::vec2(g[0], g[1]));
  EXPECT_EQ(a.uniform2(9, 0, 0, 3), glm::vec2(g[2], g[3]));
}

TEST(Sampler, UniformNumbersLieInTheUnitIntervalWithTheRightMean) {
  const Sampler s(1);
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    for (const float u : s.uniform4(uint32_t(i), 0, 0, 0)) {
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      sum += u;
    }
  }
  EXPECT_NEAR(sum / (4.0 * n), 0.5, 0.005);
  EXPECT_EQ(unitFloat(0xffffffffu), 1.0f - 0x1.0p-24f);
}

TEST(Sampler, CosineHemisphereAboutAnyNormal) {
  const Sampler s(2);
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -2, 0.5f)),
                            glm::vec3(1, 0, 0)}) {
    double meanCos = 0;
    const int count = 4000;
    for (int i = 0; i < count; ++i) {
      const glm::vec3 d = aboutNormal(n, cosineHemisphere(s.uniform2(uint32_t(i), 0, 0, 0)));
      ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
      ASSERT_GE(glm::dot(d, n), -1e-6f);
      meanCos += glm::dot(d, n);
    }
    EXPECT_NEAR(meanCos / count, 2.0 / 3.0, 0.02);  // E[cos] under the cosine density
  }
}

// ---- Ambient occlusion on the float reference ------------------------------------

// The Cornell box's camera samples, size x size, and the integrators on the float reference.
struct CornellRun {
  Scene scene = makeCornellBox();
  std::vector<Ray> camera;
  explicit CornellRun(int size = 24) {
    CameraOptions o;
    o.width = size;
    o.height = size;
    camera = frameScene(scene, o).generateRays(Sampling::Centers);
  }
  IntegratorResult ao(const AoOptions& options) {
    return trace([&](WaveTracer& t) { return traceAo(scene, options, camera, t); });
  }
  IntegratorResult path(const PathOptions& options) {
    return trace([&](WaveTracer& t) { return tracePath(scene, options, camera, t); });
  }

 private:
  template <class Integrator>
  IntegratorResult trace(Integrator integrator) {
    const Bvh bvh(scene, AccelOptions{});
    RefWaveTracer tracer(scene, bvh);
    return integrator(tracer);
  }
};

TEST(AmbientOcclusion, TwoWavesOfTheirClassesAndValuesInTheUnitInterval) {
  CornellRun r;
  AoOptions o;
  o.rays = 6;
  const IntegratorResult result = r.ao(o);
  ASSERT_EQ(result.waveRays.size(), 2u);
  const auto& camera = result.classes.at(RayClass::Camera);
  const auto& ao = result.classes.at(RayClass::Ao);
  EXPECT_EQ(camera.rays, r.camera.size());
  EXPECT_EQ(ao.rays, camera.hits * 6);
  EXPECT_GT(ao.hits, 0u);       // the box's corners occlude
  EXPECT_LT(ao.hits, ao.rays);  // and its open faces do not
  EXPECT_EQ(result.selfHits, 0u);
  for (const glm::vec3& v : result.samples) {
    EXPECT_GE(v.x, 0.0f);
    EXPECT_LE(v.x, 1.0f + 1e-6f);
    EXPECT_EQ(v.x, v.y);
  }
  EXPECT_EQ(toString(ClassKey(RayClass::Ao)), "ao");
  EXPECT_EQ(toString(ClassKey(RayClass::Bounce, 3)), "bounce3");
}

TEST(AmbientOcclusion, TheSameImageEveryRunAndAnotherForAnotherSeed) {
  CornellRun r;
  AoOptions o;
  o.rays = 4;
  const IntegratorResult a = r.ao(o), b = r.ao(o);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(relativeMse(a.samples, b.samples), 0.0);
  o.seed = 2;
  const IntegratorResult c = r.ao(o);
  EXPECT_NE(a.samples, c.samples);
  EXPECT_GT(relativeMse(c.samples, a.samples), 0.0);
  EXPECT_LT(relativeMse(c.samples, a.samples), 0.2);  // the same picture, other noise
}

TEST(AmbientOcclusion, BadOptionsNameTheOption) {
  CornellRun r;
  for (const auto& [rays, distance, option] : {std::tuple{0, 0.0f, "--ao-rays 0"}, {kMaxAoRays + 1, 0.0f, "--ao-rays"},
                                               {4, -1.0f, "--ao-distance -1"}, {4, NAN, "--ao-distance nan"}}) {
    AoOptions o;
    o.rays = rays;
    o.distance = distance;
    try {
      r.ao(o);
      ADD_FAILURE() << option << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(option, 0), 0u) << e.what();
    }
  }
}

// ---- The path tracer on the float reference -----------------------------------------

TEST(PathTracer, CameraRaysThenBouncesAndShadowRaysUpToTheDepth) {
  CornellRun r(16);
  PathOptions o;
  o.spp = 3;
  o.maxDepth = 4;
  const IntegratorResult result = r.path(o);
  EXPECT_EQ(result.classes.at(RayClass::Camera).rays, r.camera.size() * 3);
  EXPECT_GT(result.classes.at(RayClass::Shadow).rays, 0u);  // the box's lamp and point light
  EXPECT_GT(result.classes.at(ClassKey(RayClass::Bounce, 1)).rays, 0u);
  EXPECT_TRUE(result.classes.contains(ClassKey(RayClass::Bounce, 3)));
  EXPECT_FALSE(result.classes.contains(ClassKey(RayClass::Bounce, 4)));  // depth 4: the camera ray and 3 bounces
  EXPECT_LE(result.waveRays.size(), 5u);
  EXPECT_EQ(result.selfHits, 0u);
  for (const glm::vec3& v : result.samples) {
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
    EXPECT_GE(std::min({v.x, v.y, v.z}), 0.0f);
  }
  o.maxDepth = 1;  // direct light only
  const IntegratorResult direct = r.path(o);
  EXPECT_FALSE(direct.classes.contains(ClassKey(RayClass::Bounce, 1)));
}

TEST(PathTracer, TheSameImageEveryRunAndConvergingWithMorePaths) {
  CornellRun r(16);
  PathOptions o;
  o.spp = 2;
  EXPECT_EQ(r.path(o).samples, r.path(o).samples);
  o.spp = 64;
  const IntegratorResult reference = r.path(o);
  o.spp = 1;
  const double one = relativeMse(r.path(o).samples, reference.samples);
  o.spp = 8;
  const double eight = relativeMse(r.path(o).samples, reference.samples);
  EXPECT_GT(one, 0.0);
  EXPECT_LT(eight, 0.5 * one);  // the error falls about as 1 / spp
}

TEST(PathTracer, BadOptionsNameTheOption) {
  CornellRun r(16);
  const auto fails = [&](PathOptions o, const std::string& start) {
    try {
      r.path(o);
      ADD_FAILURE() << start << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(start, 0), 0u) << e.what();
    }
  };
  PathOptions o;
  o.spp = 0;
  fails(o, "--spp 0");
  o = {};
  o.maxDepth = kMaxPathDepth + 1;
  fails(o, "--max-depth");
  o = {};
  o.rrDepth = 0;
  fails(o, "--rr-depth 0");
  o = {};
  o.spp = kMaxSpp;  // 576 samples x 65536 paths: more than one wave may hold
  CornellRun big(24);
  try {
    big.path(o);
    ADD_FAILURE() << "--spp 65536 at 24x24: accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--spp 65536: 576 camera samples", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace lancer
