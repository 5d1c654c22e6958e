#include "oracle/exact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "common/aabb.h"

namespace lancer {

// ---- Exact t -------------------------------------------------------------------

ExactT::ExactT(mpz_class num, mpz_class den, long shift) : num_(std::move(num)), den_(std::move(den)), shift_(shift) {
  if (sgn(den_) < 0) {
    num_ = -num_;
    den_ = -den_;
  }
}

double ExactT::toDouble() const {
  mpq_class q(num_, den_);
  q.canonicalize();
  return std::ldexp(q.get_d(), static_cast<int>(shift_));
}

int compare(const ExactT& a, const ExactT& b) {
  // a.num / a.den * 2^a.shift  vs  b.num / b.den * 2^b.shift, dens > 0.
  const long base = std::min(a.shift_, b.shift_);
  mpz_class lhs = a.num_ * b.den_;
  mpz_class rhs = b.num_ * a.den_;
  mpz_mul_2exp(lhs.get_mpz_t(), lhs.get_mpz_t(), static_cast<mp_bitcnt_t>(a.shift_ - base));
  mpz_mul_2exp(rhs.get_mpz_t(), rhs.get_mpz_t(), static_cast<mp_bitcnt_t>(b.shift_ - base));
  const int c = cmp(lhs, rhs);
  return (c > 0) - (c < 0);
}

namespace {

// ---- The double filter -----------------------------------------------------------
//
// Notation: a_i = v_i - o (rounded to double: relative error <= u per
// component, u = 2^-53; the floats' own values are exact in double), d exact.
//   s_i = det(a_j, a_k, d), (i, j, k) cyclic: the signed volume of the ray and
//         the edge opposite v_i; the crossing's barycentric of v_i is s_i / den;
//   den = s_0 + s_1 + s_2 = d . ((v1 - v0) x (v2 - v0));
//   num = det(a_0, a_1, a_2) = (v0 - o) . n;  t = num / den.
// Each is a sum of products of three inputs; with two or three rounded rows
// and five rounded operations its error is below 8u times its permanent (the
// same sum with absolute values; Shewchuk's orient3d bound is (7u + 56u^2)).
// The filter uses 16u (num, s_i) and adds the sum's rounding for den, so every
// sign it reports is the exact sign. No underflow: nonzero differences of
// floats are at least 2^-149, their triple products at least 2^-447.

constexpr double kU = 0x1p-53;
constexpr double kProductBound = 16 * kU;

struct Vec3d {
  double x, y, z;
};

Vec3d toVec(const glm::vec3& v) { return {v.x, v.y, v.z}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d absVec(const Vec3d& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }

double det3(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return a.x * (b.y * c.z - b.z * c.y) + a.y * (b.z * c.x - b.x * c.z) + a.z * (b.x * c.y - b.y * c.x);
}
// The permanent: det3 with every term's sign made positive (inputs already |.|).
double perm3(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return a.x * (b.y * c.z + b.z * c.y) + a.y * (b.z * c.x + b.x * c.z) + a.z * (b.x * c.y + b.y * c.x);
}

// A value and a bound on its error: its sign is certain when |value| > error.
struct Bounded {
  double value = 0.0;
  double error = 0.0;
  bool certain() const { return std::fabs(value) > error; }
  int sign() const { return (value > 0) - (value < 0); }
};

struct FilterOutcome {
  enum Kind { Miss, Hit, Unsure } kind = Unsure;
  double t = 0.0, tLow = 0.0, tHigh = 0.0;  // for Hit: t and an interval holding the exact t
};

FilterOutcome filterPair(const Vec3d& o, const Vec3d& d, const Vec3d& ad, float tMax, const Triangle& tri) {
  const Vec3d a[3] = {sub(toVec(tri.v0), o), sub(toVec(tri.v1), o), sub(toVec(tri.v2), o)};
  const Vec3d aa[3] = {absVec(a[0]), absVec(a[1]), absVec(a[2])};
  Bounded s[3];
  bool positive = false, negative = false, unsure = false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    s[i] = {det3(a[j], a[k], d), kProductBound * perm3(aa[j], aa[k], ad)};
    if (!s[i].certain()) {
      unsure = true;
    } else if (s[i].value > 0) {
      positive = true;
    } else {
      negative = true;
    }
  }
  // Two edges certainly on opposite sides: the line misses the closed triangle.
  if (positive && negative) return {FilterOutcome::Miss};
  if (unsure) return {};
  // All three strictly of one sign: the line crosses the interior; den has that sign.
  const double den = s[0].value + s[1].value + s[2].value;
  const double denError = s[0].error + s[1].error + s[2].error + 2 * kU * (std::fabs(s[0].value) + std::fabs(s[1].value) + std::fabs(s[2].value));
  const Bounded num{det3(a[0], a[1], a[2]), kProductBound * perm3(aa[0], aa[1], aa[2])};
  if (!num.certain()) return {};
  if ((num.value > 0) != (den > 0)) return {FilterOutcome::Miss};  // t < 0
  const double relNum = num.error / std::fabs(num.value);
  const double relDen = denError / std::fabs(den);
  if (relNum > 0.25 || relDen > 0.25) return {};
  const double t = num.value / den;
  const double rel = (relNum + relDen) / (1.0 - relDen) + 3 * kU;
  FilterOutcome out{FilterOutcome::Hit, t, t * (1.0 - rel), t * (1.0 + rel)};
  if (std::isfinite(tMax)) {
    if (out.tLow > tMax) return {FilterOutcome::Miss};
    if (out.tHigh > tMax) return {};  // t may lie either side of tMax
  }
  return out;
}

// ---- The exact evaluation ---------------------------------------------------------

// A float as m * 2^e with m an integer (|m| < 2^24); e of zero is irrelevant.
struct Binary {
  long mantissa = 0;
  int exponent = 0;
};

Binary decompose(float f) {
  int e = 0;
  const double m = std::frexp(static_cast<double>(f), &e);  // f = m * 2^e, 0.5 <= |m| < 1
  return {static_cast<long>(std::ldexp(m, 24)), e - 24};
}

// The floats of one group scaled by 2^-base to integers.
mpz_class scaled(float f, int base) {
  const Binary b = decompose(f);
  mpz_class z(b.mantissa);
  if (b.mantissa != 0) mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(b.exponent - base));
  return z;
}

int minExponent(std::initializer_list<float> values) {
  int base = std::numeric_limits<int>::max();
  for (float f : values) {
    if (f != 0.0f) base = std::min(base, decompose(f).exponent);
  }
  return base == std::numeric_limits<int>::max() ? 0 : base;
}

using Zvec = std::array<mpz_class, 3>;

mpz_class det3(const Zvec& a, const Zvec& b, const Zvec& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The crossing's signed distance from the triangle's boundary and the cosine
// of the ray with the plane, in double (the exact t rounded): what a tolerance
// is measured against.
void measureCrossing(const Ray& ray, const Triangle& tri, double t, ExactRelation& rel) {
  const glm::dvec3 v[3] = {glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2)};
  const glm::dvec3 d(ray.dir);
  const glm::dvec3 p = glm::dvec3(ray.origin) + t * d;
  const glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
  rel.cosine = std::fabs(glm::dot(d, n)) / (glm::length(d) * glm::length(n));
  double inside = std::numeric_limits<double>::infinity(), outside = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 a = v[(i + 1) % 3], b = v[(i + 2) % 3];
    const glm::dvec3 ab = b - a;
    // Distance to the edge's line (inside) and to the edge segment (outside).
    inside = std::min(inside, glm::length(glm::cross(ab, p - a)) / glm::length(ab));
    const double along = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    outside = std::min(outside, glm::length(p - (a + along * ab)));
  }
  rel.boundaryDistance = rel.minBarycentric >= 0.0 ? inside : -outside;
}

