#include "driver/job.h"

#include <chrono>

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
class IsectPath final : public HardwarePath {
 public:
  IsectPath(const Scene& scene, const Quantizer& quantizer, const JobConfig& config)
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

// A traversal unit (its descriptor `Unit`): its model against its golden
// model, over the image the driver builds for the scene.
template <class Unit>
class TraversalPath final : public HardwarePath {
 public:
  TraversalPath(const Scene& scene, const Quantizer& quantizer, const JobConfig& config)
      : config_(config), model_(makeTraversalDevice<Unit>(config.model)), image_([&] {
          const auto start = std::chrono::steady_clock::now();
          auto image = buildImageFor<Unit>(scene, quantizer, config.accel);
          buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          return image;
        }()) {}
  // The memory hierarchy lives as long as the path: its caches stay warm
  // from batch to batch and wave to wave. (The fixed memory holds no state
  // worth keeping: each run makes its own, as a single unit always did.)
  JobResult run(std::span<const std::optional<QuantizedRay>> rays, const ProgressFn& onProgress) override {
    if (config_.memory.kind == mem::MemoryKind::Hierarchy && !memory_) {
      const TraversalRunOptions options = traversalOptionsOf(config_);
      checkChipOptions(options);
      memory_ = mem::MemorySystem::make(memoryConfigOf(options), addressMapOf<Unit>(image_), config_.units);
    }
    JobResult result = runTraversalJob(image_, rays, *model_, golden_, config_, onProgress, memory_.get());
    result.addCounter("build_seconds", "build seconds", buildSeconds_);
    return result;
  }
  std::vector<JobCounter> structure() const override {
    std::vector<JobCounter> figures = imageFigures<Unit>(image_);
    figures.push_back({"build_seconds", "build seconds", buildSeconds_});
    return figures;
  }

 private:
  JobConfig config_;
  std::unique_ptr<DeviceOf<Unit>> model_;
  GoldenTraversalDevice<typename Unit::Image> golden_;
  double buildSeconds_ = 0;  // the image's build (quantizing the triangles included); set by image_'s initializer
  typename Unit::Image image_;
  std::unique_ptr<mem::MemorySystem> memory_;
};

}  // namespace

std::vector<fx::UnitKind> hardwarePaths() {
  std::vector<fx::UnitKind> paths{fx::UnitKind::Isect};
  fx::forEachTraversalUnit([&](auto unit) { paths.push_back(decltype(unit)::kKind); });
  return paths;
}

std::vector<std::string> hardwarePathNames() {
  std::vector<std::string> names;
  for (fx::UnitKind path : hardwarePaths()) names.emplace_back(toString(path));
  return names;
}

std::string_view toString(fx::UnitKind path) {
  std::string_view name = "isect";
  fx::forEachTraversalUnit([&](auto unit) {
    if (decltype(unit)::kKind == path) name = decltype(unit)::kNames.unit;
  });
  return name;
}

fx::UnitKind parseHardwarePath(std::string_view name) {
  for (fx::UnitKind path : hardwarePaths()) {
    if (toString(path) == name) return path;
  }
  throw InputError(
      fmt::format("no hardware path for --accel {} (available: {})", name, fmt::join(hardwarePathNames(), ", ")));
}

std::vector<std::string> modelsFor(fx::UnitKind path) {
  std::vector<std::string> models = isectDeviceNames();
  fx::forEachTraversalUnit([&](auto unit) {
    if (decltype(unit)::kKind == path) models = traversalDeviceNames<decltype(unit)>();
  });
  return models;
}

QuantizedRays quantizeRays(const Quantizer& quantizer, std::span<const Ray> rays) {
  QuantizedRays out(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) out[i] = quantizer.quantize(rays[i], uint32_t(i));
  return out;
}

std::unique_ptr<HardwarePath> makeHardwarePath(fx::UnitKind path, const Scene& scene, const Quantizer& quantizer,
                                               const JobConfig& config) {
  std::unique_ptr<HardwarePath> made;
  fx::forEachTraversalUnit([&](auto unit) {
    using Unit = decltype(unit);
    if (Unit::kKind == path) made = std::make_unique<TraversalPath<Unit>>(scene, quantizer, config);
  });
  if (made) return made;
  if (config.schedule != Schedule::Fifo) {
    throw InputError(fmt::format("--schedule {}: the isect path has no dispatcher (the host's BVH hands the pipeline "
                                 "its pairs ray by ray); schedules are for the traversal units",
                                 toString(config.schedule)));
  }
  return std::make_unique<IsectPath>(scene, quantizer, config);
}

JobResult runJob(fx::UnitKind path, const Scene& scene, std::span<const Ray> rays,
                 const Quantizer& quantizer, const JobConfig& config, const ProgressFn& onProgress) {
  return makeHardwarePath(path, scene, quantizer, config)->run(quantizeRays(quantizer, rays), onProgress);
}

}  // namespace lancer
