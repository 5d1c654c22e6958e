#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/candidates.h"
#include "driver/golden_device.h"
#include "driver/isect_job.h"
#include "driver/quantize.h"
#include "driver/report.h"
#include "golden/isect.h"
#include "ref/bvh.h"
#include "ref/trace.h"
#include "scene/camera.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

Aabb box(glm::vec3 lo, glm::vec3 hi) {
  Aabb b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(DriverQuantizer, MapsTheBoundingCubeOntoTheLattice) {
  const Quantizer q(box({-1, -2, -3}, {1, 2, 3}));  // longest axis z: 6 units
  const fx::QTriangle t = q.quantize(Triangle{{0, 0, -3}, {0, 0, 3}, {1, 2, 0}}, 9);
  EXPECT_EQ(t.id, 9u);
  // The bounds fill the lattice but for its margin on either side.
  EXPECT_EQ(t.v[0][2], kLatticeMarginUnits);
  EXPECT_EQ(t.v[1][2], fx::kPosMax - kLatticeMarginUnits);
  // The cube is centred on the bounds: x = 0 lands on the lattice's middle,
  // 2^P / 2 - 1/2, which rounds to either neighbour.
  EXPECT_LE(std::abs(double(t.v[0][0]) - 0.5 * double(fx::kPosMax)), 0.5);
  EXPECT_NEAR(q.unit(), 6.0 / double(fx::kPosMax - 2 * kLatticeMarginUnits), 1e-12);
}

TEST(DriverQuantizer, RejectsCoordinatesOutsideTheFormat) {
  const Quantizer q(box({0, 0, 0}, {1, 1, 1}));
  // Beyond the lattice's margin, by a unit.
  const float justOutside = 1.0f + float(kLatticeMarginUnits + 1) * float(q.unit());
  try {
    q.quantize(Triangle{{0, 0, 0}, {justOutside, 0, 0}, {0, 1, 0}}, 4);
    FAIL() << "expected an out-of-range error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 4 vertex 1"), std::string::npos) << e.what();
  }
  // The bounds themselves are fine and land inside the margin.
  const fx::QTriangle t = q.quantize(Triangle{{0, 0, 0}, {1, 1, 1}, {0, 1, 0}}, 0);
  EXPECT_EQ(t.v[1][0], fx::kPosMax - kLatticeMarginUnits);
  EXPECT_THROW(q.quantize(Triangle{{-0.01f, 0, 0}, {1, 1, 1}, {0, 1, 0}}, 0), InputError);
}

// Found by tests/fuzz/fuzz_quantize: empty or non-finite bounds gave a NaN
// lattice origin, from which every ray quantized to a made-up origin.
TEST(DriverQuantizer, RejectsEmptyOrNonFiniteBounds) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  EXPECT_THROW(Quantizer{Aabb{}}, InputError);  // the empty box of a scene without triangles
  EXPECT_THROW(Quantizer(Aabb{{nan, 0, 0}, {1, 1, 1}}), InputError);  // (box() would drop the NaN)
  EXPECT_THROW(Quantizer(Aabb{{0, 0, 0}, {1, inf, 1}}), InputError);
  try {
    Quantizer{Aabb{}};
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene bounds"), std::string::npos) << e.what();
  }
  // A point-like scene is fine: it still gets a lattice around the point.
  const Quantizer point(box({2, 2, 2}, {2, 2, 2}));
  EXPECT_TRUE(point.quantize(Ray{{2, 2, 0}, {0, 0, 1}}, 0).has_value());
}

TEST(DriverQuantizer, ClipsRaysAndNormalizesDirections) {
  const Quantizer q(box({0, 0, 0}, {1, 1, 1}));
  // From outside, along -z with a -0.0 component: clipped to the z = 1 face.
  const auto r = q.quantize(Ray{{0.5f, 0.25f, 3.0f}, {-0.0f, 0.0f, -2.0f}}, 3);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->q.dir[2], -fx::kDirMax);
  EXPECT_EQ(r->q.dir[0], 0);
  EXPECT_EQ(r->q.dir[1], 0);
  EXPECT_EQ(r->q.org[2], fx::kPosMax);
  // 2 units at |d| = 2 to the scene's face, less the margin beyond it.
  EXPECT_NEAR(r->tEnter, 1.0 - double(kLatticeMarginUnits) * q.unit() / 2.0, 1e-12);
  // A ray that misses the cube, and one that points away from it.
  EXPECT_FALSE(q.quantize(Ray{{2, 2, 2}, {1, 0, 0}}, 0).has_value());
  EXPECT_FALSE(q.quantize(Ray{{0.5f, 0.5f, 2}, {0, 0, 1}}, 0).has_value());
  // Origin inside: no clipping.
  const auto inside = q.quantize(Ray{{0.5f, 0.5f, 0.5f}, {1, 1, 0}}, 0);
  ASSERT_TRUE(inside.has_value());
  EXPECT_EQ(inside->tEnter, 0.0);
  EXPECT_EQ(inside->q.dir[0], fx::kDirMax);
  EXPECT_EQ(inside->q.dir[1], fx::kDirMax);
}

