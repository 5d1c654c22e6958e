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
//
// Quadrics (NFF spheres and open cones, Scene::quadrics, ids after the
// triangles'): always in integers. A root is t = (-B +- sqrt(disc)) / A; every
// decision about it (the line meets the surface, the root is in (0, tMax],
// its point lies between a cone's end planes, it is nearer than another root
// or a triangle's t) is the sign of a + b sqrt(r) (+ c sqrt(s)), decided by
// sign cases and squaring, never by a square root (docs/oracle.md, "Quadrics
// in the exact arbiter and the float reference").

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include <gmpxx.h>

#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// An exact ray parameter t = (num + coef sqrt(radicand)) / den * 2^shift,
// den > 0, radicand >= 0: rational (coef = 0) for a triangle's crossing, a
// quadratic irrational for a quadric's root.
class ExactT {
 public:
  ExactT(mpz_class num, mpz_class den, long shift);
  ExactT(mpz_class num, mpz_class coef, mpz_class radicand, mpz_class den, long shift);
  // A double within one ulp of t (a root's square root taken to 2^-139
  // relative, after rationalizing a difference so that nothing cancels).
  double toDouble() const;
  // -1, 0, +1: the sign of t.
  int sign() const;
  // -1, 0, +1 as a <, ==, > b, exactly.
  friend int compare(const ExactT& a, const ExactT& b);
  friend bool operator==(const ExactT& a, const ExactT& b) { return compare(a, b) == 0; }

 private:
  mpz_class num_, coef_, radicand_, den_;
  long shift_ = 0;
};

// What exact arithmetic says about one ray and one triangle. The ray's line
// crosses the triangle's plane at one point unless it is parallel to it (a
// degenerate triangle, or a ray in or parallel to the plane: never a hit).
//
// For a quadric (`quadric`): `hit` is the root the closest-hit rule takes (the
// nearer root in (0, tMax] whose point lies between a cone's end planes, rims
// included, else the farther such root), `onBoundary` a tangent (one double
// root) or a point exactly in an end plane (on a rim), `parallel` a line that
// does not meet the surface (including one along a cylinder's axis or lying in
// its wall), `t` the hit's root, or when there is no hit the root between the
// planes nearest the origin (any sign), `entering` the side, `cosine` at t's
// point; minBarycentric and boundaryDistance are NaN.
struct ExactRelation {
  bool hit = false;                // the crossing lies in the closed triangle, at t in (0, tMax]
  bool onBoundary = false;         // ... exactly on an edge or a vertex
  bool parallel = false;           // no single crossing point
  std::optional<ExactT> t;         // the crossing's t (any sign), unless parallel
  double minBarycentric = 0.0;     // smallest barycentric of the crossing, rounded (< 0: outside)
  double boundaryDistance = 0.0;   // the crossing's distance from the triangle's boundary in its
                                   // plane, scene units (> 0 inside, < 0 outside), rounded
  double cosine = 0.0;             // |cos| of the angle between the ray and the plane's normal
  bool quadric = false;            // the primitive is a sphere or a cone
  bool entering = false;           // quadric: the ray enters the solid at t (a tangent counts)
};

// The exact closest hit of a ray.
struct ExactHit {
  uint32_t prim = 0;
  double t = 0.0;           // ExactT::toDouble of the exact t
  bool onBoundary = false;  // the ray meets the triangle exactly on an edge or a vertex (a
                            // quadric: tangent, or on a rim)
  bool entering = false;    // quadric: the ray enters the solid there
};

// Counts of one oracle's work, for the tests and the docs.
struct ExactStats {
  uint64_t pairs = 0;         // ray-primitive pairs looked at
  uint64_t exactPairs = 0;    // pairs the double filter could not settle (every quadric's)
  uint64_t exactCompares = 0; // closest-hit comparisons settled in integers
};

// Brute force over every primitive of `scene` (which must outlive it): exact,
// ~40 ns a triangle pair here (bunny, 2000 rays aimed at vertices: one pair in
// 10^4 reaches the integer path), a few microseconds a quadric pair (always
// GMP). Closest hit: the least exact t in (0, ray.tMax] over triangles and
// quadrics alike; exact ties go to the lower id, the rule of closerHit().
// Throws InputError for a ray with a NaN or infinite component or a zero
// direction.
// A conservative culling of a scene's triangles for one ray: `out` receives at
// least every triangle the ray meets in exact arithmetic (e.g. from a BVH whose
// boxes are grown a little), in any order, each once. Quadrics are not culled:
// every query looks at each of them.
using TriangleCandidates = std::function<void(const Ray& ray, std::vector<uint32_t>& out)>;

