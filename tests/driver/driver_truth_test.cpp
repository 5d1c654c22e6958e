// The hardware's answers are true, not only bit-exact with the golden model:
// closed objects seen from outside (their faces on the scene's bounds, where
// every ray enters the lattice), secondary rays that cannot meet the triangle
// they leave, and every wave class judged against the float reference on the
// rays the hardware was asked (docs/number-formats.md, docs/effects.md).
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "driver/candidates.h"
#include "driver/job.h"
#include "driver/quantize.h"
#include "driver/report.h"
#include "driver/wave_tracer.h"
#include "effects/plan.h"
#include "effects/ref_tracer.h"
#include "effects/whitted.h"
#include "golden/isect.h"
#include "ref/bvh.h"
#include "ref/trace.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace lancer {
namespace {

// Rays from every side of the unit cube into it: through the middle of each
// face, and at points on each face, edge and corner, every pinned axis inward.
std::vector<Ray> raysIntoTheCube(size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> inside(0.05f, 0.95f), inward(0.3f, 1.0f), any(-1.0f, 1.0f);
  std::vector<Ray> rays;
  while (rays.size() < count) {
    const int pinned = int(rays.size() % 3) + 1;  // a face, an edge, a corner
    const int free = int(rng() % 3);
    glm::vec3 target, dir;
    for (int a = 0; a < 3; ++a) {
      const bool onFace = pinned == 3 || (pinned == 2 ? a != free : a == free);
      target[a] = onFace ? float(rng() & 1) : inside(rng);
      dir[a] = onFace ? (target[a] == 0.0f ? inward(rng) : -inward(rng)) : any(rng);
    }
    rays.push_back({target - 2.0f * dir, dir, kInfinity});
  }
  return rays;
}

TEST(DriverTruth, TheQuantizerLeavesAMarginAroundTheScene) {
  const Scene cube = makeCube();
  const Quantizer q(cube.bounds);
  const fx::QTriangle t = q.quantize(Triangle{{0, 0, 0}, {1, 1, 1}, {0, 1, 0}}, 0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(t.v[0][a], kLatticeMarginUnits);
    EXPECT_EQ(t.v[1][a], fx::kPosMax - kLatticeMarginUnits);
  }
  // A ray from outside enters on the cube's face, short of the scene's face.
  const auto r = q.quantize(Ray{{-1.0f, 0.5f, 0.5f}, {1, 0, 0}}, 0);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->q.org[0], 0);
  EXPECT_NEAR(r->tEnter + r->tScale * double(kLatticeMarginUnits) / double(fx::kDirMax), 1.0, 1e-12);
}

// The bug of issue #21: each face of a closed cube lies on the scene's box, so
// every ray entered the lattice exactly on a face's plane (t = 0, excluded) and
// the hardware saw the cube's inside.
TEST(DriverTruth, ACubeSeenFromOutsideShowsItsOutsideOnEveryPath) {
  const Scene cube = makeCube();
  const Quantizer quantizer(cube.bounds);
  const std::vector<Ray> rays = raysIntoTheCube(3000, 21);
  const Bvh reference(cube, AccelOptions{});
  const auto refHits = traceRays(reference, rays);
  for (const fx::UnitKind path : hardwarePaths()) {
    SCOPED_TRACE(toString(path));
    const JobResult job = runJob(path, cube, rays, quantizer, JobConfig{});
    EXPECT_EQ(job.mismatchedRays, 0u);
    // Rays through a face's inside (every third ray) meet one triangle first:
    // the reference's. At an edge or a corner two or three tie, and either is right.
    size_t same = 0, faceRays = 0;
    for (size_t i = 0; i < rays.size(); i += 3, ++faceRays) {
      const auto hw = sceneHit(job, i);
      same += hw && refHits[i] && hw->prim == refHits[i]->prim;
    }
    EXPECT_GE(double(same), 0.999 * double(faceRays)) << same << " of " << faceRays;
    const ReferenceComparison cmp =
        compareWithReference(cube, rays, refHits, job, quantizer, exactCandidates(reference, cube.bounds));
    EXPECT_EQ(cmp.arbiter.beyondBound(), 0u);
    EXPECT_EQ(cmp.hitMissDiffers, 0u) << "every ray into the cube must hit it";
  }
}

