#include "driver/isect_job.h"

#include <chrono>

#include <fmt/format.h>

#include "driver/report.h"
#include "golden/dual.h"
#include "golden/isect.h"

namespace lancer {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string wireHex(const fx::Wire& wire) {
  std::string out;
  for (auto it = wire.rbegin(); it != wire.rend(); ++it) out += fmt::format("{:08x}", *it);
  return out;
}

void keepCloserResult(std::optional<fx::IsectResult>& best, const fx::IsectResult& r) {
  if (r.hit && (!best || fx::closerResult(r, *best))) best = r;
}

}  // namespace

std::string describeMismatch(const Mismatch& m) {
  std::string out = fmt::format("first mismatch: ray {} ({})\n", m.rayId,
                                m.what == "count" ? "the model delivered a different number of results"
                                                  : "a pipeline result differs");
  out += fmt::format("  ray      {}\n           wire {}\n", hexFields(m.ray), wireHex(fx::packWire(m.ray)));
  if (m.tri) out += fmt::format("  triangle {}\n           wire {}\n", hexFields(*m.tri), wireHex(fx::packWire(*m.tri)));
  out += fmt::format("  model    {}\n", m.model ? hexFields(*m.model) : "(no result)");
  out += fmt::format("  golden   {}\n", m.golden ? hexFields(*m.golden) : "(no result)");
  if (m.model && m.golden) {
    out += fmt::format("  differing bits of isect_res_t ({} wide, bit 0 = LSB of v_num):{}\n", fx::kIsectResBits,
                       differingBits(fx::packWire(*m.model), fx::packWire(*m.golden), fx::kIsectResBits));
  }
  return out;
}

JobResult runIsectJob(const Scene& scene, std::span<const std::optional<QuantizedRay>> rays, const Quantizer& quantizer,
                      const CandidateSource& candidates, IsectDevice& model, IsectDevice& golden,
                      const JobConfig& config, const ProgressFn& onProgress) {
  JobResult job;
  job.rays.resize(rays.size());
  job.hits.resize(rays.size());
  uint64_t inputStalls = 0;

  // Triangles are quantized once; shared vertices quantize to the same integers.
  const std::vector<fx::QTriangle> triangles = quantizer.quantize(scene);

  std::vector<IsectRequest> requests;
  std::vector<fx::IsectResult> modelOut, goldenOut;
  std::vector<uint32_t> found;
  std::vector<bool> rayMismatched;
  // Dual precision: per narrow width, the tests its narrow unit rejects, and
  // any it rejected that hit at full width (a broken proof: never, or a bug).
  std::vector<uint64_t> rejected(config.dualNarrowBits.size()), unsound(config.dualNarrowBits.size());
  uint64_t goldenHits = 0;
  for (size_t begin = 0; begin < rays.size(); begin += config.raysPerBatch) {
    const size_t end = std::min(rays.size(), begin + config.raysPerBatch);
    requests.clear();
    for (size_t i = begin; i < end; ++i) {
      job.rays[i] = rays[i];
      if (!job.rays[i]) continue;
      job.rays[i]->q.id = uint32_t(i);
      const fx::QRay& q = job.rays[i]->q;
      found.clear();
      candidates(Ray{glm::vec3(quantizer.sceneOrigin(q)), glm::vec3(quantizer.sceneDirection(q))}, found);
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
    for (size_t k = 0; !config.dualNarrowBits.empty() && k < requests.size() && k < goldenOut.size(); ++k) {
      goldenHits += goldenOut[k].hit;
      for (size_t w = 0; w < config.dualNarrowBits.size(); ++w) {
        if (!fx::narrowRejects(requests[k].ray, requests[k].tri, config.dualNarrowBits[w])) continue;
        ++rejected[w];
        unsound[w] += goldenOut[k].hit;
      }
    }
    job.cycles += stats.cycles;
    job.cycleAccurate = stats.cycleAccurate;
    inputStalls += stats.inputStalls;

    // Bit for bit, in stream order: the pipeline keeps order, so record k of the
    // model answers request k. The model's answers are kept even when wrong, so
    // the image and the hits file show what the model did.
    rayMismatched.assign(end - begin, false);
    for (size_t k = 0; k < std::max(requests.size(), modelOut.size()); ++k) {
      const bool inModel = k < modelOut.size(), inGolden = k < goldenOut.size();
      if (inModel && modelOut[k].rayId >= begin && modelOut[k].rayId < end) {
        keepCloserResult(job.hits[modelOut[k].rayId], modelOut[k]);
      }
      if (inModel && inGolden && modelOut[k] == goldenOut[k]) continue;
      const uint32_t rayId = k < requests.size() ? requests[k].ray.id : modelOut[k].rayId;
      if (rayId >= begin && rayId < end) rayMismatched[rayId - begin] = true;
      if (!job.firstMismatch) {
        Mismatch m;
        m.rayId = rayId;
        m.what = inModel && inGolden ? "pair" : "count";
        if (k < requests.size()) {
          m.ray = requests[k].ray;
          m.tri = requests[k].tri;
        }
        if (inModel) m.model = modelOut[k];
        if (inGolden) m.golden = goldenOut[k];
        job.firstMismatch = MismatchReport{rayId, describeMismatch(m)};
      }
    }
    for (bool bad : rayMismatched) job.mismatchedRays += bad;
    if (onProgress) onProgress(end - begin);
  }
  job.addCounter("input_stall_cycles", "input stall cycles", double(inputStalls));
  const double tests = double(std::max<uint64_t>(job.intersectionTests, 1));
  if (!config.dualNarrowBits.empty()) {
    job.addCounter("dual_hit_share", "dual: hits of tests", double(goldenHits) / tests);
  }
  for (size_t w = 0; w < config.dualNarrowBits.size(); ++w) {
    const int n = config.dualNarrowBits[w];
    job.addCounter(fmt::format("dual_escalated_n{}", n), fmt::format("dual: {}-bit escalates", n),
                   double(job.intersectionTests - rejected[w]) / tests);
    job.addCounter(fmt::format("dual_unsound_n{}", n), fmt::format("dual: {}-bit unsound", n), double(unsound[w]));
  }
  return job;
}

}  // namespace lancer
