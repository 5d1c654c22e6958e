// The exact arbiter in the driver's comparison with the float reference
// (sw/driver/report.h): every disagreement judged, the reference never wrong,
// the hardware never beyond its lattice bound, and a hardware answer that is
// really wrong caught as such.

#include <gtest/gtest.h>

#include "driver/candidates.h"
#include "driver/golden_device.h"
#include "driver/isect_job.h"
#include "driver/quantize.h"
#include "driver/report.h"
#include "oracle/exact.h"
#include "ref/bvh.h"
#include "ref/trace.h"
#include "scene/camera.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

// Camera rays through the golden intersection pipeline, compared with the
// reference: each disagreement settled exactly.
void expectEveryDisagreementSettled(const Scene& scene, int size) {
  CameraOptions options;
  options.width = options.height = size;
  const PinholeCamera camera = frameScene(scene, options);
  const std::vector<Ray> rays = camera.generateRays();
  const Quantizer quantizer(scene.bounds);
  const Bvh bvh(scene, AccelOptions{});
  GoldenIsectDevice model, golden;
  const auto job = runIsectJob(scene, quantizeRays(quantizer, rays), quantizer, bvhCandidates(bvh, 2.0f * float(quantizer.unit())), model,
                               golden, JobConfig{});
  const ReferenceComparison cmp = compareWithReference(scene, rays, traceRays(bvh, rays), job, quantizer);
  const ArbiterCounts& a = cmp.arbiter;
  EXPECT_GT(a.judged, 0u);  // every scene here has silhouette pixels the lattice moves
  EXPECT_EQ(a.judged, cmp.disagreements);
  EXPECT_EQ(a.reference[size_t(Verdict::Wrong)], 0u) << "first: " << a.firstReferenceWrong.value_or(0);
  EXPECT_EQ(a.hardware[size_t(Verdict::Wrong)], 0u) << "first: " << a.firstHardwareBeyond.value_or(0);
  uint64_t reference = 0, hardware = 0;
  for (int v = 0; v < 4; ++v) {
    reference += a.reference[size_t(v)];
    hardware += a.hardware[size_t(v)];
  }
  EXPECT_EQ(reference, a.judged);
  EXPECT_EQ(hardware, a.judged);
}

// (At 128x128 the lattice moves no Cornell pixel any more: its walls lie on the
// scene's bounds, and before the lattice's margin the floor's front edge flipped.)
TEST(DriverArbiter, SettlesEveryDisagreementOnTheCornellBox) { expectEveryDisagreementSettled(makeCornellBox(), 384); }

TEST(DriverArbiter, SettlesEveryDisagreementOnTheBunny) { expectEveryDisagreementSettled(loadScene(test::kBunny), 128); }

TEST(DriverArbiter, SettlesEveryDisagreementOnAnOpenCadMesh) {
  expectEveryDisagreementSettled(loadScene(test::kAssimpModels + "/OBJ/regr01.obj"), 128);
}

// The lattice bound itself: a hardware hit on a triangle the ray misses by a
// lattice unit is within it, one it misses by a thousand units is not.
TEST(DriverArbiter, LatticeBoundSeparatesRoundingFromErrors) {
  Scene scene;
  scene.name = "two squares";
  // A square in z = 0 and a far one beside it, in a scene 1000 units wide.
  scene.triangles = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1000, 1000, 0}, {999, 1000, 0}, {1000, 999, 0}}};
  scene.materialOf = {0, 0};
  scene.materials.resize(1);
  scene.computeBounds();
  const Quantizer quantizer(scene.bounds);
  const ExactOracle oracle(scene);
  const double unit = quantizer.unit();
  const auto lattice = [&](const Ray& ray) {
    const auto q = quantizer.quantize(ray, 0);
    EXPECT_TRUE(q.has_value());
    return ToleranceOf([&, q](const Triangle& tri) { return latticeTolerance(*q, quantizer, ray, tri); });
  };
  // Just outside triangle 0's hypotenuse, by a tenth of a lattice unit: a hit there is rounding.
  const float off = float(0.1 * unit);
  const Ray near{{0.5f + off, 0.5f + off, 1}, {0, 0, -1}, kInfinity};
  ASSERT_FALSE(oracle.intersect(near));
  EXPECT_EQ(judge(oracle, near, Hit{0, 1}, oracle.intersect(near), lattice(near)).verdict, Verdict::Rounding);
  // Float rounding alone does not excuse it.
  EXPECT_EQ(judge(oracle, near, Hit{0, 1}, oracle.intersect(near)).verdict, Verdict::Wrong);
  // Thirty lattice units away: wrong for the hardware too.
  const float far = float(30 * unit);
  const Ray away{{0.5f + far, 0.5f + far, 1}, {0, 0, -1}, kInfinity};
  EXPECT_EQ(judge(oracle, away, Hit{0, 1}, oracle.intersect(away), lattice(away)).verdict, Verdict::Wrong);
  // A t off by far more than the bound on the right triangle: wrong.
  const Ray inside{{0.25f, 0.25f, 1}, {0, 0, -1}, kInfinity};
  EXPECT_EQ(judge(oracle, inside, Hit{0, 1.0f + float(20 * unit)}, oracle.intersect(inside), lattice(inside)).verdict,
            Verdict::Wrong);
  EXPECT_EQ(judge(oracle, inside, Hit{0, 1.0f + float(unit)}, oracle.intersect(inside), lattice(inside)).verdict,
            Verdict::Correct);
}

}  // namespace
}  // namespace lancer