// Two walls x = 0 and x = 1 and rays from x < 0: the wall at x = 0 was missed by all.
TEST(DriverTruth, TheNearWallOfAPairIsHit) {
  Scene walls;
  walls.name = "walls";
  for (float x : {0.0f, 1.0f}) {
    walls.triangles.push_back({{x, 0, 0}, {x, 1, 0}, {x, 1, 1}});
    walls.triangles.push_back({{x, 0, 0}, {x, 1, 1}, {x, 0, 1}});
  }
  walls.materials.push_back(Material{});
  walls.materialOf.assign(walls.size(), 0);
  walls.computeBounds();
  const Quantizer quantizer(walls.bounds);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(0.02f, 0.98f), tilt(-0.4f, 0.4f);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 target(0.0f, u(rng), u(rng));
    const glm::vec3 dir(1.0f, tilt(rng), tilt(rng));
    rays.push_back({target - 0.5f * dir, dir, kInfinity});
  }
  for (const fx::UnitKind path : hardwarePaths()) {
    SCOPED_TRACE(toString(path));
    const JobResult job = runJob(path, walls, rays, quantizer, JobConfig{});
    size_t nearWall = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const auto hw = sceneHit(job, i);
      nearWall += hw && hw->prim < 2;
    }
    EXPECT_GE(double(nearWall), 0.999 * double(rays.size()));
  }
}

// Tiny spheres (a few lattice units across) in a large scene: the lattice
// normal of such a triangle turns far from its float one, so the side of the
// float triangle a ray leaves to can be the lattice triangle's other side.
Scene tinySpheres() {
  Scene scene;
  scene.name = "tiny spheres";
  const Scene sphere = makeIcosphere(1);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> at(-0.5f, 0.5f);
  const float unit = 4.0f / float(fx::kPosMax);  // the floor below sets the scene's extent, 4
  for (int s = 0; s < 300; ++s) {
    const glm::vec3 centre(at(rng), at(rng), at(rng));
    const float radius = float(s % 3 + 1) * 1.3f * unit;  // 1.3 to 4 lattice units
    for (const Triangle& t : sphere.triangles) {
      scene.triangles.push_back({centre + radius * t.v0, centre + radius * t.v1, centre + radius * t.v2});
    }
  }
  // The scene's extent: a floor far below.
  scene.triangles.push_back({{-2, -1, -2}, {2, -1, -2}, {2, -1, 2}});
  scene.triangles.push_back({{-2, -1, -2}, {2, -1, 2}, {-2, -1, 2}});
  scene.materials.push_back(Material{});
  scene.materialOf.assign(scene.size(), 0);
  scene.computeBounds();
  return scene;
}

