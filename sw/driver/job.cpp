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

// A traversal unit's path: its model against its golden model, over the image
// the driver builds for the scene.
template <class Image, auto makeDevice, auto buildImageFor>
JobResult runTraversalPath(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                           const JobConfig& config, const ProgressFn& onProgress) {
  auto model = makeDevice(config.model);
  GoldenTraversalDevice<Image> golden;
  const Image image = buildImageFor(scene, quantizer, config.accel);
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
  if (accel == "grid") {
    return runTraversalPath<fx::GridImage, makeGridDevice, buildGridImageFor>(scene, rays, quantizer, config,
                                                                           onProgress);
  }
  if (accel == "octree") {
    return runTraversalPath<fx::OctreeImage, makeOctreeDevice, buildOctreeImageFor>(scene, rays, quantizer, config,
                                                                                 onProgress);
  }
  throw InputError(fmt::format("no hardware path for --accel {} (available: {})", accel, fmt::join(hardwareAccels(), ", ")));
}

}  // namespace lancer