// The exact predicates of one pair; with `measure`, also the rounded
// barycentric, boundary distance and cosine that judging needs (the closest-hit
// search does not).
ExactRelation exactRelation(const Ray& ray, const Triangle& tri, bool measure) {
  const glm::vec3 o = ray.origin, d = ray.dir;
  const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
  // Positions (origin and vertices) share one scale, the direction has its own:
  // t = num / den scales by 2^(positionBase - directionBase).
  const int positionBase = minExponent({o.x, o.y, o.z, v[0].x, v[0].y, v[0].z, v[1].x, v[1].y, v[1].z, v[2].x,
                                        v[2].y, v[2].z});
  const int directionBase = minExponent({d.x, d.y, d.z});
  const Zvec zo = {scaled(o.x, positionBase), scaled(o.y, positionBase), scaled(o.z, positionBase)};
  const Zvec zd = {scaled(d.x, directionBase), scaled(d.y, directionBase), scaled(d.z, directionBase)};
  Zvec a[3];
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) a[i][c] = scaled(v[i][c], positionBase) - zo[c];
  }
  mpz_class s[3];
  for (int i = 0; i < 3; ++i) s[i] = det3(a[(i + 1) % 3], a[(i + 2) % 3], zd);
  const mpz_class den = s[0] + s[1] + s[2];

  ExactRelation rel;
  if (sgn(den) == 0) {
    rel.parallel = true;
    rel.minBarycentric = std::numeric_limits<double>::quiet_NaN();
    return rel;
  }
  const int side = sgn(den);
  bool inside = true, boundary = false;
  rel.minBarycentric = std::numeric_limits<double>::infinity();
  for (const mpz_class& si : s) {
    const int sign = sgn(si) * side;
    inside = inside && sign >= 0;
    boundary = boundary || sign == 0;
    if (measure) {
      mpq_class barycentric(si, den);
      barycentric.canonicalize();  // (GMP's rationals need a positive denominator)
      rel.minBarycentric = std::min(rel.minBarycentric, barycentric.get_d());
    }
  }
  const mpz_class num = det3(a[0], a[1], a[2]);
  rel.t.emplace(num, den, static_cast<long>(positionBase) - directionBase);
  if (measure) measureCrossing(ray, tri, rel.t->toDouble(), rel);
  bool inRange = sgn(num) * side > 0;  // t > 0
  if (inRange && std::isfinite(ray.tMax)) {
    // t <= tMax exactly: tMax as a one-element ExactT.
    const Binary m = decompose(ray.tMax);
    inRange = compare(*rel.t, ExactT(mpz_class(m.mantissa), mpz_class(1), m.exponent)) <= 0;
  }
  rel.hit = inside && inRange;
  rel.onBoundary = rel.hit && boundary;
  return rel;
}

