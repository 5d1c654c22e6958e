#pragma once

// The hardware side of an effects run (docs/effects.md, "On the hardware"):
// every wave of the Whitted loop goes through a hardware path on a model, class
// by class, and is compared with the golden model bit for bit, as a primary-ray
// job is. Secondary rays start on the lattice, at the hardware's own hit of
// their parent ray (exact: o + t_num / (DIR_MAX det) d), moved off the surface
// they leave along its lattice normal (docs/number-formats.md, "Secondary
// origins").

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/job.h"
#include "driver/report.h"
#include "ref/bvh.h"
#include "effects/whitted.h"

namespace lancer {

// The offset of a secondary origin along the unit normal of the triangle it
// leaves, in lattice units: above the worst rounding of the origin to the
// lattice (sqrt(3) / 2 across the plane), so the origin lies strictly on the
// side it leaves to (docs/number-formats.md).
inline constexpr double kSecondaryOffsetUnits = 1.0;

// A shadow ray's segment ends this many lattice units (along the ray) before
// its light: the lattice ray deviates from the float one by up to about 2.3
// units across the lattice (docs/number-formats.md), so a segment ending
// exactly on an area light's triangle would be blocked by the lamp itself.
// The margin is across the light's plane for an area light (its triangle):
// along the ray it is 4 / cos of the angle to the plane's normal, for angles up
// to acos(kMinEmitterCosine) (89.4 degrees; a grazing ray carries almost no light).
inline constexpr double kSegmentEndMarginUnits = 4.0;
inline constexpr double kMinEmitterCosine = 0.01;

// What the hardware did for one class of rays over a run.
struct ClassHardwareStats {
  uint64_t rays = 0;          // rays of the class
  uint64_t traced = 0;        // of which entered the lattice and went through the model
  uint64_t hits = 0;
  uint64_t intersectionTests = 0;
  uint64_t quadricTests = 0;  // of which ray-quadric (the rest ray-triangle)
  uint64_t steps = 0;         // cells or nodes entered
  uint64_t memoryReads = 0;
  uint64_t nodeBytes = 0;     // bytes of the node-port reads
  uint64_t cycles = 0;
  uint64_t mismatches = 0;
  uint64_t closestHitSteps = 0;  // any-hit rays: steps of the same rays as closest-hit (golden model; grid, octree)
  uint64_t closestHitTests = 0;
  double modelSeconds = 0, goldenSeconds = 0;
  std::optional<ChipFigures> chip;  // traversal units on a cycle-accurate model

  // One job's figures over the class's `rays` (nullopt: outside the lattice).
  void add(const JobResult& job, std::span<const std::optional<QuantizedRay>> rays);
  // The class's report entry; `clockHz` turns cycles into simulated seconds.
  nlohmann::json toJson(double clockHz) const;
};

// The first wave ray on which the model and the golden model disagree.
struct WaveMismatch {
  int generation = 0;
  ClassKey cls;
  uint32_t index = 0;  // in its wave
  std::string details;
};

class HardwareWaveTracer final : public WaveTracer {
 public:
  // The path is set up once (image, model); `scene` and `quantizer` must outlive the tracer.
  // With a `reference` (which must outlive it too), every wave's rays are also
  // traced by it, as the hardware was asked them, and each class's disagreements
  // are settled by the exact arbiter (comparison()).
  HardwareWaveTracer(fx::UnitKind path, const Scene& scene, const Quantizer& quantizer, const JobConfig& config,
                     const Bvh* reference = nullptr, double offsetUnits = kSecondaryOffsetUnits);

  void trace(int generation, std::span<const WaveRay> rays, std::vector<std::optional<Hit>>& hits) override;

  // The classes traced so far (bounces by number), in order.
  std::vector<ClassKey> classes() const;
  const ClassHardwareStats& stats(ClassKey cls) const;
  // The class's rays against the reference on the same rays: a secondary ray as
  // the hardware traced it (from its lattice origin, to its segment's end).
  const ReferenceComparison& comparison(ClassKey cls) const;
  // Answers beyond the hardware's bound, over every class.
  uint64_t beyondBound() const;
  // The first of them: its wave, class and the scene ray asked, as a reproducer.
  const std::optional<WaveMismatch>& firstBeyond() const { return firstBeyond_; }
  uint64_t mismatches() const;
  const std::optional<WaveMismatch>& firstMismatch() const { return firstMismatch_; }
  // Secondary rays whose offset origin fell outside the lattice cube (they leave
  // the scene through its boundary): not traced, answered as misses.
  uint64_t originsOutside() const { return originsOutside_; }
  bool cycleAccurate() const { return cycleAccurate_; }
  // Secondary origins moved to the other side of their triangle (or past their
  // lattice quadric, for a ray leaving its solid), where the
  // lattice ray would have met it again from the loop's side.
  uint64_t sideFlips() const { return sideFlips_; }
  double offsetUnits() const { return offset_; }
  // The structure the hardware path built (HardwarePath::structure).
  std::vector<JobCounter> structure() const { return path_->structure(); }

 private:
  std::optional<QuantizedRay> latticeRay(const WaveRay& ray, uint32_t index);
  // The unit geometric normal of primitive `prim` at lattice point `point`.
  glm::dvec3 latticeNormal(uint32_t prim, const glm::dvec3& point) const;
  // Compares one class's job with the reference (members: the class's rays in the wave).
  void compare(int generation, ClassKey cls, std::span<const WaveRay> rays, std::span<const uint32_t> members,
               const QuantizedRays& batch, const JobResult& job);
  // What a class did: its stats and its comparison with the reference.
  struct ClassRecord {
    ClassHardwareStats stats;
    ReferenceComparison comparison;
  };
  ClassRecord& record(ClassKey cls) { return classes_[cls]; }

  const Quantizer& quantizer_;
  std::unique_ptr<HardwarePath> path_;
  std::unique_ptr<HardwarePath> golden_;  // closest-hit steps of any-hit rays (traversal units only)
  double offset_;
  std::vector<glm::dvec3> normals_;  // unit geometric normal of every quantized triangle, lattice space
  std::vector<fx::QQuadric> quadrics_;  // the scene's quadrics on the lattice (their normals vary)

  const Scene& scene_;
  const Bvh* reference_;
  TriangleCandidates candidates_;  // the exact arbiter's, from reference_
  std::map<ClassKey, ClassRecord> classes_;
  std::optional<WaveMismatch> firstMismatch_, firstBeyond_;
  uint64_t originsOutside_ = 0;
  uint64_t sideFlips_ = 0;
  bool cycleAccurate_ = true;
  // The previous wave: its lattice rays and the hardware's hits, which the next wave's origins come from.
  QuantizedRays wave_;
  std::vector<std::optional<fx::IsectResult>> waveHits_;
};

}  // namespace lancer
