#pragma once

// The exact arbiter: ray-triangle relations decided in exact arithmetic over
// the binary values of the floats (docs/oracle.md, "The exact arbiter").
//
// A float tracer (the reference, Embree) rounds; so does the fixed-point
// hardware. When two of them disagree, neither is ground truth. This oracle
// is: it treats every float of the scene and the ray as the exact binary
// number it is, and decides each predicate (which side of an edge, t > 0,
// t <= tMax, which of two hits is closer) without rounding.
//
// How: the predicates are signs of polynomials of degree 3 (edge volumes, the
// plane crossing) and 6 (comparing two t) in the inputs. Each is first
// evaluated in double with a forward error bound (a static filter, as in
// Shewchuk's robust predicates); only when the bound cannot settle the sign
// is it evaluated again in integers (GMP), the floats scaled to integers by
// a common power of two. Most pairs are settled by the filter.

#include <cstdint>
#include <optional>
#include <string_view>

#include <gmpxx.h>

#include "ref/ray.h"
#include "scene/scene.h"

namespace lancer {

// An exact ray parameter t = num / den * 2^shift, den > 0.
class ExactT {
 public:
  ExactT(mpz_class num, mpz_class den, long shift);
  // Nearest double below or at t (within one ulp).
  double toDouble() const;
  // -1, 0, +1 as a <, ==, > b, exactly.
  friend int compare(const ExactT& a, const ExactT& b);
  friend bool operator==(const ExactT& a, const ExactT& b) { return compare(a, b) == 0; }

 private:
  mpz_class num_, den_;
  long shift_ = 0;
};

// What exact arithmetic says about one ray and one triangle. The ray's line
// crosses the triangle's plane at one point unless it is parallel to it (a
// degenerate triangle, or a ray in or parallel to the plane: never a hit).
struct ExactRelation {
  bool hit = false;                // the crossing lies in the closed triangle, at t in (0, tMax]
  bool onBoundary = false;         // ... exactly on an edge or a vertex
  bool parallel = false;           // no single crossing point
  std::optional<ExactT> t;         // the crossing's t (any sign), unless parallel
  double minBarycentric = 0.0;     // smallest barycentric of the crossing, rounded (< 0: outside)
};

// The exact closest hit of a ray.
struct ExactHit {
  uint32_t prim = 0;
  double t = 0.0;           // ExactT::toDouble of the exact t
  bool onBoundary = false;  // the ray meets the triangle exactly on an edge or a vertex
};

// Counts of one oracle's work, for the tests and the docs.
struct ExactStats {
  uint64_t pairs = 0;         // ray-triangle pairs looked at
  uint64_t exactPairs = 0;    // pairs the double filter could not settle
  uint64_t exactCompares = 0; // closest-hit comparisons settled in integers
};

// Brute force over every triangle of `scene` (which must outlive it): exact,
// ~40 ns a pair here (bunny, 2000 rays aimed at vertices: one pair in 10^4
// reaches the integer path). Closest hit: the least
// exact t in (0, ray.tMax]; exact ties go to the lower triangle id, the
// rule of closerHit(). Throws InputError for a ray with a NaN or infinite
// component or a zero direction.
class ExactOracle {
 public:
  explicit ExactOracle(const Scene& scene) : scene_(scene) {}

  std::optional<ExactHit> intersect(const Ray& ray, ExactStats* stats = nullptr) const;
  ExactRelation relation(const Ray& ray, uint32_t prim) const;
  const Scene& scene() const { return scene_; }

 private:
  const Scene& scene_;
};

// The verdict on one tracer's answer for one ray, against the exact truth.
enum class Verdict {
  Correct,   // same hit triangle at a t within rounding (or both miss)
  Tie,       // another triangle at exactly the same t
  Rounding,  // within float rounding of the truth: a near-tie in t, or a
             // crossing within rounding of a triangle's boundary (a grazing
             // ray, a ray aimed at an edge or a vertex of an open mesh)
  Wrong,     // anything else: a real error of the tracer
};
std::string_view toString(Verdict verdict);

struct Judgement {
  Verdict verdict = Verdict::Correct;
  std::string_view reason;  // one phrase, e.g. "missed a hit away from any edge"
};

// Judges `answer` (a float or fixed-point tracer's closest hit of `ray`, or
// nullopt for a miss) against `truth` = oracle.intersect(ray). The rounding
// bounds are those of float32 inputs: a crossing point within 2^-20 of the
// largest coordinate magnitude of the ray and triangle (M) from an edge,
// measured as a barycentric against the triangle's smallest altitude, and t
// within 2^-20 * M / |d| (docs/oracle.md).
Judgement judge(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                const std::optional<ExactHit>& truth);

}  // namespace lancer