void checkRay(const Ray& ray) {
  if (!allFinite(ray.origin) || !allFinite(ray.dir) || std::isnan(ray.tMax)) {
    throw InputError(fmt::format("exact oracle: ray ({}, {}, {}) + t ({}, {}, {}) has a NaN or infinite component",
                                 ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z));
  }
  if (ray.dir == glm::vec3(0.0f)) throw InputError("exact oracle: ray with a zero direction");
}

// A hit found while searching: its t known as an interval, and exactly once needed.
struct Candidate {
  uint32_t prim = 0;
  double t = 0.0, tLow = 0.0, tHigh = 0.0;
  bool onBoundary = false;
  std::optional<ExactT> exact;
};

}  // namespace

template <class Visit>
void ExactOracle::forEachCandidate(const Ray& ray, Visit&& visit) const {
  if (!candidates_) {
    for (uint32_t prim = 0; prim < scene_.triangles.size(); ++prim) visit(prim);
    return;
  }
  // Id order: the closest-hit search keeps the lower id on an exact tie.
  std::vector<uint32_t> prims;
  candidates_(ray, prims);
  std::sort(prims.begin(), prims.end());
  for (uint32_t prim : prims) visit(prim);
}

ExactRelation ExactOracle::relation(const Ray& ray, uint32_t prim) const {
  checkRay(ray);
  if (prim >= scene_.triangles.size()) {
    throw InputError(fmt::format("exact oracle: triangle {} does not exist (the scene has {})", prim,
                                 scene_.triangles.size()));
  }
  return exactRelation(ray, scene_.triangles[prim], /*measure=*/true);
}

