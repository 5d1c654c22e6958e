#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "driver/isect_device.h"
#include "driver/job.h"
#include "driver/quantize.h"
#include "ref/accel.h"

namespace lancer {

// Host-side traversal that names each ray's candidate triangles: every triangle
// the hardware's ray could hit must be among them (the reference BVH, queried
// with the dequantized ray and conservatively enlarged boxes).
using CandidateSource = std::function<void(const Ray& latticeRay, std::vector<uint32_t>& out)>;

// The first differing pipeline record, with its inputs.
struct Mismatch {
  uint32_t rayId = 0;
  std::string what;  // "pair" (a pipeline output differs) or "count"
  fx::QRay ray;
  std::optional<fx::QTriangle> tri;
  std::optional<fx::QQuadric> quadric;
  std::optional<fx::IsectResult> model, golden;
};

// The reproducer text of a mismatch: inputs in hex, both records, differing bits.
std::string describeMismatch(const Mismatch& mismatch);

// Streams every (ray, candidate) pair of the rays that entered the lattice
// (rays[k], id k; the candidates ignore segment ends) through `model` and through `golden`,
// compares the two output streams record by record, bit for bit, and reduces
// the model's results to each ray's closest hit (fx::closerResult). The
// candidates are primitive ids: triangles go through the triangle pipeline
// (IsectDevice::run), quadrics through the quadric pipeline beside it
// (runQuadrics); the two run side by side, so a batch takes the longer of
// their cycles.
JobResult runIsectJob(const Scene& scene, std::span<const std::optional<QuantizedRay>> rays, const Quantizer& quantizer,
                      const CandidateSource& candidates, IsectDevice& model, IsectDevice& golden,
                      const JobConfig& config, const ProgressFn& onProgress = {});

}  // namespace lancer
