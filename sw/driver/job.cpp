#include "driver/job.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/candidates.h"
#include "driver/devices.h"
#include "driver/golden_device.h"
#include "driver/traversal_job.h"
#include "driver/isect_job.h"
#include "ref/bvh.h"

namespace lancer {

namespace {

// Host-side candidate boxes grow by this many lattice units, which covers the
// float rounding of the dequantized ray (the hardware's ray itself is exact).
constexpr float kCandidateMarginUnits = 2.0f;

JobResult runBvhPath(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                     const JobConfig& config, const ProgressFn& onProgress) {
  auto model = makeIsectDevice(config.model);
  GoldenIsectDevice golden;
  const Bvh bvh(scene, AccelOptions{});
  return runIsectJob(scene, rays, quantizer, bvhCandidates(bvh, kCandidateMarginUnits * float(quantizer.unit())),
                     *model, golden, config, onProgress);
}

JobResult runGridPath(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                      const JobConfig& config, const ProgressFn& onProgress) {
  auto model = makeGridDevice(config.model);
  GoldenGridDevice golden;
  const fx::GridImage image = buildGridImageFor(scene, quantizer, config.accel);
  return runTraversalJob(image, rays, quantizer, *model, golden, config, onProgress);
}

JobResult runOctreePath(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                        const JobConfig& config, const ProgressFn& onProgress) {
  auto model = makeOctreeDevice(config.model);
  GoldenOctreeDevice golden;
  const fx::OctreeImage image = buildOctreeImageFor(scene, quantizer, config.accel);
  return runTraversalJob(image, rays, quantizer, *model, golden, config, onProgress);
}

}  // namespace

std::vector<std::string> hardwareAccels() { return {"bvh", "grid", "octree"}; }

std::vector<std::string> modelsFor(const std::string& accel) {
  if (accel == "bvh") return isectDeviceNames();
  if (accel == "grid") return gridDeviceNames();
  if (accel == "octree") return octreeDeviceNames();
  return {};
}

JobResult runJob(const std::string& accel, const Scene& scene, std::span<const Ray> rays,
                 const Quantizer& quantizer, const JobConfig& config, const ProgressFn& onProgress) {
  if (accel == "bvh") return runBvhPath(scene, rays, quantizer, config, onProgress);
  if (accel == "grid") return runGridPath(scene, rays, quantizer, config, onProgress);
  if (accel == "octree") return runOctreePath(scene, rays, quantizer, config, onProgress);
  throw InputError(fmt::format("no hardware path for --accel {} (available: {})", accel, fmt::join(hardwareAccels(), ", ")));
}

}  // namespace lancer
