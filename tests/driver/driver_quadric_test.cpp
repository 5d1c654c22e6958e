// The driver's native quadrics (issue #40, docs/quadrics.md "On the lattice,
// and on the command line"): the quantizer's records, the quadric pipeline
// behind every model of the device interface, and the isect job on a scene of
// triangles, spheres and cones: bit for bit against golden, hits on quadrics
// with their side, the exact arbiter finding no hardware answer beyond the
// lattice's bound.

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include <algorithm>

#include "driver/candidates.h"
#include "driver/devices.h"
#include "driver/golden_device.h"
#include "driver/isect_job.h"
#include "driver/quantize.h"
#include "driver/report.h"
#include "ref/bvh.h"
#include "ref/trace.h"
#include "scene/camera.h"
#include "scene/nff.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

Aabb unitCube() {
  Aabb b;
  b.extend(glm::vec3(0.0f));
  b.extend(glm::vec3(1.0f));
  return b;
}

TEST(DriverQuadricQuantizer, RoundsCentersAndRadiiAsVertices) {
  const Quantizer q(unitCube());
  const double unit = q.unit();
  const fx::QQuadric s = q.quantize(Quadric::sphere({0.5f, 0.5f, 0.5f}, float(10.4 * unit)), 7);
  EXPECT_EQ(s.id, 7u);
  EXPECT_EQ(s.constant, -4 * 10 * 10) << "radius 10.4 units rounds to 10";
  const glm::dvec3 c = q.toLattice({0.5, 0.5, 0.5});
  for (int a = 0; a < 3; ++a) EXPECT_EQ(s.axisSum[size_t(a)], 2 * std::llrint(c[a]));
  // A sphere thinner than half a unit keeps radius 1; NFF's negative radius is its size.
  EXPECT_EQ(q.quantize(Quadric::sphere({0.5f, 0.5f, 0.5f}, float(0.2 * unit)), 1).constant, -4);
  EXPECT_EQ(q.quantize(Quadric::sphere({0.5f, 0.5f, 0.5f}, float(-3.0 * unit)), 1).constant, -36);
}

TEST(DriverQuadricQuantizer, KeepsDegenerateConesTraceable) {
  const Quantizer q(unitCube());
  const double unit = q.unit();
  // Both radii below half a unit: 1 at the wider end.
  const fx::QQuadric thin =
      q.quantize(Quadric::cone({0.2f, 0.5f, 0.5f}, float(0.1 * unit), {0.8f, 0.5f, 0.5f}, float(0.3 * unit)), 3);
  const fx::QQuadric reference = fx::coneRecord(
      3, {q.quantize(Triangle{{0.2f, 0.5f, 0.5f}, {0.2f, 0.5f, 0.5f}, {0.2f, 0.5f, 0.5f}}, 0).v[0],
          q.quantize(Triangle{{0.8f, 0.5f, 0.5f}, {0.8f, 0.5f, 0.5f}, {0.8f, 0.5f, 0.5f}}, 0).v[0], 0, 1});
  EXPECT_EQ(thin, reference);
  // Shorter than a unit along y: one unit long along y.
  const fx::QQuadric flat =
      q.quantize(Quadric::cone({0.5f, 0.5f, 0.5f}, float(4 * unit), {0.5f, float(0.5 + 0.2 * unit), 0.5f}, float(4 * unit)), 4);
  EXPECT_EQ(flat.axis[0], 0);
  EXPECT_EQ(std::abs(flat.axis[1]), 1);
  EXPECT_EQ(flat.axis[2], 0);
}

TEST(DriverQuadricQuantizer, NamesAQuadricOutsideTheLattice) {
  const Quantizer q(unitCube());
  try {
    q.quantize(Quadric::sphere({40.0f, 0.5f, 0.5f}, 0.1f), 12);
    FAIL() << "a center off the lattice was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sphere 12 center"), std::string::npos) << e.what();
  }
}

// A scene of 2 triangles, 2 spheres (a glass one) and a cone, read natively.
struct NativeJob {
  Scene scene = loadNff(std::string(LANCER_TEST_DATA) + "/quadrics.nff", [] {
    NffOptions o;
    o.quadrics = QuadricForm::Native;
    return o;
  }());
  PinholeCamera camera = frameScene(scene, CameraOptions::sized(32, 32));
  std::vector<Ray> rays = camera.generateRays();
  Quantizer quantizer{scene.bounds};
  Bvh bvh{scene, AccelOptions{}};

  JobResult run(IsectDevice& model) {
    GoldenIsectDevice golden;
    return runIsectJob(scene, quantizeRays(quantizer, rays), quantizer,
                       bvhCandidates(bvh, 2.0f * float(quantizer.unit())), model, golden, JobConfig{});
  }
};

TEST(DriverQuadricJob, EveryModelMatchesGoldenOnAMixedScene) {
  NativeJob n;
  ASSERT_EQ(n.scene.primitivesByKind().spheres, 2u);
  ASSERT_EQ(n.scene.primitivesByKind().cones, 1u);
  GoldenIsectDevice golden;
  const JobResult ideal = n.run(golden);
  size_t onQuadrics = 0;
  for (const auto& h : ideal.hits) onQuadrics += h && h->primId >= n.scene.size();
  EXPECT_GT(onQuadrics, n.rays.size() / 10) << "the camera sees the quadrics";
  EXPECT_EQ(ideal.firstQuadric, n.scene.size());

  // Every model this build has (a tree without the hardware models, the
  // sanitizers', has golden alone).
  for (const std::string& name : isectDeviceNames()) {
    if (name == "golden") continue;
    const std::unique_ptr<IsectDevice> model = makeIsectDevice(name);
    const JobResult job = n.run(*model);
    EXPECT_EQ(job.mismatchedRays, 0u) << model->name();
    EXPECT_FALSE(job.firstMismatch.has_value()) << model->name();
    EXPECT_EQ(job.hits, ideal.hits) << model->name();
    EXPECT_TRUE(job.cycleAccurate) << model->name();
    EXPECT_GT(job.cycles, 0u) << model->name();
  }
}

TEST(DriverQuadricJob, AgreesWithTheReferenceWithinTheLatticeBound) {
  NativeJob n;
  GoldenIsectDevice golden;
  const JobResult job = n.run(golden);
  const auto reference = traceRays(n.bvh, n.rays);
  const ReferenceComparison cmp = compareWithReference(n.scene, n.rays, reference, job, n.quantizer);
  EXPECT_EQ(cmp.arbiter.beyondBound(), 0u);
  EXPECT_LE(cmp.disagreements, n.rays.size() / 50);
  EXPECT_LT(cmp.meanTError, 4.0) << "mean t error in lattice units";
  // A hit on a quadric carries its side: the camera is outside every solid.
  for (size_t i = 0; i < job.hits.size(); ++i) {
    const auto hit = sceneHit(job, i);
    if (hit && n.scene.isQuadric(hit->prim)) {
      EXPECT_EQ(hit->u, 0.0f) << i;
    }
  }
}

}  // namespace
}  // namespace lancer
