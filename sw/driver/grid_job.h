#pragma once

#include "driver/grid_device.h"
#include "driver/job.h"

namespace lancer {

// The grid's memory image for a scene: triangles quantized, resolution from
// AccelOptions::gridResolution (a cube of that many cells a side) or the
// golden model's heuristic.
fx::GridImage buildGridImageFor(const Scene& scene, const Quantizer& quantizer, const AccelOptions& options);

// Runs every ray that enters the lattice through `model` and `golden` and
// compares, per ray, bit for bit: the cells visited in order, the tests
// issued, and the closest hit record.
JobResult runGridJob(const fx::GridImage& image, std::span<const Ray> rays, const Quantizer& quantizer,
                     GridDevice& model, GridDevice& golden, const JobConfig& config,
                     const ProgressFn& onProgress = {});

// The reproducer text of a grid mismatch: the ray, both cell sequences from the
// first difference, both hit records.
std::string describeGridMismatch(const fx::QRay& ray, const fx::GridTrace& model, const fx::GridTrace& golden);

}  // namespace lancer