// A device that is wrong on purpose: flips one bit of the t numerator of one pair.
class FaultyDevice final : public IsectDevice {
 public:
  explicit FaultyDevice(uint32_t badRay) : badRay_(badRay) {}
  std::string_view name() const override { return "faulty"; }
  StreamStats run(std::span<const IsectRequest> requests, std::vector<fx::IsectResult>& results,
                  const StreamOptions& options) override {
    const StreamStats stats = golden_.run(requests, results, options);
    for (auto& r : results) {
      if (r.rayId == badRay_ && r.hit) {
        r.tNum ^= 4;
        break;
      }
    }
    return stats;
  }
  StreamStats runQuadrics(std::span<const QuadricRequest> requests, std::vector<fx::IsectResult>& results,
                          const StreamOptions& options) override {
    return golden_.runQuadrics(requests, results, options);
  }

 private:
  GoldenIsectDevice golden_;
  uint32_t badRay_;
};

struct CornellJob {
  Scene scene = makeCornellBox();
  PinholeCamera camera = frameScene(scene, CameraOptions::sized(32, 32));
  std::vector<Ray> rays = camera.generateRays();
  Quantizer quantizer{scene.bounds};
  Bvh bvh{scene, AccelOptions{}};
};

TEST(DriverJob, GoldenAgainstItselfIsExactAndMatchesTheReference) {
  CornellJob c;
  GoldenIsectDevice model, golden;
  const auto job = runIsectJob(c.scene, quantizeRays(c.quantizer, c.rays), c.quantizer, bvhCandidates(c.bvh, 2.0f * float(c.quantizer.unit())),
                               model, golden, JobConfig{});
  EXPECT_EQ(job.mismatchedRays, 0u);
  EXPECT_FALSE(job.firstMismatch.has_value());
  EXPECT_GT(job.intersectionTests, c.rays.size());
  const auto reference = traceRays(c.bvh, c.rays);
  const ReferenceComparison cmp = compareWithReference(c.scene, c.rays, reference, job, c.quantizer);
  // At 32x32 the Cornell box has few silhouettes thin enough for 16-bit positions
  // to flip; at the narrow 10-bit lattice (64x coarser) more edge pixels move.
  EXPECT_LE(cmp.disagreements, fx::kPosBits >= 16 ? 2u : 32u);
  EXPECT_LT(cmp.meanTError, 4.0) << "mean t error in lattice units";
}

TEST(DriverJob, ReportsTheFirstMismatchAsAReproducer) {
  CornellJob c;
  const uint32_t bad = 16 * 32 + 16;  // the centre pixel hits the back wall
  FaultyDevice model(bad);
  GoldenIsectDevice golden;
  const auto job = runIsectJob(c.scene, quantizeRays(c.quantizer, c.rays), c.quantizer, bvhCandidates(c.bvh, 2.0f * float(c.quantizer.unit())),
                               model, golden, JobConfig{});
  EXPECT_EQ(job.mismatchedRays, 1u);
  ASSERT_TRUE(job.firstMismatch.has_value());
  EXPECT_EQ(job.firstMismatch->rayId, bad);
  const std::string& text = job.firstMismatch->details;
  EXPECT_NE(text.find(fmt::format("ray {}", bad)), std::string::npos) << text;
  EXPECT_NE(text.find("differing bits of isect_res_t"), std::string::npos) << text;
  EXPECT_NE(text.find("wire "), std::string::npos) << "inputs in hex: " << text;
  // Bit 2 of t_num differs: its position is after v_num, u_num and det.
  const int bit = 2 + 2 * fx::kBaryBits + fx::kDetAbsBits;
  EXPECT_NE(text.find(fmt::format(" {}\n", bit)), std::string::npos) << text;
}

TEST(DriverCandidates, IncludeEveryTriangleTheHardwareRayHits) {
  const Scene scene = loadScene(test::kBunny);
  const Quantizer quantizer(scene.bounds);
  const Bvh bvh(scene, AccelOptions{});
  const CandidateSource source = bvhCandidates(bvh, 2.0f * float(quantizer.unit()));
  std::vector<fx::QTriangle> triangles;
  for (uint32_t i = 0; i < scene.size(); ++i) triangles.push_back(quantizer.quantize(scene.triangles[i], i));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const glm::vec3 c = scene.bounds.center(), e = scene.bounds.diagonal();
  std::vector<uint32_t> found;
  int checked = 0;
  for (int i = 0; i < 300; ++i) {
    const Ray ray{c + 0.6f * e * glm::vec3(unit(rng), unit(rng), unit(rng)), {unit(rng), unit(rng), unit(rng)}};
    if (ray.dir == glm::vec3(0.0f)) continue;
    const auto q = quantizer.quantize(ray, uint32_t(i));
    if (!q) continue;
    found.clear();
    source(Ray{glm::vec3(quantizer.sceneOrigin(q->q)), glm::vec3(quantizer.sceneDirection(q->q))}, found);
    std::sort(found.begin(), found.end());
    for (uint32_t t = 0; t < scene.size(); ++t) {
      if (fx::intersect(q->q, triangles[t]).hit) {
        ASSERT_TRUE(std::binary_search(found.begin(), found.end(), t)) << "ray " << i << " triangle " << t;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace lancer