std::optional<ExactHit> ExactOracle::intersect(const Ray& ray, ExactStats* stats) const {
  checkRay(ray);
  const Vec3d o = toVec(ray.origin), d = toVec(ray.dir), ad = absVec(d);
  ExactStats local;
  std::optional<Candidate> best;
  const auto exactOf = [&](Candidate& c) -> const ExactT& {
    if (!c.exact) c.exact = exactRelation(ray, scene_.triangles[c.prim], /*measure=*/false).t;
    return *c.exact;
  };
  forEachCandidate(ray, [&](uint32_t prim) {
    ++local.pairs;
    const Triangle& tri = scene_.triangles[prim];
    const FilterOutcome f = filterPair(o, d, ad, ray.tMax, tri);
    if (f.kind == FilterOutcome::Miss) return;
    Candidate c{prim, f.t, f.tLow, f.tHigh, false, std::nullopt};
    if (f.kind == FilterOutcome::Unsure) {
      ++local.exactPairs;
      ExactRelation rel = exactRelation(ray, tri, /*measure=*/false);
      if (!rel.hit) return;
      c.t = c.tLow = c.tHigh = rel.t->toDouble();
      c.onBoundary = rel.onBoundary;
      c.exact = std::move(rel.t);
      // toDouble rounds toward zero: widen by an ulp so the interval holds t.
      c.tHigh = std::nextafter(c.tHigh, std::numeric_limits<double>::infinity());
    }
    if (!best || c.tHigh < best->tLow) {
      best = std::move(c);
    } else if (c.tLow <= best->tHigh) {
      // Overlapping intervals: compare exactly; a tie keeps the lower id (best).
      ++local.exactCompares;
      if (compare(exactOf(c), exactOf(*best)) < 0) best = std::move(c);
    }
  });
  if (stats) {
    stats->pairs += local.pairs;
    stats->exactPairs += local.exactPairs;
    stats->exactCompares += local.exactCompares;
  }
  if (!best) return std::nullopt;
  return ExactHit{best->prim, exactOf(*best).toDouble(), best->onBoundary};
}

std::vector<ExactHit> ExactOracle::hitsOnSegment(const Ray& ray) const {
  checkRay(ray);
  const Vec3d o = toVec(ray.origin), d = toVec(ray.dir), ad = absVec(d);
  std::vector<ExactHit> hits;
  forEachCandidate(ray, [&](uint32_t prim) {
    const Triangle& tri = scene_.triangles[prim];
    const FilterOutcome f = filterPair(o, d, ad, ray.tMax, tri);
    if (f.kind == FilterOutcome::Miss) return;
    if (f.kind == FilterOutcome::Hit) {
      hits.push_back({prim, f.t, false});
      return;
    }
    const ExactRelation rel = exactRelation(ray, tri, /*measure=*/false);
    if (rel.hit) hits.push_back({prim, rel.t->toDouble(), rel.onBoundary});
  });
  return hits;
}

// ---- Judging a tracer's answer -----------------------------------------------------

std::string_view toString(Verdict verdict) {
  switch (verdict) {
    case Verdict::Correct: return "correct";
    case Verdict::Tie: return "tie";
    case Verdict::Rounding: return "rounding";
    case Verdict::Wrong: return "wrong";
  }
  return "?";
}

