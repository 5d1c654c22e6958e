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
  if (m.quadric) {
    fx::Wire wire(size_t(fx::wireWords(fx::kIsectQuadricBits)));
    fx::packWire(*m.quadric, wire);
    out += fmt::format("  quadric  {}\n           wire {}\n", hexFields(*m.quadric), wireHex(wire));
  }
  out += fmt::format("  model    {}\n", m.model ? hexFields(*m.model) : "(no result)");
  out += fmt::format("  golden   {}\n", m.golden ? hexFields(*m.golden) : "(no result)");
  if (m.model && m.golden) {
    out += fmt::format("  differing bits of isect_res_t ({} wide, bit 0 = LSB of v_num):{}\n", fx::kIsectResBits,
                       differingBits(fx::packWire(*m.model), fx::packWire(*m.golden), fx::kIsectResBits));
  }
  return out;
}

namespace {

// One pipeline's stream of a batch: its requests, both models' results.
template <class Request>
struct PipelineStream {
  std::vector<Request> requests;
  std::vector<fx::IsectResult> model, golden;
  void clear() {
    requests.clear();
    model.clear();
    golden.clear();
  }
};

void setPrimitive(Mismatch& m, const IsectRequest& r) { m.tri = r.tri; }
void setPrimitive(Mismatch& m, const QuadricRequest& r) { m.quadric = r.quadric; }

// Bit for bit, in stream order: a pipeline keeps order, so record k of the
// model answers request k. The model's answers are kept even when wrong, so
// the image and the hits file show what the model did.
template <class Request>
void compareStream(const PipelineStream<Request>& s, size_t begin, size_t end, JobResult& job,
                   std::vector<bool>& rayMismatched) {
  for (size_t k = 0; k < std::max(s.requests.size(), s.model.size()); ++k) {
    const bool inModel = k < s.model.size(), inGolden = k < s.golden.size();
    if (inModel && s.model[k].rayId >= begin && s.model[k].rayId < end) {
      keepCloserResult(job.hits[s.model[k].rayId], s.model[k]);
    }
    if (inModel && inGolden && s.model[k] == s.golden[k]) continue;
    const uint32_t rayId = k < s.requests.size() ? s.requests[k].ray.id : s.model[k].rayId;
    if (rayId >= begin && rayId < end) rayMismatched[rayId - begin] = true;
    if (!job.firstMismatch) {
      Mismatch m;
      m.rayId = rayId;
      m.what = inModel && inGolden ? "pair" : "count";
      if (k < s.requests.size()) {
        m.ray = s.requests[k].ray;
        setPrimitive(m, s.requests[k]);
      }
      if (inModel) m.model = s.model[k];
      if (inGolden) m.golden = s.golden[k];
      job.firstMismatch = MismatchReport{rayId, describeMismatch(m)};
    }
  }
}

}  // namespace

JobResult runIsectJob(const Scene& scene, std::span<const std::optional<QuantizedRay>> rays, const Quantizer& quantizer,
                      const CandidateSource& candidates, IsectDevice& model, IsectDevice& golden,
                      const JobConfig& config, const ProgressFn& onProgress) {
  JobResult job;
  job.rays.resize(rays.size());
  job.hits.resize(rays.size());
  uint64_t inputStalls = 0;

  // Primitives are quantized once; shared vertices quantize to the same integers.
  const std::vector<fx::QTriangle> triangles = quantizer.quantizeTriangles(scene);
  const std::vector<fx::QQuadric> quadrics = quantizer.quantizeQuadrics(scene);

  if (!quadrics.empty()) job.firstQuadric = uint32_t(triangles.size());
  PipelineStream<IsectRequest> tris;
  PipelineStream<QuadricRequest> quads;
  std::vector<uint32_t> found;
  std::vector<bool> rayMismatched;
  // Dual precision: per narrow width, the tests its narrow unit rejects, and
  // any it rejected that hit at full width (a broken proof: never, or a bug).
  std::vector<uint64_t> rejected(config.dualNarrowBits.size()), unsound(config.dualNarrowBits.size());
  uint64_t goldenHits = 0;
  for (size_t begin = 0; begin < rays.size(); begin += config.raysPerBatch) {
    const size_t end = std::min(rays.size(), begin + config.raysPerBatch);
    tris.clear();
    quads.clear();
    for (size_t i = begin; i < end; ++i) {
      job.rays[i] = rays[i];
      if (!job.rays[i]) continue;
      job.rays[i]->q.id = uint32_t(i);
      const fx::QRay& q = job.rays[i]->q;
      found.clear();
      candidates(Ray{glm::vec3(quantizer.sceneOrigin(q)), glm::vec3(quantizer.sceneDirection(q))}, found);
      for (uint32_t prim : found) {
        if (prim < triangles.size()) {
          tris.requests.push_back({q, triangles[prim]});
        } else {
          quads.requests.push_back({q, quadrics[prim - triangles.size()]});
        }
      }
    }
    job.intersectionTests += tris.requests.size() + quads.requests.size();
    job.quadricTests += quads.requests.size();

    auto start = std::chrono::steady_clock::now();
    const StreamStats stats = model.run(tris.requests, tris.model, config.stream);
    StreamStats quadStats;
    if (!quads.requests.empty()) quadStats = model.runQuadrics(quads.requests, quads.model, config.stream);
    job.modelSeconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    golden.run(tris.requests, tris.golden, {});
    if (!quads.requests.empty()) golden.runQuadrics(quads.requests, quads.golden, {});
    job.goldenSeconds += secondsSince(start);
    for (size_t k = 0; !config.dualNarrowBits.empty() && k < tris.requests.size() && k < tris.golden.size(); ++k) {
      goldenHits += tris.golden[k].hit;
      for (size_t w = 0; w < config.dualNarrowBits.size(); ++w) {
        if (!fx::narrowRejects(tris.requests[k].ray, tris.requests[k].tri, config.dualNarrowBits[w])) continue;
        ++rejected[w];
        unsound[w] += tris.golden[k].hit;
      }
    }
    // The two pipelines side by side: the batch takes the longer stream.
    job.cycles += std::max(stats.cycles, quadStats.cycles);
    job.cycleAccurate = stats.cycleAccurate;
    inputStalls += stats.inputStalls + quadStats.inputStalls;

    rayMismatched.assign(end - begin, false);
    compareStream(tris, begin, end, job, rayMismatched);
    compareStream(quads, begin, end, job, rayMismatched);
    for (bool bad : rayMismatched) job.mismatchedRays += bad;
    if (onProgress) onProgress(end - begin);
  }
  job.addCounter("input_stall_cycles", "input stall cycles", double(inputStalls));
  if (!quadrics.empty()) job.addCounter("quadric_tests", "ray-quadric tests", double(job.quadricTests));
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
