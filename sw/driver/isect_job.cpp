#include "driver/isect_job.h"

#include <chrono>

#include "golden/isect.h"

namespace lancer {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

IsectJobResult runIsectJob(const Scene& scene, std::span<const Ray> rays, const Quantizer& quantizer,
                           const CandidateSource& candidates, IsectDevice& model, IsectDevice& golden,
                           const IsectJobConfig& config, const std::function<void(size_t)>& onProgress) {
  IsectJobResult job;
  job.rays.resize(rays.size());
  job.hits.resize(rays.size());

  // Triangles are quantized once; shared vertices quantize to the same integers.
  std::vector<fx::QTriangle> triangles(scene.size());
  for (uint32_t i = 0; i < scene.size(); ++i) triangles[i] = quantizer.quantize(scene.triangles[i], i);

  std::vector<IsectRequest> requests;
  std::vector<fx::IsectResult> modelOut, goldenOut;
  std::vector<uint32_t> found;
  std::vector<bool> rayMismatched;
  for (size_t begin = 0; begin < rays.size(); begin += config.raysPerBatch) {
    const size_t end = std::min(rays.size(), begin + config.raysPerBatch);
    requests.clear();
    for (size_t i = begin; i < end; ++i) {
      job.rays[i] = quantizer.quantize(rays[i], uint32_t(i));
      if (!job.rays[i]) continue;
      const fx::QRay& q = job.rays[i]->q;
      const glm::dvec3 origin = quantizer.sceneOrigin(q);
      const Ray latticeRay{glm::vec3(origin), glm::vec3(quantizer.sceneDirection(q))};
      found.clear();
      candidates(latticeRay, found);
      for (uint32_t prim : found) requests.push_back({q, triangles[prim]});
    }
    job.intersectionTests += requests.size();

    modelOut.clear();
    goldenOut.clear();
    auto start = std::chrono::steady_clock::now();
    const StreamStats stats = model.run(requests, modelOut, config.stream);
    job.modelSeconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    golden.run(requests, goldenOut, {});
    job.goldenSeconds += secondsSince(start);
    job.model.cycles += stats.cycles;
    job.model.requests += stats.requests;
    job.model.results += stats.results;
    job.model.inputStalls += stats.inputStalls;
    job.model.cycleAccurate = stats.cycleAccurate;

    // Bit-for-bit, in stream order: the pipeline keeps order, so record k of the
    // model answers request k.
    rayMismatched.assign(end - begin, false);
    const size_t common = std::min(modelOut.size(), goldenOut.size());
    for (size_t k = 0; k < requests.size(); ++k) {
      const uint32_t rayId = requests[k].ray.id;
      const bool present = k < common;
      if (present && modelOut[k] == goldenOut[k]) {
        if (modelOut[k].hit) {
          auto& best = job.hits[rayId];
          if (!best || fx::closerResult(modelOut[k], *best)) best = modelOut[k];
        }
        continue;
      }
      rayMismatched[rayId - begin] = true;
      if (!job.firstMismatch) {
        Mismatch m;
        m.rayId = rayId;
        m.what = present ? "pair" : "count";
        m.ray = requests[k].ray;
        m.tri = requests[k].tri;
        if (k < modelOut.size()) m.model = modelOut[k];
        if (k < goldenOut.size()) m.golden = goldenOut[k];
        job.firstMismatch = m;
      }
      // Keep the model's answer for the image and hits file even when it is wrong.
      if (k < modelOut.size() && modelOut[k].hit) {
        auto& best = job.hits[rayId];
        if (!best || fx::closerResult(modelOut[k], *best)) best = modelOut[k];
      }
    }
    if (modelOut.size() > requests.size() && !job.firstMismatch) {
      Mismatch m;
      m.rayId = modelOut[requests.size()].rayId;
      m.what = "count";
      m.model = modelOut[requests.size()];
      job.firstMismatch = m;
    }
    for (bool bad : rayMismatched) job.mismatchedRays += bad;
    if (onProgress) onProgress(end - begin);
  }
  return job;
}

}  // namespace lancer
