#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "driver/isect_device.h"
#include "driver/quantize.h"
#include "ref/accel.h"

namespace lancer {

// Host-side traversal that names each ray's candidate triangles: every triangle
// the hardware's ray could hit must be among them (the reference BVH, queried
// with the dequantized ray and conservatively enlarged boxes).
using CandidateSource = std::function<void(const Ray& latticeRay, std::vector<uint32_t>& out)>;

struct IsectJobConfig {
  StreamOptions stream;
  size_t raysPerBatch = 4096;  // bounds memory: pairs are built and streamed a batch at a time
};

// The first ray on which the model and the golden model disagree, with what it
// takes to reproduce it.
struct Mismatch {
  uint32_t rayId = 0;
  std::string what;           // "pair" (a pipeline output differs) or "count"
  fx::QRay ray;
  std::optional<fx::QTriangle> tri;
  std::optional<fx::IsectResult> model, golden;
};

struct IsectJobResult {
  std::vector<std::optional<QuantizedRay>> rays;       // per ray; nullopt: missed the lattice cube
  std::vector<std::optional<fx::IsectResult>> hits;    // the model's closest hit per ray
  uint64_t intersectionTests = 0;
  uint64_t mismatchedRays = 0;
  std::optional<Mismatch> firstMismatch;
  StreamStats model;   // summed over batches
  double modelSeconds = 0;   // host time inside the model
  double goldenSeconds = 0;  // host time inside the golden model
};

// Streams every (ray, candidate) pair through `model` and through `golden`,
// compares the two output streams record by record, bit for bit, and reduces
// the model's results to each ray's closest hit (fx::closerResult).
IsectJobResult runIsectJob(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                           const CandidateSource& candidates, IsectDevice& model, IsectDevice& golden,
                           const IsectJobConfig& config, const std::function<void(size_t)>& onProgress = {});

}  // namespace lancer