class ExactOracle {
 public:
  // Without candidates every query looks at every triangle.
  explicit ExactOracle(const Scene& scene, TriangleCandidates candidates = {})
      : scene_(scene), candidates_(std::move(candidates)) {}
  explicit ExactOracle(Scene&&, TriangleCandidates = {}) = delete;  // keeps a reference: a temporary would dangle

  std::optional<ExactHit> intersect(const Ray& ray, ExactStats* stats = nullptr) const;
  // Every primitive the ray hits in (0, ray.tMax], in id order: what an any-hit
  // answer must account for.
  std::vector<ExactHit> hitsOnSegment(const Ray& ray) const;
  ExactRelation relation(const Ray& ray, uint32_t prim) const;
  const Scene& scene() const { return scene_; }

 private:
  // Calls visit(prim) for every primitive the query must look at, in id order.
  template <class Visit>
  void forEachCandidate(const Ray& ray, Visit&& visit) const;

  const Scene& scene_;
  TriangleCandidates candidates_;
};

// The verdict on one tracer's answer for one ray, against the exact truth.
enum class Verdict {
  Correct,   // same hit triangle at a t within the tolerance (or both miss)
  Tie,       // another triangle at exactly the same t
  Rounding,  // within the tracer's tolerance of the truth: a near-tie in t, or a
             // crossing within the tolerance of a triangle's boundary (a grazing
             // ray, a ray aimed at an edge or a vertex of an open mesh), or a
             // hit at t ~ 0 from an origin on a triangle
  Wrong,     // anything else: a real error of the tracer
};
std::string_view toString(Verdict verdict);

struct Judgement {
  Verdict verdict = Verdict::Correct;
  std::string_view reason;  // one phrase, e.g. "missed a hit away from any edge"
};

// How far a tracer's geometry may lie from the exact one, for one triangle,
// and still be explained by the rounding of its inputs: the ray or the
// triangle moved by up to `edge` scene units across the ray (so a crossing
// within edge / cos of the boundary may go either way), and t off by up to
// t / cos + tRelative * t.
struct Tolerance {
  double edge = 0.0;
  double t = 0.0;
  double tRelative = 0.0;
};
using ToleranceOf = std::function<Tolerance(const Triangle&)>;
// The same for a quadric: its surface may lie up to `edge` scene units from
// the exact one along its normal (a sphere's radius off by edge; a cone's
// radii by edge sqrt(1 + k^2), k its slope, and its end planes by edge along
// the axis), and t as for a triangle with the cosine at the hit. judge()
// moves the surface out and in by `edge` (a cone's ends out and in too: four
// moves; the float reference in double on the moved shapes) and excuses an
// answer one of those gives: a grazing ray within edge of the silhouette, a
// ray past a rim, a root at t ~ 0 from an origin on the surface, the other root.
using QuadricToleranceOf = std::function<Tolerance(const Quadric&)>;

// A float32 tracer's: 2^-20 (a few float roundings) times the largest
// coordinate magnitude M of the ray's origin and the triangle; t within that
// over |d|, and 2^-20 relative.
inline constexpr double kFloatRoundingBound = 0x1p-20;
Tolerance floatRounding(const Ray& ray, const Triangle& tri);
// A quadric's: the same with M over the ray's origin and the quadric's box
// (Quadric::bounds: the center or axis ends grown by the radii).
Tolerance floatRounding(const Ray& ray, const Quadric& quadric);

// Judges `answer` (a tracer's closest hit of `ray`, or nullopt for a miss)
// against `truth` = oracle.intersect(ray), with the tracer's tolerance
// (floatRounding when empty; the fixed-point hardware brings its lattice's,
// sw/driver/report.h) and, for quadrics, `quadricTolerance` (floatRounding
// when empty).
Judgement judge(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                const std::optional<ExactHit>& truth, const ToleranceOf& tolerance = {},
                const QuadricToleranceOf& quadricTolerance = {});

// Judges an any-hit answer (a shadow ray's: blocked when `answer` holds some hit
// in (0, ray.tMax], clear when nullopt) against exact arithmetic. Blocked is
// correct when any triangle truly blocks; a blocker the truth does not have
// must lie within the tolerance (of an edge, the ray's origin or the segment's
// end), and so must every true blocker of an answer of clear.
Judgement judgeAnyHit(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                      const ToleranceOf& tolerance = {}, const QuadricToleranceOf& quadricTolerance = {});

}  // namespace lancer
