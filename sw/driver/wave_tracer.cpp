#include "driver/wave_tracer.h"

#include <cmath>

#include <fmt/format.h>

#include "driver/report.h"
#include "golden/isect.h"

namespace lancer {

HardwareWaveTracer::HardwareWaveTracer(const std::string& accel, const Scene& scene, const Quantizer& quantizer,
                                       const JobConfig& config, double offsetUnits)
    : quantizer_(quantizer), path_(makeHardwarePath(accel, scene, quantizer, config)),
      offset_(offsetUnits) {
  // The bvh path streams every candidate either way: any-hit saves it nothing to measure.
  if (accel != "bvh") {
    JobConfig golden = config;
    golden.model = "golden";
    golden_ = makeHardwarePath(accel, scene, quantizer, golden);
  }
  for (const fx::QTriangle& t : quantizer.quantize(scene)) {
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(double(t.v[k][0]), double(t.v[k][1]), double(t.v[k][2]));
    const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double length = glm::length(n);
    normals_.push_back(length > 0 ? n / length : glm::dvec3(0.0));  // degenerate: never hit
  }
}

uint64_t HardwareWaveTracer::mismatches() const {
  uint64_t n = 0;
  for (const ClassHardwareStats& s : stats_) n += s.mismatches;
  return n;
}

std::optional<QuantizedRay> HardwareWaveTracer::latticeRay(const WaveRay& ray, uint32_t index) const {
  std::optional<QuantizedRay> q;
  if (ray.cls == RayClass::Primary || ray.parent >= wave_.size() || !wave_[ray.parent] || !waveHits_[ray.parent]) {
    q = quantizer_.quantize(ray.ray, index);
  } else {
    // The parent's hit on the lattice, exactly where the hardware found it, moved
    // off the triangle along its normal to the side the ray leaves to.
    const fx::QRay& parent = wave_[ray.parent]->q;
    const fx::IsectResult& hit = *waveHits_[ray.parent];
    const double t = fx::tOf(hit, parent);
    glm::dvec3 point;
    for (int a = 0; a < 3; ++a) point[a] = double(parent.org[a]) + t * double(parent.dir[a]);
    point += double(ray.side) * offset_ * normals_[hit.primId];
    Ray shortened = ray.ray;
    if (std::isfinite(shortened.tMax)) {  // stop short of the light (an emitter's own triangle)
      const double latticeUnitsPerT = glm::length(glm::dvec3(ray.ray.dir)) / quantizer_.unit();
      shortened.tMax = float(std::max(0.0, double(shortened.tMax) - kSegmentEndMarginUnits / latticeUnitsPerT));
    }
    q = quantizer_.quantizeFrom(point, shortened, index);
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
    if (!wave[i] && rays[i].cls != RayClass::Primary) ++originsOutside_;
  }
  // One job per class, so each class's cycles and steps are its own.
  for (int c = 0; c < kRayClassCount; ++c) {
    const RayClass cls = RayClass(c);
    std::vector<uint32_t> members;
    for (uint32_t i = 0; i < rays.size(); ++i) {
      if (rays[i].cls == cls) members.push_back(i);
    }
    if (members.empty()) continue;
    QuantizedRays batch(members.size());
    bool anyHitRays = false;
    for (size_t k = 0; k < members.size(); ++k) {
      batch[k] = wave[members[k]];
      anyHitRays |= rays[members[k]].anyHit;
    }
    const JobResult job = path_->run(batch);
    ClassHardwareStats& s = stats_[size_t(c)];
    s.rays += members.size();
    for (const auto& r : batch) s.traced += r.has_value();
    s.intersectionTests += job.intersectionTests;
    s.steps += job.steps;
    s.memoryReads += job.memoryReads;
    s.cycles += job.cycles;
    s.mismatches += job.mismatchedRays;
    s.modelSeconds += job.modelSeconds;
    s.goldenSeconds += job.goldenSeconds;
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
      s.hits += job.hits[k].has_value();
    }
    if (anyHitRays && golden_) {  // what the same rays would have cost as closest-hit rays
      for (auto& r : batch) {
        if (r) r->q.anyHit = false;
      }
      const JobResult closest = golden_->run(batch);
      s.closestHitSteps += closest.steps;
      s.closestHitTests += closest.intersectionTests;
    }
  }
  wave_ = std::move(wave);
  waveHits_ = std::move(waveHits);
}

}  // namespace lancer