namespace {

// The distance between the ray (a half-line) and the segment [a, b], in double
// (closest points of two segments, Ericson's "Real-Time Collision Detection"
// 5.1.9, the ray cut off beyond the segment's farthest point).
double rayToSegment(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b) {
  const double reach = 2.0 * (std::max(glm::length(a - o), glm::length(b - o)) + glm::length(b - a)) / glm::length(d);
  const glm::dvec3 d1 = d * reach, d2 = b - a, r = o - a;
  const double aa = glm::dot(d1, d1), ee = glm::dot(d2, d2), f = glm::dot(d2, r);
  double s = 0.0, t = 0.0;
  if (ee <= 0.0) {
    s = std::clamp(-glm::dot(d1, r) / aa, 0.0, 1.0);
  } else {
    const double c = glm::dot(d1, r), bb = glm::dot(d1, d2), denom = aa * ee - bb * bb;
    s = denom > 0.0 ? std::clamp((bb * f - c * ee) / denom, 0.0, 1.0) : 0.0;
    t = (bb * s + f) / ee;
    if (t < 0.0) {
      t = 0.0;
      s = std::clamp(-c / aa, 0.0, 1.0);
    } else if (t > 1.0) {
      t = 1.0;
      s = std::clamp((bb - c) / aa, 0.0, 1.0);
    }
  }
  return glm::length((o + s * d1) - (a + t * d2));
}

// The distance between the ray and the triangle's boundary (its three edges).
double rayToBoundary(const Ray& ray, const Triangle& tri) {
  const glm::dvec3 o(ray.origin), d(ray.dir), v0(tri.v0), v1(tri.v1), v2(tri.v2);
  return std::min({rayToSegment(o, d, v0, v1), rayToSegment(o, d, v1, v2), rayToSegment(o, d, v2, v0)});
}

// Whether a move of the ray or the triangle within the tolerance can take the
// crossing across the triangle's boundary: the crossing lies within
// edge / cos of it in the plane (an error of `edge` across the ray moves the
// crossing by edge / cos there), or the ray passes within `edge` of an edge in
// space. The second decides for slivers and needles, whose plane a move of a
// vertex within the tolerance can turn far: their crossing point says little.
bool marginal(const ExactRelation& rel, const Tolerance& tolerance, const Ray& ray, const Triangle& tri) {
  if (!rel.parallel && std::fabs(rel.boundaryDistance) * rel.cosine <= tolerance.edge) return true;
  return rayToBoundary(ray, tri) <= tolerance.edge;
}

// How far a crossing's t may move when its plane moves within the tolerance:
// further the more the ray grazes the plane (a small `cosine`).
double tSlack(const Tolerance& tolerance, double cosine, double t) {
  return tolerance.t / std::max(cosine, 1e-300) + tolerance.tRelative * std::fabs(t);
}

// Two t within the tolerance of each other, for a crossing at `cosine`.
bool nearT(double a, double b, const Tolerance& tolerance, double cosine) {
  return std::fabs(a - b) <= tSlack(tolerance, cosine, b);
}

// A crossing at t within the tolerance of the segment's end: a move of the
// plane within the tolerance can put it on either side of the end.
bool nearEnd(const Ray& ray, double t, const Tolerance& tolerance, double cosine) {
  return std::isfinite(ray.tMax) && nearT(t, double(ray.tMax), tolerance, cosine);
}

}  // namespace

Tolerance floatRounding(const Ray& ray, const Triangle& tri) {
  double m = 0.0;
  for (const glm::vec3& p : {tri.v0, tri.v1, tri.v2, ray.origin}) {
    m = std::max({m, double(std::fabs(p.x)), double(std::fabs(p.y)), double(std::fabs(p.z))});
  }
  const double edge = kFloatRoundingBound * m;
  return {edge, edge / glm::length(glm::dvec3(ray.dir)), kFloatRoundingBound};
}

