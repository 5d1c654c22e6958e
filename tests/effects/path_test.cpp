// The path tracer (effects/path.h) on the float reference: its waves and
// classes, the depth limit, determinism, convergence with more paths, and
// bad options.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "effects/path.h"
#include "effects/ref_tracer.h"
#include "ref/bvh.h"
#include "scene/camera.h"

namespace lancer {
namespace {

struct PathRun {
  Scene scene = makeCornellBox();
  std::vector<Ray> camera;
  explicit PathRun(int size = 16) {
    CameraOptions o;
    o.width = size;
    o.height = size;
    camera = frameScene(scene, o).generateRays(Sampling::Centers);
  }
  IntegratorResult run(const PathOptions& options) {
    const Bvh bvh(scene, AccelOptions{});
    RefWaveTracer tracer(scene, bvh);
    return tracePath(scene, options, camera, tracer);
  }
};

TEST(PathTracer, CameraRaysThenBouncesAndShadowRaysUpToTheDepth) {
  PathRun r;
  PathOptions o;
  o.spp = 3;
  o.maxDepth = 4;
  const IntegratorResult result = r.run(o);
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
  const IntegratorResult direct = r.run(o);
  EXPECT_FALSE(direct.classes.contains(ClassKey(RayClass::Bounce, 1)));
}

TEST(PathTracer, TheSameImageEveryRunAndConvergingWithMorePaths) {
  PathRun r;
  PathOptions o;
  o.spp = 2;
  EXPECT_EQ(r.run(o).samples, r.run(o).samples);
  o.spp = 64;
  const IntegratorResult reference = r.run(o);
  o.spp = 1;
  const double one = relativeMse(r.run(o).samples, reference.samples);
  o.spp = 8;
  const double eight = relativeMse(r.run(o).samples, reference.samples);
  EXPECT_GT(one, 0.0);
  EXPECT_LT(eight, 0.5 * one);  // the error falls about as 1 / spp
}

TEST(PathTracer, BadOptionsNameTheOption) {
  PathRun r;
  const auto fails = [&](PathOptions o, const std::string& start) {
    try {
      r.run(o);
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
  PathRun big(24);
  try {
    big.run(o);
    ADD_FAILURE() << "--spp 65536 at 24x24: accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--spp 65536: 576 camera samples", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace lancer
