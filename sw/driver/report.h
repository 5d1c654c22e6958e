#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/job.h"
#include "golden/quadric.h"
#include "golden/records.h"
#include "oracle/exact.h"

namespace lancer {

// A record's fields as hex, in wire order: "ray_id=0x.. org=[0x..,..] ...".
std::string hexFields(const fx::QRay& ray);
std::string hexFields(const fx::QTriangle& tri);
std::string hexFields(const fx::QQuadric& quadric);
std::string hexFields(const fx::IsectResult& res);

// Bit positions (most significant first) where two wire images of a `bits`-wide record differ.
std::string differingBits(const fx::Wire& a, const fx::Wire& b, int bits);

// How the hardware's closest hits differ from the floating-point reference on
// the original rays. t errors are distances along the ray in lattice units
// (the position format's quantum), the reference t re-evaluated in long double.
// Each disagreement is settled by the exact arbiter (sw/oracle/exact.h): the
// reference judged within float32 rounding, the hardware within its lattice
// bound (latticeTolerance), verdicts counted by kind.
struct ArbiterCounts {
  uint64_t judged = 0;                   // disagreements settled
  std::array<uint64_t, 4> reference{};   // by Verdict: correct, tie, rounding, wrong
  std::array<uint64_t, 4> hardware{};    // by Verdict: correct, tie, within its bound, beyond it
  std::optional<uint32_t> firstHardwareBeyond;  // the first ray the hardware got wrong beyond its bound
  std::string firstHardwareBeyondWhy;           // its verdict's reason and both answers
  std::optional<uint32_t> firstReferenceWrong;

  uint64_t beyondBound() const { return hardware[3]; }
};

struct ReferenceComparison {
  uint64_t disagreements = 0;  // rays where hit/miss or the triangle differs
  uint64_t hitMissDiffers = 0;
  uint64_t primDiffers = 0;
  uint64_t compared = 0;       // rays where both hit the same triangle
  double maxTError = 0;
  double meanTError = 0;
  double sumTError = 0;        // of the compared rays (meanTError's numerator)
  std::optional<uint32_t> firstDisagreement;
  ArbiterCounts arbiter;
};

// The hardware's tolerance for one ray against one triangle
// (docs/number-formats.md, "What the rounding costs"): its ray lies within
// sqrt(3)/2 + r sqrt(2) / (2^D - 2) lattice units of the true one at distance r
// from its origin, and each vertex within sqrt(3)/2; r is taken as the
// farthest vertex, so the bound is conservative. The t reported is a float,
// so t may also be off by its rounding (kHitTRounding, relative).
// The relative rounding of a hit's t reported as a float (Hit::t): one ulp.
inline constexpr double kHitTRounding = 0x1p-23;
Tolerance latticeTolerance(const QuantizedRay& ray, const Quantizer& quantizer, const Ray& sceneRay,
                           const Triangle& tri);
// The same against a native quadric (docs/quadrics.md, "On the lattice"): the
// ray's part as for a triangle (r the farthest point of the quadric's box),
// plus the quantized quadric's distance from the scene's: its center or ends
// within sqrt(3)/2 units, its radii within one unit (rounding, and a radius
// below half a unit kept at 1), and for a cone the rounding of its record
// (docs/quadrics.md, "The error against the scene's cone").
Tolerance latticeTolerance(const QuantizedRay& ray, const Quantizer& quantizer, const Ray& sceneRay,
                           const Quadric& quadric);

// The comparison's report keys: reference_disagreements,
// reference_hit_miss_differs, reference_prim_differs, reference_compared (rays both hit on the same
// triangle: the t errors' count), t_error_max_lattice_units,
// t_error_mean_lattice_units and arbiter {judged, reference {correct, tie,
// rounding, wrong}, hardware {correct, tie, within_bound, beyond_bound}}.
nlohmann::json toJson(const ReferenceComparison& cmp);

// `candidates` (optional) culls the exact arbiter's triangles (exactCandidates()).
ReferenceComparison compareWithReference(const Scene& scene, std::span<const Ray> rays,
                                         std::span<const std::optional<Hit>> reference,
                                         const JobResult& job, const Quantizer& quantizer,
                                         const TriangleCandidates& candidates = {});

// The same for rays the hardware was asked as `quantized` (t_enter: where each
// scene ray's t = 0 lies before the lattice origin) and answered with `hits`.
// Any-hit rays (shadow rays) agree when both are blocked or both clear, and are
// judged by judgeAnyHit; they have no t error.
ReferenceComparison compareWithReference(const Scene& scene, std::span<const Ray> rays,
                                         std::span<const std::optional<Hit>> reference,
                                         std::span<const std::optional<QuantizedRay>> quantized,
                                         std::span<const std::optional<fx::IsectResult>> hits,
                                         const Quantizer& quantizer, bool anyHit,
                                         const TriangleCandidates& candidates = {});

// Adds another comparison's counts (a later wave of the same class); the first
// disagreements keep their own ray indices.
ReferenceComparison& operator+=(ReferenceComparison& into, const ReferenceComparison& more);

// The hardware's closest hit as a scene-space Hit (t in the original ray's units).
std::optional<Hit> sceneHit(const JobResult& job, size_t ray);

}  // namespace lancer
