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

// The host BVH feeding the intersection pipeline.
class BvhPath final : public HardwarePath {
 public:
  BvhPath(const Scene& scene, const Quantizer& quantizer, const JobConfig& config)
      : scene_(scene), quantizer_(quantizer), config_(config), model_(makeIsectDevice(config.model)),
        bvh_(scene, AccelOptions{}),
        candidates_(bvhCandidates(bvh_, kCandidateMarginUnits * float(quantizer.unit()))) {}
  JobResult run(std::span<const std::optional<QuantizedRay>> rays, const ProgressFn& onProgress) override {
    return runIsectJob(scene_, rays, quantizer_, candidates_, *model_, golden_, config_, onProgress);
  }

 private:
  const Scene& scene_;
  const Quantizer& quantizer_;
  JobConfig config_;
  std::unique_ptr<IsectDevice> model_;
  GoldenIsectDevice golden_;
  Bvh bvh_;
  CandidateSource candidates_;
};

// A traversal unit: its model against its golden model, over the image the
// driver builds for the scene.
template <class Image, auto makeDevice, auto buildImageFor>
class TraversalPath final : public HardwarePath {
 public:
  TraversalPath(const Scene& scene, const Quantizer& quantizer, const JobConfig& config)
      : config_(config), model_(makeDevice(config.model)), image_(buildImageFor(scene, quantizer, config.accel)) {}
  JobResult run(std::span<const std::optional<QuantizedRay>> rays, const ProgressFn& onProgress) override {
    return runTraversalJob(image_, rays, *model_, golden_, config_, onProgress);
  }

 private:
  JobConfig config_;
  std::unique_ptr<TraversalDevice<Image>> model_;
  GoldenTraversalDevice<Image> golden_;
  Image image_;
};

}  // namespace

std::vector<std::string> hardwareAccels() { return {"bvh", "grid", "octree"}; }

std::vector<std::string> modelsFor(const std::string& accel) {
  if (accel == "bvh") return isectDeviceNames();
  if (accel == "grid") return gridDeviceNames();
  if (accel == "octree") return octreeDeviceNames();
  return {};
}

QuantizedRays quantizeRays(const Quantizer& quantizer, std::span<const Ray> rays) {
  QuantizedRays out(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) out[i] = quantizer.quantize(rays[i], uint32_t(i));
  return out;
}

std::unique_ptr<HardwarePath> makeHardwarePath(const std::string& accel, const Scene& scene,
                                               const Quantizer& quantizer, const JobConfig& config) {
  if (accel == "bvh") return std::make_unique<BvhPath>(scene, quantizer, config);
  if (accel == "grid") {
    return std::make_unique<TraversalPath<fx::GridImage, makeGridDevice, buildGridImageFor>>(scene, quantizer, config);
  }
  if (accel == "octree") {
    return std::make_unique<TraversalPath<fx::OctreeImage, makeOctreeDevice, buildOctreeImageFor>>(scene, quantizer,
                                                                                                   config);
  }
  throw InputError(fmt::format("no hardware path for --accel {} (available: {})", accel, fmt::join(hardwareAccels(), ", ")));
}

JobResult runJob(const std::string& accel, const Scene& scene, std::span<const Ray> rays,
                 const Quantizer& quantizer, const JobConfig& config, const ProgressFn& onProgress) {
  return makeHardwarePath(accel, scene, quantizer, config)->run(quantizeRays(quantizer, rays), onProgress);
}

}  // namespace lancer
