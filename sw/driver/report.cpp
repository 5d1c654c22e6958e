#include "driver/report.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <fmt/format.h>

#include "golden/isect.h"
#include "ref/quadric.h"
#include "ref/triangle.h"

namespace lancer {

namespace {

std::string hex(fx::u128 value) {
  const uint64_t hi = uint64_t(value >> 64), lo = uint64_t(value);
  return hi ? fmt::format("0x{:x}{:016x}", hi, lo) : fmt::format("0x{:x}", lo);
}

std::string hexTriple(const std::array<int64_t, 3>& v, int width) {
  const fx::u128 mask = (fx::u128(1) << width) - 1;
  return fmt::format("[{},{},{}]", hex(fx::u128(fx::i128(v[0])) & mask), hex(fx::u128(fx::i128(v[1])) & mask),
                     hex(fx::u128(fx::i128(v[2])) & mask));
}

// Settles one disagreement between the reference and the hardware. A ray that
// missed the lattice has no hardware answer: a miss, with no lattice to
// excuse it, judged at float rounding.
void arbitrate(const ExactOracle& oracle, const Ray& ray, uint32_t index, const std::optional<Hit>& reference,
               const std::optional<Hit>& hardware, const std::optional<QuantizedRay>& quantized,
               const Quantizer& quantizer, bool anyHit, ArbiterCounts& counts) {
  ++counts.judged;
  ToleranceOf lattice;
  QuadricToleranceOf quadricLattice;
  if (quantized) {
    lattice = [&](const Triangle& tri) { return latticeTolerance(*quantized, quantizer, ray, tri); };
    quadricLattice = [&](const Quadric& q) { return latticeTolerance(*quantized, quantizer, ray, q); };
  }
  Verdict ref;
  Judgement hw;
  if (anyHit) {
    ref = judgeAnyHit(oracle, ray, reference).verdict;
    hw = judgeAnyHit(oracle, ray, hardware, lattice, quadricLattice);
  } else {
    const std::optional<ExactHit> truth = oracle.intersect(ray);
    ref = judge(oracle, ray, reference, truth).verdict;
    hw = judge(oracle, ray, hardware, truth, lattice, quadricLattice);
  }
  ++counts.reference[size_t(ref)];
  ++counts.hardware[size_t(hw.verdict)];
  if (ref == Verdict::Wrong && !counts.firstReferenceWrong) counts.firstReferenceWrong = index;
  if (hw.verdict == Verdict::Wrong && !counts.firstHardwareBeyond) {
    const auto answer = [](const std::optional<Hit>& h) {
      return h ? fmt::format("prim {} at t {:a}", h->prim, h->t) : std::string("a miss");
    };
    counts.firstHardwareBeyond = index;
    counts.firstHardwareBeyondWhy =
        fmt::format("{}; the hardware answered {}, the float reference {}", hw.reason, answer(hardware), answer(reference));
  }
}

}  // namespace

std::string hexFields(const fx::QRay& r) {
  return fmt::format("ray_id={} org={} dir={}", hex(r.id), hexTriple(r.org, fx::kPosBits),
                     hexTriple(r.dir, fx::kDirBits));
}

std::string hexFields(const fx::QTriangle& t) {
  return fmt::format("prim_id={} v0={} v1={} v2={}", hex(t.id), hexTriple(t.v[0], fx::kPosBits),
                     hexTriple(t.v[1], fx::kPosBits), hexTriple(t.v[2], fx::kPosBits));
}

std::string hexFields(const fx::QQuadric& q) {
  return fmt::format("prim_id={} axis_sum={} axis={} axis_len2={} quad=({} {} {} {} {} {}) lin=({} {} {}) konst={}",
                     hex(q.id), hexTriple(q.axisSum, fx::kQuadricAxisSumBits), hexTriple(q.axis, fx::kQuadricAxisBits),
                     hex(q.axisLen2), q.quad[0], q.quad[1], q.quad[2], q.quad[3], q.quad[4], q.quad[5], q.lin[0],
                     q.lin[1], q.lin[2], q.constant);
}

std::string hexFields(const fx::IsectResult& r) {
  return fmt::format("ray_id={} prim_id={} hit={} t_num={} det={} u_num={} v_num={}", hex(r.rayId),
                     hex(r.primId), int(r.hit), hex(r.tNum), hex(r.det), hex(r.uNum), hex(r.vNum));
}

std::string differingBits(const fx::Wire& a, const fx::Wire& b, int bits) {
  std::string out;
  for (int i = bits - 1; i >= 0; --i) {
    if (((a[size_t(i / 32)] ^ b[size_t(i / 32)]) >> (i % 32)) & 1) out += fmt::format(" {}", i);
  }
  return out;
}

namespace {

// A hardware hit's t in its scene ray's units, in double.
double sceneT(const QuantizedRay& q, const fx::IsectResult& r) { return q.tEnter + q.tScale * fx::tOf(r, q.q); }

std::optional<Hit> sceneHit(const std::optional<QuantizedRay>& q, const std::optional<fx::IsectResult>& r,
                            uint32_t firstQuadric) {
  if (!q || !r) return std::nullopt;
  // A quadric's hit carries its side, as the float reference's does (u = 1: leaving).
  if (r->primId >= firstQuadric) return Hit{r->primId, float(sceneT(*q, *r)), float(r->uNum), 0.0f};
  return Hit{r->primId, float(sceneT(*q, *r)), float(fx::uOf(*r)), float(fx::vOf(*r))};
}

}  // namespace

std::optional<Hit> sceneHit(const JobResult& job, size_t ray) {
  return sceneHit(job.rays[ray], job.hits[ray], job.firstQuadric);
}

namespace {

// A lattice ray's distance from the scene's at `r` lattice units from its
// origin: its origin within sqrt(3)/2, its direction within sqrt(2) / (2^D - 2).
double rayErrorUnits(double r) {
  return std::sqrt(3.0) / 2.0 + r * std::sqrt(2.0) / double((int64_t(1) << fx::kDirBits) - 2);
}

// The tolerance of `units` lattice units across the ray; the answer's t comes
// back as a float: from far away (t large against the lattice) its last bit
// outweighs the lattice's error.
Tolerance toleranceOf(double units, const Quantizer& quantizer, const Ray& sceneRay) {
  const double edge = units * quantizer.unit();
  return {edge, edge / glm::length(glm::dvec3(sceneRay.dir)), kHitTRounding};
}

}  // namespace

Tolerance latticeTolerance(const QuantizedRay& ray, const Quantizer& quantizer, const Ray& sceneRay,
                           const Triangle& tri) {
  const glm::dvec3 origin = quantizer.sceneOrigin(ray.q);
  double farthest = 0.0;
  for (const glm::vec3& v : {tri.v0, tri.v1, tri.v2}) farthest = std::max(farthest, glm::length(glm::dvec3(v) - origin));
  // Each vertex within sqrt(3)/2 units.
  return toleranceOf(std::sqrt(3.0) / 2.0 + rayErrorUnits(farthest / quantizer.unit()), quantizer, sceneRay);
}

Tolerance latticeTolerance(const QuantizedRay& ray, const Quantizer& quantizer, const Ray& sceneRay,
                           const Quadric& quadric) {
  const glm::dvec3 origin = quantizer.sceneOrigin(ray.q);
  const Aabb box = quadric.bounds();
  double farthest = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                       (corner & 4) ? box.hi.z : box.lo.z);
    farthest = std::max(farthest, glm::length(p - origin));
  }
  double units = std::sqrt(3.0) / 2.0 + 1.0 + rayErrorUnits(farthest / quantizer.unit());
  if (quadric.kind == Quadric::Kind::Cone) {
    // The record's rounding: |rho^2 - R^2| <= 3 max(1, tau^2) |x - c|^2 2^-K
    // units^2 at a point x (c the axis' midpoint; docs/quadrics.md), so
    // |rho - R| is at most that over R, and at most its square root; then
    // across the side, tilted by tau from the radial direction.
    const double scale = 1.0 / quantizer.unit();
    const double length = glm::length(glm::dvec3(quadric.apex) - glm::dvec3(quadric.base)) * scale;
    const double r0 = std::abs(double(quadric.baseRadius)) * scale, r1 = std::abs(double(quadric.apexRadius)) * scale;
    const double tau = std::abs(r1 - r0) / std::max(length, 1.0);
    const double reach = 0.5 * length + std::max(r0, r1) + 1.0;
    const double radial2 = 3.0 * std::max(1.0, tau * tau) * reach * reach * std::ldexp(1.0, -fx::kQuadricK);
    const double thinnest = std::min(r0, r1);
    const double radial = thinnest > 0.0 ? std::min(std::sqrt(radial2), radial2 / thinnest) : std::sqrt(radial2);
    units += radial * std::sqrt(1.0 + tau * tau);
  }
  return toleranceOf(units, quantizer, sceneRay);
}

