#include "driver/wave_tracer.h"

#include <cmath>

#include <fmt/format.h>

#include "common/progress.h"
#include "driver/candidates.h"
#include "driver/report.h"
#include "golden/isect.h"

namespace lancer {

HardwareWaveTracer::HardwareWaveTracer(fx::UnitKind path, const Scene& scene, const Quantizer& quantizer,
                                       const JobConfig& config, const Bvh* reference, double offsetUnits)
    : quantizer_(quantizer), path_(makeHardwarePath(path, scene, quantizer, config)),
      offset_(offsetUnits), scene_(scene), reference_(reference) {
  if (reference_) candidates_ = exactCandidates(*reference_, scene.bounds);
  // The isect path streams every candidate either way: any-hit saves it nothing to measure.
  if (path != fx::UnitKind::Isect) {
    JobConfig golden = config;
    golden.model = "golden";
    golden_ = makeHardwarePath(path, scene, quantizer, golden);
  }
  for (const fx::QTriangle& t : quantizer.quantizeTriangles(scene)) {
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(double(t.v[k][0]), double(t.v[k][1]), double(t.v[k][2]));
    const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double length = glm::length(n);
    normals_.push_back(length > 0 ? n / length : glm::dvec3(0.0));  // degenerate: never hit
  }
  quadrics_ = quantizer.quantizeQuadrics(scene);
}

namespace {

// The point of lattice ray `q` at lattice t.
glm::dvec3 pointAt(const fx::QRay& q, double t) {
  glm::dvec3 p;
  for (int a = 0; a < 3; ++a) p[a] = double(q.org[size_t(a)]) + t * double(q.dir[size_t(a)]);
  return p;
}

}  // namespace

glm::dvec3 HardwareWaveTracer::latticeNormal(uint32_t prim, const glm::dvec3& point) const {
  if (prim < normals_.size()) return normals_[prim];
  // A quadric's: the gradient of its record q'Qq + 2g'q + k at q = 2x - S,
  // 2(Qq + g), outwards (F < 0 inside); an inside-visible quadric's geometric
  // normal points in (as its tessellation is wound), and so does this one.
  const fx::QQuadric& rec = quadrics_[prim - normals_.size()];
  glm::dvec3 q, n;
  for (int a = 0; a < 3; ++a) q[a] = 2.0 * point[a] - double(rec.axisSum[size_t(a)]);
  for (int i = 0; i < 3; ++i) {
    n[i] = double(rec.lin[size_t(i)]);
    for (int j = 0; j < 3; ++j) n[i] += double(rec.quadAt(i, j)) * q[j];
  }
  const double length = glm::length(n);
  if (!(length > 0.0)) return glm::dvec3(0.0);  // at a pointed cone's apex: no offset
  return (scene_.quadricOf(prim).insideVisible() ? -1.0 : 1.0) * n / length;
}

void ClassHardwareStats::add(const JobResult& job, std::span<const std::optional<QuantizedRay>> batch) {
  rays += batch.size();
  for (const auto& r : batch) traced += r.has_value();
  for (const auto& h : job.hits) hits += h.has_value();
  intersectionTests += job.intersectionTests;
  quadricTests += job.quadricTests;
  steps += job.steps;
  memoryReads += job.memoryReads;
  nodeBytes += job.nodeBytes;
  cycles += job.cycles;
  mismatches += job.mismatchedRays;
  modelSeconds += job.modelSeconds;
  goldenSeconds += job.goldenSeconds;
  if (job.chip) {
    if (chip) {
      *chip += *job.chip;
    } else {
      chip = job.chip;
    }
  }
}

nlohmann::json ClassHardwareStats::toJson(double clockHz) const {
  nlohmann::json j = {{"rays", rays},
                      {"rays_in_lattice", traced},
                      {"hits", hits},
                      {"triangle_tests", intersectionTests - quadricTests},
                      {"quadric_tests", quadricTests},
                      {"intersection_tests", intersectionTests},
                      {"steps", steps},
                      {"memory_reads", memoryReads},
                      {"node_bytes", nodeBytes},
                      {"cycles", cycles},
                      {"simulated_seconds", double(cycles) / clockHz},
                      {"mismatches", mismatches},
                      {"host_seconds", modelSeconds + goldenSeconds},
                      {"model_seconds", modelSeconds},
                      {"golden_seconds", goldenSeconds}};
  if (chip) j["chip"] = chip->toJson(cycles, rays, clockHz);
  if (closestHitSteps || closestHitTests) {
    j["closest_hit_steps"] = closestHitSteps;
    j["closest_hit_tests"] = closestHitTests;
  }
  return j;
}

std::vector<ClassKey> HardwareWaveTracer::classes() const {
  std::vector<ClassKey> keys;
  for (const auto& [key, record] : classes_) keys.push_back(key);
  return keys;
}

const ClassHardwareStats& HardwareWaveTracer::stats(ClassKey cls) const {
  static const ClassHardwareStats kNone;
  const auto it = classes_.find(cls);
  return it == classes_.end() ? kNone : it->second.stats;
}

const ReferenceComparison& HardwareWaveTracer::comparison(ClassKey cls) const {
  static const ReferenceComparison kNone;
  const auto it = classes_.find(cls);
  return it == classes_.end() ? kNone : it->second.comparison;
}

uint64_t HardwareWaveTracer::beyondBound() const {
  uint64_t n = 0;
  for (const auto& [key, record] : classes_) n += record.comparison.arbiter.beyondBound();
  return n;
}

uint64_t HardwareWaveTracer::mismatches() const {
  uint64_t n = 0;
  for (const auto& [key, record] : classes_) n += record.stats.mismatches;
  return n;
}

std::optional<QuantizedRay> HardwareWaveTracer::latticeRay(const WaveRay& ray, uint32_t index) {
  std::optional<QuantizedRay> q;
  if (fromCamera(ray.cls) || ray.parent >= wave_.size() || !wave_[ray.parent] || !waveHits_[ray.parent]) {
    q = quantizer_.quantize(ray.ray, index);
  } else {
    // The parent's hit on the lattice, exactly where the hardware found it, moved
    // off the triangle along its normal to the side the ray leaves to.
    const fx::QRay& parent = wave_[ray.parent]->q;
    const fx::IsectResult& hit = *waveHits_[ray.parent];
    const glm::dvec3 point = pointAt(parent, fx::tOf(hit, parent));
    Ray shortened = ray.ray;
    if (std::isfinite(shortened.tMax)) {  // stop short of the light (an emitter's own triangle)
      const double latticeUnitsPerT = glm::length(glm::dvec3(ray.ray.dir)) / quantizer_.unit();
      // Short of an emitting triangle's plane by the margin across it: along a ray
      // that meets the plane at a grazing angle that is margin / cos, where the
      // lattice ray's error across the plane is magnified the same way.
      double margin = kSegmentEndMarginUnits;
      if (ray.targetPrim < normals_.size()) {
        const double cosine = std::abs(glm::dot(glm::normalize(glm::dvec3(ray.ray.dir)), normals_[ray.targetPrim]));
        margin /= std::max(cosine, kMinEmitterCosine);
      }
      shortened.tMax = float(std::max(0.0, double(shortened.tMax) - margin / latticeUnitsPerT));
    }
    const glm::dvec3 normal = latticeNormal(hit.primId, point);
    const auto offsetTo = [&](double side) {
      return quantizer_.quantizeFrom(point + side * offset_ * normal, shortened, index);
    };
    q = offsetTo(double(ray.side));
    // The side the loop chose is that of the float triangle. Where the lattice
    // ray meets its own lattice triangle from there (a ray almost in the plane,
    // or a triangle a few lattice units across whose lattice normal turns far
    // from its float one), the ray in truth leaves the lattice triangle to its
    // other side: start it there, and it cannot meet the triangle again.
    if (q && hit.primId < normals_.size() &&
        fx::intersect(q->q, quantizer_.quantize(scene_.triangles[hit.primId], hit.primId)).hit) {
      q = offsetTo(-double(ray.side));
      ++sideFlips_;
    }
    // A quadric is left along its own record's normal; a ray into its solid
    // meets its far side by right. One the loop sends out of the solid that
    // meets the lattice quadric again (the lattice surface turned from the
    // float one: a branch a unit or two thick, a grazing ray) in truth passes
    // through its lattice solid: it starts again past it, off its far side.
    for (int pass = 0; q && hit.primId >= normals_.size() && !ray.intoSolid && pass < 2; ++pass) {
      const fx::QQuadric& own = quadrics_[hit.primId - normals_.size()];
      const fx::IsectResult again = fx::intersectQuadric(q->q, own);
      if (!again.hit) break;
      const glm::dvec3 exit = pointAt(q->q, fx::tOf(again, q->q));
      const glm::dvec3 outward = latticeNormal(hit.primId, exit);
      // Off the surface to the side the ray goes on to.
      const glm::dvec3 dir(double(q->q.dir[0]), double(q->q.dir[1]), double(q->q.dir[2]));
      q = quantizer_.quantizeFrom(exit + offset_ * (glm::dot(outward, dir) >= 0.0 ? outward : -outward), shortened,
                                  index);
      ++sideFlips_;
    }
  }
  if (q) q->q.anyHit = ray.anyHit;
  return q;
}

void HardwareWaveTracer::trace(int generation, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) {
  hits.assign(rays.size(), std::nullopt);
  QuantizedRays wave(rays.size());
  std::vector<std::optional<fx::IsectResult>> waveHits(rays.size());
  for (uint32_t i = 0; i < rays.size(); ++i) {
    wave[i] = latticeRay(rays[i], i);
    if (!wave[i] && !fromCamera(rays[i].cls)) ++originsOutside_;
  }
  // One job per class (bounces by number), so each class's cycles and steps
  // are its own; a bar over the wave on a terminal.
  Progress progress(fmt::format("wave {}", generation), rays.size());
  std::map<ClassKey, std::vector<uint32_t>> byClass;
  for (uint32_t i = 0; i < rays.size(); ++i) byClass[keyOf(rays[i])].push_back(i);
  for (const auto& [cls, members] : byClass) {
    QuantizedRays batch(members.size());
    bool anyHitRays = false;
    for (size_t k = 0; k < members.size(); ++k) {
      batch[k] = wave[members[k]];
      anyHitRays |= rays[members[k]].anyHit;
    }
    const JobResult job = path_->run(batch, [&](size_t n) { progress.advance(n); });
    ClassHardwareStats& s = record(cls).stats;
    s.add(job, batch);
    cycleAccurate_ = cycleAccurate_ && job.cycleAccurate;
    if (job.firstMismatch && !firstMismatch_) {
      const uint32_t index = members[job.firstMismatch->rayId];
      firstMismatch_ = WaveMismatch{generation, cls, index,
                                    fmt::format("wave {} ({} ray {} of the wave):\n{}", generation, toString(cls),
                                                index, job.firstMismatch->details)};
    }
    for (size_t k = 0; k < members.size(); ++k) {
      hits[members[k]] = sceneHit(job, k);
      waveHits[members[k]] = job.hits[k];
    }
    if (reference_) compare(generation, cls, rays, members, batch, job);
    if (anyHitRays && golden_) {  // what the same rays would have cost as closest-hit rays
      for (auto& r : batch) {
        if (r) r->q.anyHit = false;
      }
      const JobResult closest = golden_->run(batch);
      s.closestHitSteps += closest.steps;
      s.closestHitTests += closest.intersectionTests;
    }
  }
  progress.finish();
  wave_ = std::move(wave);
  waveHits_ = std::move(waveHits);
}

void HardwareWaveTracer::compare(int generation, ClassKey cls, std::span<const WaveRay> rays,
                                 std::span<const uint32_t> members, const QuantizedRays& batch, const JobResult& job) {
  // The question the hardware was asked, in scene space: a primary ray as
  // given; a secondary one from its lattice origin (so t = 0 there), along the
  // same direction, to its segment's end as coded (formats.h). Rays the hardware
  // did not trace (a secondary origin outside the lattice) are left out.
  std::vector<Ray> asked;
  QuantizedRays quantized;
  std::vector<std::optional<fx::IsectResult>> answers;
  std::vector<uint32_t> index;
  bool anyHit = false;
  for (size_t k = 0; k < members.size(); ++k) {
    const WaveRay& ray = rays[members[k]];
    if (!batch[k] && !fromCamera(ray.cls)) continue;
    anyHit = ray.anyHit;
    Ray question = ray.ray;
    std::optional<QuantizedRay> q = batch[k];
    if (!fromCamera(ray.cls)) {
      question.origin = glm::vec3(quantizer_.sceneOrigin(q->q));
      question.tMax = kInfinity;
      if (q->q.bounded()) {
        const double along = double(q->q.tMax) / double(uint64_t(1) << fx::kSegFracBits);
        question.tMax = float(q->tScale * along / double(fx::kDirMax));
      }
      q->tEnter = 0.0;
    }
    asked.push_back(question);
    quantized.push_back(q);
    answers.push_back(job.hits[k]);
    index.push_back(members[k]);
  }
  std::vector<std::optional<Hit>> reference(asked.size());
  for (size_t k = 0; k < asked.size(); ++k) reference[k] = reference_->intersect(asked[k]);
  const ReferenceComparison cmp =
      compareWithReference(scene_, asked, reference, quantized, answers, quantizer_, anyHit, candidates_);
  if (const auto first = cmp.arbiter.firstHardwareBeyond; first && !firstBeyond_) {
    const Ray& r = asked[*first];
    firstBeyond_ = WaveMismatch{
        generation, cls, index[*first],
        fmt::format("wave {} ({} ray {} of the wave): the hardware's answer is beyond its lattice bound ({}); the ray "
                    "as asked: {:a} {:a} {:a} {:a} {:a} {:a} (t max {:a}){}\n",
                    generation, toString(cls), index[*first], cmp.arbiter.firstHardwareBeyondWhy, r.origin.x,
                    r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tMax, anyHit ? ", any hit" : "")};
  }
  record(cls).comparison += cmp;
}

}  // namespace lancer