Judgement judge(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                const std::optional<ExactHit>& truth, const ToleranceOf& tolerance) {
  const auto& tris = oracle.scene().triangles;
  const ToleranceOf& tol = tolerance ? tolerance : ToleranceOf([&](const Triangle& t) { return floatRounding(ray, t); });
  if (!answer && !truth) return {Verdict::Correct, "both miss"};
  std::optional<ExactRelation> truthRel;
  if (truth) truthRel = oracle.relation(ray, truth->prim);
  if (answer && truth && answer->prim == truth->prim) {
    // The right triangle; its t must be right within the tolerance too.
    if (nearT(answer->t, truth->t, tol(tris[truth->prim]), truthRel->cosine)) return {Verdict::Correct, "same triangle"};
    return {Verdict::Wrong, "the right triangle at a t beyond the tolerance"};
  }
  // The true hit within the tolerance of the ray's origin (a ray leaving a
  // surface): a tracer whose rounded origin lies on the far side of the plane
  // rightly goes on to whatever lies beyond.
  const bool truthAtOrigin = truth && nearT(truth->t, 0.0, tol(tris[truth->prim]), truthRel->cosine);
  if (!answer) {
    if (marginal(*truthRel, tol(tris[truth->prim]), ray, tris[truth->prim])) return {Verdict::Rounding, "missed a hit within the tolerance of an edge"};
    if (truthAtOrigin) return {Verdict::Rounding, "missed a hit within the tolerance of the ray's origin"};
    return {Verdict::Wrong, "missed a hit away from any edge"};
  }
  const ExactRelation given = oracle.relation(ray, answer->prim);
  const Tolerance givenTol = tol(tris[answer->prim]);
  // An origin on (or within the tolerance of) the answered triangle: a
  // tracer's t of about 0 is rounding, the exact t = 0 is no hit.
  if (!given.hit && given.t && nearT(given.t->toDouble(), 0.0, givenTol, given.cosine) &&
      given.boundaryDistance * given.cosine >= -givenTol.edge) {
    return {Verdict::Rounding, "a hit within the tolerance of the ray's origin"};
  }
  const bool givenPlausible = given.hit || marginal(given, givenTol, ray, tris[answer->prim]);
  if (!truth) {
    if (givenPlausible) return {Verdict::Rounding, "hit a triangle the ray passes within the tolerance of"};
    return {Verdict::Wrong, "hit where the ray misses everything"};
  }
  // Another triangle than the truth's.
  if (given.hit && *given.t == *truthRel->t) return {Verdict::Tie, "another triangle at the same t"};
  if (truthAtOrigin) return {Verdict::Rounding, "passed a hit within the tolerance of the ray's origin"};
  if (givenPlausible) {
    // A triangle degenerate in the scene's floats has no plane and no exact t;
    // the tracer's own t stands in (it could only hit it as rounded).
    const double givenT = given.t ? given.t->toDouble() : double(answer->t);
    // Either crossing may move: the answered one with its triangle's slack,
    // the true one with its own (large where the ray grazes its plane).
    const double slack = tSlack(givenTol, given.cosine, givenT) +
                         tSlack(tol(tris[truth->prim]), truthRel->cosine, truth->t);
    if (std::fabs(givenT - truth->t) <= slack) {
      return {Verdict::Rounding, "another triangle within the tolerance of the same t"};
    }
    // A triangle the ray passes within the tolerance of, nearer than the
    // truth: a tracer that rounds it to a hit rightly reports it.
    if (givenT < truth->t) return {Verdict::Rounding, "a nearer triangle the ray passes within the tolerance of"};
    if (marginal(*truthRel, tol(tris[truth->prim]), ray, tris[truth->prim])) {
      return {Verdict::Rounding, "missed a nearer hit within the tolerance of an edge"};
    }
  }
  return {Verdict::Wrong, given.hit ? "a farther triangle than the closest" : "a triangle the ray misses"};
}

Judgement judgeAnyHit(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                      const ToleranceOf& tolerance) {
  const auto& tris = oracle.scene().triangles;
  const ToleranceOf& tol = tolerance ? tolerance : ToleranceOf([&](const Triangle& t) { return floatRounding(ray, t); });
  const std::vector<ExactHit> blockers = oracle.hitsOnSegment(ray);
  if (answer.has_value() == !blockers.empty()) return {Verdict::Correct, answer ? "both blocked" : "both clear"};
  // Whether a crossing of triangle `prim` could go either way under the tolerance.
  const auto excusable = [&](uint32_t prim) {
    const ExactRelation rel = oracle.relation(ray, prim);
    const Tolerance t = tol(tris[prim]);
    if (marginal(rel, t, ray, tris[prim])) return true;
    if (!rel.t) return false;
    const double crossing = rel.t->toDouble();
    return nearT(crossing, 0.0, t, rel.cosine) || nearEnd(ray, crossing, t, rel.cosine);
  };
  if (answer) {
    if (excusable(answer->prim)) return {Verdict::Rounding, "blocked by a triangle within the tolerance"};
    return {Verdict::Wrong, "blocked where the segment is clear"};
  }
  for (const ExactHit& blocker : blockers) {
    if (!excusable(blocker.prim)) return {Verdict::Wrong, "clear where a triangle blocks away from any edge or end"};
  }
  return {Verdict::Rounding, "every blocker within the tolerance"};
}

}  // namespace lancer