nlohmann::json toJson(const ReferenceComparison& cmp) {
  const ArbiterCounts& a = cmp.arbiter;
  return {
      {"reference_disagreements", cmp.disagreements},
      {"reference_hit_miss_differs", cmp.hitMissDiffers},
      {"reference_prim_differs", cmp.primDiffers},
      {"reference_compared", cmp.compared},
      {"t_error_max_lattice_units", cmp.maxTError},
      {"t_error_mean_lattice_units", cmp.meanTError},
      {"arbiter",
       {{"judged", a.judged},
        {"reference", {{"correct", a.reference[0]}, {"tie", a.reference[1]}, {"rounding", a.reference[2]},
                       {"wrong", a.reference[3]}}},
        {"hardware", {{"correct", a.hardware[0]}, {"tie", a.hardware[1]}, {"within_bound", a.hardware[2]},
                      {"beyond_bound", a.hardware[3]}}}}},
  };
}

ReferenceComparison compareWithReference(const Scene& scene, std::span<const Ray> rays,
                                         std::span<const std::optional<Hit>> reference,
                                         const JobResult& job, const Quantizer& quantizer,
                                         const TriangleCandidates& candidates) {
  return compareWithReference(scene, rays, reference, job.rays, job.hits, quantizer, /*anyHit=*/false, candidates);
}