// Reflection-like secondary rays from every hit on a tiny sphere, in random
// directions on the float triangle's front side: none may hit its own triangle.
TEST(DriverTruth, SecondaryRaysNeverMeetTheTriangleTheyLeave) {
  const Scene scene = tinySpheres();
  const Quantizer quantizer(scene.bounds);
  const Bvh reference(scene, AccelOptions{});
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  // Primary rays aimed at the spheres' vertices' neighbourhood.
  std::vector<WaveRay> primaries;
  for (size_t t = 0; t + 2 < scene.size(); t += 7) {
    const Triangle& tri = scene.triangles[t];
    const glm::vec3 target = (tri.v0 + tri.v1 + tri.v2) / 3.0f;
    WaveRay r;
    r.ray = {target + glm::vec3(0.3f, 0.9f, 0.2f), glm::vec3(-0.3f, -0.9f, -0.2f), kInfinity};
    primaries.push_back(r);
  }
  for (const fx::UnitKind path : {fx::UnitKind::Isect, fx::UnitKind::Octree}) {
    SCOPED_TRACE(toString(path));
    HardwareWaveTracer tracer(path, scene, quantizer, JobConfig{}, &reference);
    std::vector<std::optional<Hit>> hits;
    tracer.trace(0, primaries, hits);
    std::vector<WaveRay> secondaries;
    for (uint32_t k = 0; k < hits.size(); ++k) {
      if (!hits[k]) continue;
      const Triangle& tri = scene.triangles[hits[k]->prim];
      const glm::vec3 n = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
      const int8_t side = glm::dot(primaries[k].ray.dir, n) < 0 ? 1 : -1;  // the side the primary came from
      const glm::vec3 p = primaries[k].ray.origin + hits[k]->t * primaries[k].ray.dir;
      for (int j = 0; j < 16; ++j) {
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (glm::dot(d, n) * float(side) < 0) d -= 2.0f * glm::dot(d, n) * n;  // onto the leaving side
        WaveRay s;
        s.ray = {p, d, kInfinity};
        s.cls = RayClass::Reflection;
        s.parent = k;
        s.originPrim = hits[k]->prim;
        s.side = side;
        secondaries.push_back(s);
      }
    }
    ASSERT_GT(secondaries.size(), 1000u);
    tracer.trace(1, secondaries, hits);
    size_t selfHits = 0;
    for (size_t k = 0; k < hits.size(); ++k) selfHits += hits[k] && hits[k]->prim == secondaries[k].originPrim;
    EXPECT_EQ(selfHits, 0u);
    // Each flip is a ray that would have met its own triangle from the float side.
    EXPECT_GT(tracer.sideFlips(), 0u) << "the case this test is for did not occur";
    EXPECT_EQ(tracer.comparison(RayClass::Reflection).arbiter.beyondBound(), 0u);
  }
}

// An effects run judges every class against the reference on the same rays.
TEST(DriverTruth, EveryWaveClassIsJudgedAndTheCornellShadowsAgree) {
  const Scene scene = makeCornellBox();
  const Quantizer quantizer(scene.bounds);
  const Bvh reference(scene, AccelOptions{});
  const EffectsPlan plan = planEffects(scene, EffectsOptions{});
  const std::vector<Ray> eye = frameScene(scene, CameraOptions::sized(64, 64)).generateRays();
  HardwareWaveTracer tracer(fx::UnitKind::Octree, scene, quantizer, JobConfig{}, &reference);
  const WhittedResult hw = traceWhitted(scene, plan, eye, tracer);
  RefWaveTracer refTracer(scene, reference);
  const WhittedResult ref = traceWhitted(scene, plan, eye, refTracer);
  for (RayClass cls : {RayClass::Primary, RayClass::Shadow, RayClass::Reflection, RayClass::Refraction}) {
    SCOPED_TRACE(std::string(toString(cls)));
    const ReferenceComparison& cmp = tracer.comparison(cls);
    EXPECT_EQ(cmp.arbiter.judged, cmp.disagreements);
    EXPECT_EQ(cmp.arbiter.beyondBound(), 0u);
  }
  EXPECT_GT(tracer.comparison(RayClass::Shadow).arbiter.judged, 0u);
  EXPECT_EQ(tracer.beyondBound(), 0u);
  EXPECT_EQ(hw.selfHits, 0u);
  // The lamp no longer shadows the walls it grazes (the segment ends short of
  // its plane, not of its sample point): blocked within 1% of the reference.
  EXPECT_NEAR(double(hw.shadowRaysBlocked), double(ref.shadowRaysBlocked), 0.01 * double(ref.shadowRaysBlocked));
}

}  // namespace
}  // namespace lancer
