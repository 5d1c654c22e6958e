// The traversal-unit job (grid, octree): golden against itself is exact, the
// counters add up, and a wrong visit sequence is reported with both sequences.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/job.h"
#include "driver/traversal_job.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "support/cornell_rays.h"

namespace lancer {
namespace {


std::map<std::string, double> counters(const JobResult& job) {
  std::map<std::string, double> out;
  for (const JobCounter& c : job.counters) out[c.key] = c.value;
  return out;
}

// Golden, except that one ray's visit sequence loses its last element.
template <class Image, class Golden>
class DropLastVisit final : public TraversalDevice<Image> {
 public:
  explicit DropLastVisit(uint32_t victim) : victim_(victim) {}
  std::string_view name() const override { return "faulty"; }
  int maxRaysInFlight() const override { return 1; }
  TraversalRunStats run(const Image& image, std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                        const TraversalRunOptions& options) override {
    const TraversalRunStats stats = golden_.run(image, rays, traces, options);
    for (size_t k = 0; k < rays.size(); ++k) {
      if (rays[k].id == victim_ && !traces[k].visits.empty()) traces[k].visits.pop_back();
    }
    return stats;
  }

 private:
  uint32_t victim_;
  Golden golden_;
};

TEST(DriverTraversalJob, EveryUnitIsExactAgainstItselfAndCountsWhatItDid) {
  CornellRays c(24);
  for (const fx::UnitKind path : {fx::UnitKind::Grid, fx::UnitKind::Octree}) {
    SCOPED_TRACE(toString(path));
    const JobResult job = runJob(path, c.scene, c.rays, c.quantizer, JobConfig{});
    EXPECT_EQ(job.mismatchedRays, 0u);
    EXPECT_FALSE(job.cycleAccurate);
    auto k = counters(job);
    const std::string steps = path == fx::UnitKind::Grid ? "voxel_steps" : "node_steps";
    const std::string reads = path == fx::UnitKind::Grid ? "cell_reads" : "node_reads";
    EXPECT_GT(k[steps], double(c.rays.size()) / 2) << "most rays enter a few elements";
    EXPECT_EQ(k["index_reads"], double(job.intersectionTests));
    EXPECT_EQ(k["triangle_reads"], double(job.intersectionTests));
    EXPECT_EQ(k["memory_reads"], k[reads] + k["index_reads"] + k["triangle_reads"]);
    EXPECT_FALSE(k.contains("isect_utilization")) << "no timing figures from the golden model";
    size_t hits = 0;
    for (const auto& h : job.hits) hits += h.has_value();
    EXPECT_GT(hits, c.rays.size() * 9 / 10) << "the closed Cornell box catches nearly every camera ray";
  }
}

TEST(DriverTraversalJob, OctreeReadsCountTheChildGroupBuffer) {
  CornellRays c(24);
  const fx::OctreeImage image = buildImageFor<fx::OctreeUnit>(c.scene, c.quantizer, AccelOptions{.octreeMaxDepth = 4});
  GoldenOctreeDevice golden;
  std::vector<fx::QRay> rays;
  for (uint32_t i = 0; i < c.rays.size(); ++i) {
    if (auto q = c.quantizer.quantize(c.rays[i], i)) rays.push_back(q->q);
  }
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunStats stats = golden.run(image, rays, traces);
  uint64_t interior = 0;
  for (const auto& t : traces) {
    for (uint32_t node : t.visits) interior += !image.nodes[node].leaf;
  }
  // Every interior node entered reads its children; walking back up and on to
  // an uncle's subtree re-reads that level's group.
  EXPECT_GT(stats.nodeReads, interior);
  EXPECT_LT(stats.nodeReads, stats.steps);
}

TEST(DriverTraversalJob, AWrongVisitSequenceIsReportedWithBothSequences) {
  CornellRays c(24);
  const uint32_t victim = 12 * 24 + 12;
  for (const std::string accel : {"grid", "octree"}) {
    SCOPED_TRACE(accel);
    JobResult job;
    if (accel == "grid") {
      DropLastVisit<fx::GridImage, GoldenGridDevice> model(victim);
      GoldenGridDevice golden;
      job = runTraversalJob(buildImageFor<fx::GridUnit>(c.scene, c.quantizer, {}), quantizeRays(c.quantizer, c.rays), model, golden, {});
    } else {
      DropLastVisit<fx::OctreeImage, GoldenOctreeDevice> model(victim);
      GoldenOctreeDevice golden;
      job = runTraversalJob(buildImageFor<fx::OctreeUnit>(c.scene, c.quantizer, {}), quantizeRays(c.quantizer, c.rays), model, golden, {});
    }
    EXPECT_EQ(job.mismatchedRays, 1u);
    ASSERT_TRUE(job.firstMismatch.has_value());
    EXPECT_EQ(job.firstMismatch->rayId, victim);
    const std::string& text = job.firstMismatch->details;
    EXPECT_NE(text.find(fmt::format("first mismatch: ray {} ({} unit)", victim, accel)), std::string::npos) << text;
    EXPECT_NE(text.find("model  from step"), std::string::npos) << text;
    EXPECT_NE(text.find("golden from step"), std::string::npos) << text;
  }
}

TEST(DriverTraversalJob, ImpossibleConfigurationsAreInputErrors) {
  CornellRays c(24);
  JobConfig config;
  config.raysInFlight = 1 << 20;
  EXPECT_THROW(runJob(fx::UnitKind::Octree, c.scene, c.rays, c.quantizer, config), InputError);
  config = {};
  config.memLatency = 0;
  EXPECT_THROW(runJob(fx::UnitKind::Grid, c.scene, c.rays, c.quantizer, config), InputError);
  config = {};
  config.accel.octreeMaxDepth = fx::kOctreeMaxDepth + 1;
  EXPECT_THROW(runJob(fx::UnitKind::Octree, c.scene, c.rays, c.quantizer, config), InputError);
  EXPECT_THROW(parseHardwarePath("kdtree"), InputError);
}

// --accel names each path by its unit: the pipeline behind the host BVH is
// "isect"; "bvh" is the reference tracer's structure, no hardware path.
TEST(DriverJob, HardwarePathsAreNamedByTheirUnits) {
  EXPECT_EQ(hardwarePathNames(), (std::vector<std::string>{"isect", "grid", "octree", "bvh"}));
  EXPECT_EQ(parseHardwarePath("isect"), fx::UnitKind::Isect);
  EXPECT_EQ(parseHardwarePath("bvh"), fx::UnitKind::Bvh);
  EXPECT_EQ(toString(fx::UnitKind::Isect), "isect");
  try {
    parseHardwarePath("kdtree");
    ADD_FAILURE() << "kdtree should name no hardware path";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "no hardware path for --accel kdtree (available: isect, grid, octree, bvh)");
  }
}

}  // namespace
}  // namespace lancer