ReferenceComparison compareWithReference(const Scene& scene, std::span<const Ray> rays,
                                         std::span<const std::optional<Hit>> reference,
                                         std::span<const std::optional<QuantizedRay>> quantized,
                                         std::span<const std::optional<fx::IsectResult>> hits,
                                         const Quantizer& quantizer, bool anyHit,
                                         const TriangleCandidates& candidates) {
  ReferenceComparison cmp;
  const ExactOracle oracle(scene, candidates);
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::optional<Hit> hw = sceneHit(quantized[i], hits[i], uint32_t(scene.size()));
    const std::optional<Hit>& ref = reference[i];
    const bool primDiffers = !anyHit && hw && ref && hw->prim != ref->prim;
    if (hw.has_value() != ref.has_value() || primDiffers) {
      ++cmp.disagreements;
      (primDiffers ? cmp.primDiffers : cmp.hitMissDiffers) += 1;
      if (!cmp.firstDisagreement) cmp.firstDisagreement = uint32_t(i);
      arbitrate(oracle, rays[i], uint32_t(i), ref, hw, quantized[i], quantizer, anyHit, cmp.arbiter);
      continue;
    }
    if (!hw || anyHit) continue;
    // The reference t of the same triangle in long double (of a quadric in
    // double), and the hardware's t in double from its exact fraction; the
    // difference as a distance in lattice units.
    double tRef = double(ref->t);
    if (scene.isQuadric(ref->prim)) {
      if (const auto exact = intersectQuadric(rays[i], scene.quadricOf(ref->prim), ref->prim)) tRef = exact->t;
    } else if (const auto exact = intersectTriangleExtended(rays[i], scene.triangles[ref->prim], ref->prim)) {
      tRef = double(exact->t);
    }
    const double error = std::abs(sceneT(*quantized[i], *hits[i]) - tRef) * double(glm::length(rays[i].dir)) /
                         quantizer.unit();
    cmp.maxTError = std::max(cmp.maxTError, error);
    cmp.sumTError += error;
    ++cmp.compared;
  }
  cmp.meanTError = cmp.compared ? cmp.sumTError / double(cmp.compared) : 0.0;
  return cmp;
}

ReferenceComparison& operator+=(ReferenceComparison& into, const ReferenceComparison& more) {
  into.disagreements += more.disagreements;
  into.hitMissDiffers += more.hitMissDiffers;
  into.primDiffers += more.primDiffers;
  into.compared += more.compared;
  into.maxTError = std::max(into.maxTError, more.maxTError);
  into.sumTError += more.sumTError;
  into.meanTError = into.compared ? into.sumTError / double(into.compared) : 0.0;
  if (!into.firstDisagreement) into.firstDisagreement = more.firstDisagreement;
  ArbiterCounts& a = into.arbiter;
  const ArbiterCounts& b = more.arbiter;
  a.judged += b.judged;
  for (size_t k = 0; k < a.reference.size(); ++k) {
    a.reference[k] += b.reference[k];
    a.hardware[k] += b.hardware[k];
  }
  if (!a.firstHardwareBeyond) {
    a.firstHardwareBeyond = b.firstHardwareBeyond;
    a.firstHardwareBeyondWhy = b.firstHardwareBeyondWhy;
  }
  if (!a.firstReferenceWrong) a.firstReferenceWrong = b.firstReferenceWrong;
  return into;
}

}  // namespace lancer
