#include "oracle/exact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "common/aabb.h"
#include "ref/quadric.h"

namespace lancer {

// ---- Signs of a + b sqrt(r) + c sqrt(s), without a square root ---------------------

namespace {

int signOf(const mpz_class& z) { return sgn(z) > 0 ? 1 : (sgn(z) < 0 ? -1 : 0); }

// sign(a + b sqrt(r)), r >= 0: the sign of a term that is alone or agrees with
// the other; else the sign of the larger, |a| against |b| sqrt(r) by their
// squares a^2 against b^2 r.
int signOfSum(const mpz_class& a, const mpz_class& b, const mpz_class& r) {
  const int sa = signOf(a), sb = sgn(r) == 0 ? 0 : signOf(b);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  const int c = cmp(a * a, b * b * r);
  return c == 0 ? 0 : (c > 0 ? sa : sb);
}

// sign(a + b sqrt(r) + c sqrt(s)), r, s >= 0: with X = a + b sqrt(r) (its sign
// from above) and Y = c sqrt(s), as above, |X| against |Y| by the sign of
// X^2 - Y^2 = (a^2 + b^2 r - c^2 s) + 2ab sqrt(r), again of the first form.
int signOfSum(const mpz_class& a, const mpz_class& b, const mpz_class& r, const mpz_class& c, const mpz_class& s) {
  if (r == s) return signOfSum(a, b + c, r);
  const int sx = signOfSum(a, b, r), sy = sgn(s) == 0 ? 0 : signOf(c);
  if (sy == 0) return sx;
  if (sx == 0 || sx == sy) return sy;
  const mpz_class twoAb = 2 * a * b;
  const int larger = signOfSum(a * a + b * b * r - c * c * s, twoAb, r);
  return larger == 0 ? 0 : (larger > 0 ? sx : sy);
}

mpz_class shifted(const mpz_class& z, long bits) {
  mpz_class out;
  mpz_mul_2exp(out.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(bits));
  return out;
}

}  // namespace

// ---- Exact t -------------------------------------------------------------------

ExactT::ExactT(mpz_class num, mpz_class den, long shift)
    : ExactT(std::move(num), mpz_class(0), mpz_class(0), std::move(den), shift) {}

ExactT::ExactT(mpz_class num, mpz_class coef, mpz_class radicand, mpz_class den, long shift)
    : num_(std::move(num)), coef_(std::move(coef)), radicand_(std::move(radicand)), den_(std::move(den)),
      shift_(shift) {
  if (sgn(radicand_) == 0) coef_ = 0;
  if (sgn(coef_) == 0) radicand_ = 0;
  if (sgn(den_) < 0) {
    num_ = -num_;
    coef_ = -coef_;
    den_ = -den_;
  }
}

int ExactT::sign() const { return signOfSum(num_, coef_, radicand_); }

double ExactT::toDouble() const {
  mpq_class q;
  if (sgn(coef_) == 0) {
    q = mpq_class(num_, den_);
  } else {
    // sqrt(radicand) * 2^k to >= 140 bits, floored: relative error < 2^-139.
    const long k = std::max(0L, 140 - static_cast<long>(mpz_sizeinbase(radicand_.get_mpz_t(), 2)) / 2);
    mpz_class root;
    const mpz_class scaledRadicand = shifted(radicand_, 2 * k);
    mpz_sqrt(root.get_mpz_t(), scaledRadicand.get_mpz_t());
    if (signOf(num_) * signOf(coef_) >= 0) {
      // num and coef sqrt(r) of one sign: their sum loses nothing.
      q = mpq_class(shifted(num_, k) + coef_ * root, shifted(den_, k));
    } else {
      // A difference: rationalize, (n + c sqrt r) = (n^2 - c^2 r) / (n - c sqrt r),
      // whose denominator is again a sum of one sign.
      q = mpq_class(shifted(num_ * num_ - coef_ * coef_ * radicand_, k), den_ * (shifted(num_, k) - coef_ * root));
    }
  }
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
  if (sgn(a.coef_) == 0 && sgn(b.coef_) == 0) {
    const int c = cmp(lhs, rhs);
    return (c > 0) - (c < 0);
  }
  // (a.num + a.coef sqrt(a.r)) b.den 2^.. - (b.num + b.coef sqrt(b.r)) a.den 2^..
  const mpz_class ca = shifted(a.coef_ * b.den_, a.shift_ - base);
  const mpz_class cb = shifted(b.coef_ * a.den_, b.shift_ - base);
  return signOfSum(lhs - rhs, ca, a.radicand_, -cb, b.radicand_);
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

// ---- Quadrics, exactly ----------------------------------------------------------------
//
// The origin, the quadric's points and radii share one scale 2^positionBase, the
// direction has its own: x = 2^positionBase (O + mu D) with integer O, D, and
// t = mu 2^(positionBase - directionBase). Along the line, in integers,
//   sphere (center P, radius R): M = O - P,
//     G(mu) = |M + mu D|^2 - R^2;
//   cone (base P0, apex P1, radii R0, R1; w = P1 - P0, W = w.w, dR = R1 - R0):
//     M = O - P0, with h W = (M + mu D).w the height times |w|^2 / |w|,
//     G(mu) = W^2 |M + mu D|^2 - W ((M + mu D).w)^2 - (R0 W + dR (M + mu D).w)^2
//           = W^2 (rho^2 - R(h)^2),
// both G = A mu^2 + 2 B mu + C, G < 0 inside the solid; a cone's point lies
// between its end planes iff 0 <= (M + mu D).w <= W.

struct QuadricLine {
  mpz_class a, b, c, disc;
  long shift = 0;
  bool cone = false;
  mpz_class mw, dw, ww;  // cone: M.w, D.w, W
};

mpz_class dot(const Zvec& a, const Zvec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

QuadricLine quadricLine(const Ray& ray, const Quadric& q) {
  const glm::vec3 o = ray.origin, d = ray.dir, p0 = q.base, p1 = q.apex;
  const bool cone = q.kind == Quadric::Kind::Cone;
  const float r0 = std::fabs(q.baseRadius), r1 = cone ? std::fabs(q.apexRadius) : 0.0f;
  const int positionBase = cone ? minExponent({o.x, o.y, o.z, p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, r0, r1})
                                : minExponent({o.x, o.y, o.z, p0.x, p0.y, p0.z, r0});
  const int directionBase = minExponent({d.x, d.y, d.z});
  const auto scaledVec = [](const glm::vec3& v, int base) {
    return Zvec{scaled(v.x, base), scaled(v.y, base), scaled(v.z, base)};
  };
  const Zvec zo = scaledVec(o, positionBase), zd = scaledVec(d, directionBase), z0 = scaledVec(p0, positionBase);
  const Zvec m = {zo[0] - z0[0], zo[1] - z0[1], zo[2] - z0[2]};
  const mpz_class rb = scaled(r0, positionBase);
  QuadricLine line;
  line.shift = static_cast<long>(positionBase) - directionBase;
  line.cone = cone;
  if (!cone) {
    line.a = dot(zd, zd);
    line.b = dot(m, zd);
    line.c = dot(m, m) - rb * rb;
  } else {
    const Zvec z1 = scaledVec(p1, positionBase);
    const Zvec w = {z1[0] - z0[0], z1[1] - z0[1], z1[2] - z0[2]};
    const mpz_class dr = scaled(r1, positionBase) - rb;
    line.ww = dot(w, w);
    line.mw = dot(m, w);
    line.dw = dot(zd, w);
    const mpz_class w2 = line.ww * line.ww;
    const mpz_class s = rb * line.ww + dr * line.mw;  // R(h at M) W
    line.a = w2 * dot(zd, zd) - line.ww * line.dw * line.dw - dr * dr * line.dw * line.dw;
    line.b = w2 * dot(m, zd) - line.ww * line.mw * line.dw - s * dr * line.dw;
    line.c = w2 * dot(m, m) - line.ww * line.mw * line.mw - s * s;
  }
  line.disc = line.b * line.b - line.a * line.c;
  return line;
}

// One root mu = (p + q sqrt(disc)) / e, e > 0, and where its point lies.
struct ExactRoot {
  mpz_class p, q, e;
  bool entering = false;
  bool tangent = false;  // disc = 0: a double root
  bool between = true;   // between a cone's end planes, rims included
  bool onRim = false;    // exactly in an end plane
};

// The roots in ascending order. With A != 0, mu = (-B + s sqrt(disc)) / A and
// A mu + B = s sqrt(disc): the root with s = -1 is entering (G falls through 0),
// the smaller one when A > 0, the larger when A < 0. A = 0: one root -C / 2B,
// entering when B < 0; A = B = 0: none (a line along a cylinder's axis, or in
// its wall).
std::vector<ExactRoot> rootsOf(const QuadricLine& line) {
  std::vector<ExactRoot> roots;
  if (sgn(line.disc) < 0) return roots;
  if (sgn(line.a) == 0) {
    if (sgn(line.b) == 0) return roots;
    roots.push_back({-line.c, 0, 2 * line.b, sgn(line.b) < 0, false});
  } else if (sgn(line.disc) == 0) {
    roots.push_back({-line.b, 0, line.a, true, true});
  } else {
    const ExactRoot entering{-line.b, -1, line.a, true, false}, leaving{-line.b, 1, line.a, false, false};
    if (sgn(line.a) > 0) {
      roots = {entering, leaving};
    } else {
      roots = {leaving, entering};
    }
  }
  for (ExactRoot& r : roots) {
    if (sgn(r.e) < 0) {
      r.p = -r.p;
      r.q = -r.q;
      r.e = -r.e;
    }
    if (!line.cone) continue;
    // (M + mu D).w e = mw e + dw p + dw q sqrt(disc), against 0 and W e.
    const mpz_class low = line.mw * r.e + line.dw * r.p, slope = line.dw * r.q;
    const int aboveBase = signOfSum(low, slope, line.disc);
    const int belowApex = -signOfSum(low - line.ww * r.e, slope, line.disc);
    r.between = aboveBase >= 0 && belowApex >= 0;
    r.onRim = aboveBase == 0 || belowApex == 0;
  }
  return roots;
}

ExactT exactTOf(const ExactRoot& root, const QuadricLine& line) {
  return ExactT(root.p, root.q, line.disc, root.e, line.shift);
}

// t <= tMax exactly: tMax as a one-element ExactT.
bool withinTMax(const ExactT& t, float tMax) {
  if (!std::isfinite(tMax)) return true;
  const Binary m = decompose(tMax);
  return compare(t, ExactT(mpz_class(m.mantissa), mpz_class(1), m.exponent)) <= 0;
}

// |cos| of the angle between the ray and a unit normal.
double cosineWith(const Ray& ray, const glm::dvec3& normal) {
  const glm::dvec3 d(ray.dir);
  return std::fabs(glm::dot(d, normal)) / glm::length(d);
}

ExactRelation quadricRelation(const Ray& ray, const Quadric& quadric, bool measure) {
  const QuadricLine line = quadricLine(ray, quadric);
  const std::vector<ExactRoot> roots = rootsOf(line);
  ExactRelation rel;
  rel.quadric = true;
  rel.minBarycentric = rel.boundaryDistance = std::numeric_limits<double>::quiet_NaN();
  if (roots.empty()) {
    rel.parallel = true;
    return rel;
  }
  // The closest-hit rule: the first root ahead of the origin between the planes.
  for (const ExactRoot& root : roots) {
    if (!root.between || signOfSum(root.p, root.q, line.disc) <= 0) continue;
    rel.t = exactTOf(root, line);
    rel.entering = root.entering;
    rel.hit = withinTMax(*rel.t, ray.tMax);
    rel.onBoundary = rel.hit && (root.tangent || root.onRim);
    break;
  }
  if (!rel.t) {
    // No root ahead: the one between the planes nearest the origin.
    for (const ExactRoot& root : roots) {
      if (root.between) {
        rel.t = exactTOf(root, line);
        rel.entering = root.entering;
      }
    }
  }
  if (measure && rel.t) {
    const glm::dvec3 point = glm::dvec3(ray.origin) + rel.t->toDouble() * glm::dvec3(ray.dir);
    rel.cosine = cosineWith(ray, quadricNormal(QuadricShape::of(quadric), point));
  }
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
  bool entering = false;
};

// A quadric's hit as a candidate: its exact t, and an interval of an ulp either side.
Candidate quadricCandidate(uint32_t prim, ExactRelation&& rel) {
  const double t = rel.t->toDouble();
  return {prim, t, std::nextafter(t, -std::numeric_limits<double>::infinity()),
          std::nextafter(t, std::numeric_limits<double>::infinity()), rel.onBoundary, std::move(rel.t), rel.entering};
}

}  // namespace

template <class Visit>
void ExactOracle::forEachCandidate(const Ray& ray, Visit&& visit) const {
  const auto triangles = static_cast<uint32_t>(scene_.triangles.size());
  const auto total = static_cast<uint32_t>(scene_.primitiveCount());
  if (!candidates_) {
    for (uint32_t prim = 0; prim < total; ++prim) visit(prim);
    return;
  }
  // Id order: the closest-hit search keeps the lower id on an exact tie. The
  // candidates are triangles; every quadric follows them.
  std::vector<uint32_t> prims;
  candidates_(ray, prims);
  std::sort(prims.begin(), prims.end());
  for (uint32_t prim : prims) {
    if (prim < triangles) visit(prim);
  }
  for (uint32_t prim = triangles; prim < total; ++prim) visit(prim);
}

ExactRelation ExactOracle::relation(const Ray& ray, uint32_t prim) const {
  checkRay(ray);
  if (prim >= scene_.primitiveCount()) {
    throw InputError(fmt::format("exact oracle: primitive {} does not exist (the scene has {} triangles and {} quadrics)",
                                 prim, scene_.triangles.size(), scene_.quadrics.size()));
  }
  if (scene_.isQuadric(prim)) return quadricRelation(ray, scene_.quadricOf(prim), /*measure=*/true);
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
    Candidate c;
    if (scene_.isQuadric(prim)) {
      ++local.exactPairs;
      ExactRelation rel = quadricRelation(ray, scene_.quadricOf(prim), /*measure=*/false);
      if (!rel.hit) return;
      c = quadricCandidate(prim, std::move(rel));
    } else if (const FilterOutcome f = filterPair(o, d, ad, ray.tMax, scene_.triangles[prim]);
               f.kind == FilterOutcome::Miss) {
      return;
    } else if (f.kind == FilterOutcome::Hit) {
      c = Candidate{prim, f.t, f.tLow, f.tHigh, false, std::nullopt};
    } else {
      const Triangle& tri = scene_.triangles[prim];
      ++local.exactPairs;
      ExactRelation rel = exactRelation(ray, tri, /*measure=*/false);
      if (!rel.hit) return;
      c.prim = prim;
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
  return ExactHit{best->prim, exactOf(*best).toDouble(), best->onBoundary, best->entering};
}

std::vector<ExactHit> ExactOracle::hitsOnSegment(const Ray& ray) const {
  checkRay(ray);
  const Vec3d o = toVec(ray.origin), d = toVec(ray.dir), ad = absVec(d);
  std::vector<ExactHit> hits;
  forEachCandidate(ray, [&](uint32_t prim) {
    if (scene_.isQuadric(prim)) {
      const ExactRelation rel = quadricRelation(ray, scene_.quadricOf(prim), /*measure=*/false);
      if (rel.hit) hits.push_back({prim, rel.t->toDouble(), rel.onBoundary, rel.entering});
      return;
    }
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

namespace {

// kFloatRoundingBound times the largest coordinate magnitude of `points`.
Tolerance floatRoundingOver(const Ray& ray, std::initializer_list<glm::vec3> points) {
  double m = 0.0;
  for (const glm::vec3& p : points) {
    m = std::max({m, double(std::fabs(p.x)), double(std::fabs(p.y)), double(std::fabs(p.z))});
  }
  const double edge = kFloatRoundingBound * m;
  return {edge, edge / glm::length(glm::dvec3(ray.dir)), kFloatRoundingBound};
}

}  // namespace

Tolerance floatRounding(const Ray& ray, const Triangle& tri) {
  return floatRoundingOver(ray, {tri.v0, tri.v1, tri.v2, ray.origin});
}

Tolerance floatRounding(const Ray& ray, const Quadric& quadric) {
  const Aabb box = quadric.bounds();
  return floatRoundingOver(ray, {box.lo, box.hi, ray.origin});
}

namespace {

// The quadric's surface moved by `e` along its normal (out for e > 0, in for
// e < 0) and a cone's end planes by `ends` along its axis (out for ends > 0):
// a sphere's radius by e; a cone's radii by e sqrt(1 + k^2) (k its slope: the
// radial step of a normal step e), the radius continued along the slope past
// moved ends, radii clamped at 0. Nothing is left when the move swallows it.
std::optional<QuadricShape> movedShape(const QuadricShape& s, double e, double ends) {
  QuadricShape out = s;
  if (s.kind == Quadric::Kind::Sphere) {
    out.baseRadius = s.baseRadius + e;
    if (!(out.baseRadius > 0.0)) return std::nullopt;
    return out;
  }
  const glm::dvec3 w = s.apex - s.base;
  const double length = glm::length(w);
  if (!(length + 2.0 * ends > 0.0)) return std::nullopt;
  const glm::dvec3 axis = w / length;
  const double k = (s.apexRadius - s.baseRadius) / length, grow = e * std::sqrt(1.0 + k * k);
  out.base = s.base - ends * axis;
  out.apex = s.apex + ends * axis;
  out.baseRadius = std::max(0.0, s.baseRadius - k * ends + grow);
  out.apexRadius = std::max(0.0, s.apexRadius + k * ends + grow);
  if (out.baseRadius == 0.0 && out.apexRadius == 0.0) return std::nullopt;
  return out;
}

// The moves a quadric's view tries, each at 1/kMoveSteps of the tolerance up to it.
constexpr int kMoveSteps = 16;

// The unit vector from a cone's axis toward the ray, square to the axis, at
// their lines' closest approach (where the ray is parallel to the axis, from
// the axis to the ray's origin); zero when the ray meets the axis.
glm::dvec3 towardRay(const QuadricShape& s, const Ray& ray) {
  const glm::dvec3 w = glm::normalize(s.apex - s.base), d = glm::dvec3(ray.dir), o = glm::dvec3(ray.origin);
  const glm::dvec3 n = glm::cross(w, d);
  glm::dvec3 gap;
  if (glm::length(n) > 1e-12 * glm::length(d)) {
    // The common perpendicular of the two lines, signed from the axis to the ray.
    const glm::dvec3 unit = n / glm::length(n);
    gap = glm::dot(o - s.base, unit) * unit;
  } else {
    gap = (o - s.base) - glm::dot(o - s.base, w) * w;
  }
  const double length = glm::length(gap);
  return length > 0.0 ? gap / length : glm::dvec3(0.0);
}

// What judging asks of one primitive on the ray: the exact relation, the
// tracer's tolerance for it, whether a move within that tolerance can change
// whether the ray hits it, and (a quadric) the hits a move gives.
struct PrimView {
  ExactRelation rel;
  Tolerance tolerance;
  bool quadric = false;
  bool marginal = false;
  struct Moved {
    double t, cosine;
  };
  std::vector<Moved> moved;  // quadric: the hits of its surface moved out and in by up to tolerance.edge

  // t within the tolerance of a hit a move gives (another root, or the same root moved).
  bool nearMoved(double t) const {
    return std::any_of(moved.begin(), moved.end(),
                       [&](const Moved& m) { return nearT(t, m.t, tolerance, m.cosine); });
  }
  // A triangle's exact t (else `t`); a quadric's exact hit or a moved one,
  // whichever is nearest `t` (a move can trade one root for the other: at a
  // rim the near root's point crosses an end plane, and the exact hit is the
  // inside wall behind it), else `t`; with its cosine.
  std::pair<double, double> tNear(double t) const {
    if (!quadric) return rel.t ? std::pair{rel.t->toDouble(), rel.cosine} : std::pair{t, rel.cosine};
    std::pair<double, double> best{t, rel.cosine};
    double distance = std::numeric_limits<double>::infinity();
    if (rel.hit) {
      best = {rel.t->toDouble(), rel.cosine};
      distance = std::fabs(best.first - t);
    }
    for (const Moved& m : moved) {
      if (std::fabs(m.t - t) < distance) {
        distance = std::fabs(m.t - t);
        best = {m.t, m.cosine};
      }
    }
    return best;
  }
};

class Judging {
 public:
  Judging(const ExactOracle& oracle, const Ray& ray, const ToleranceOf& tolerance, const QuadricToleranceOf& quadric)
      : oracle_(oracle), ray_(ray), tolerance_(tolerance), quadricTolerance_(quadric) {}

  PrimView view(uint32_t prim) const {
    const Scene& scene = oracle_.scene();
    PrimView v;
    v.rel = oracle_.relation(ray_, prim);
    if (!scene.isQuadric(prim)) {
      const Triangle& tri = scene.triangles[prim];
      v.tolerance = tolerance_ ? tolerance_(tri) : floatRounding(ray_, tri);
      v.marginal = marginal(v.rel, v.tolerance, ray_, tri);
      return v;
    }
    const Quadric& q = scene.quadricOf(prim);
    v.quadric = true;
    v.tolerance = quadricTolerance_ ? quadricTolerance_(q) : floatRounding(ray_, q);
    // The float reference in double on the surface moved out and in, a cone's
    // ends out and in too (four moves: a rim's crossing goes either way when
    // the wall and the end plane move apart); its rounding (~1e-16 relative)
    // is far below any tolerance it is asked about.
    // Whether the ray hits is not monotonic in the move (a ray almost along a
    // short cone's axis meets its wall moved out a little and passes through
    // both open ends moved out a lot: the window can be a fifth of the
    // tolerance wide), so the moves are sampled at every 1/kMoveSteps of it.
    // A cone is also shifted square to its axis, toward the ray and away: for
    // a ray almost along a thin cone's axis a shift decides what no change of
    // its radii does (the SPD's tree, again).
    const QuadricShape shape = QuadricShape::of(q);
    const bool cone = q.kind == Quadric::Kind::Cone;
    const int moves = cone ? 6 : 2;
    const glm::dvec3 toward = cone ? towardRay(shape, ray_) : glm::dvec3(0.0);
    bool anyHit = v.rel.hit, anyMiss = !v.rel.hit;
    for (int step = kMoveSteps; step >= 1; --step) {
      const double e = v.tolerance.edge * step / kMoveSteps;
      for (int i = 0; i < moves; ++i) {
        std::optional<QuadricShape> moved;
        if (i < 4) {
          moved = movedShape(shape, i & 1 ? -e : e, i & 2 ? -e : e);
        } else {
          moved = shape;
          const glm::dvec3 shift = (i == 4 ? e : -e) * toward;
          moved->base += shift;
          moved->apex += shift;
        }
        const std::optional<QuadricHit> hit = moved ? intersectQuadric(ray_, *moved, prim) : std::nullopt;
        if (!hit) {
          anyMiss = true;
          continue;
        }
        anyHit = true;
        v.moved.push_back({hit->t, cosineWith(ray_, hit->normal)});
      }
    }
    v.marginal = anyHit && anyMiss;
    return v;
  }

 private:
  const ExactOracle& oracle_;
  const Ray& ray_;
  const ToleranceOf& tolerance_;
  const QuadricToleranceOf& quadricTolerance_;
};

// The phrase for "an edge" of the primitive.
std::string_view boundaryWord(const PrimView& v, std::string_view triangle, std::string_view quadric) {
  return v.quadric ? quadric : triangle;
}

}  // namespace

Judgement judge(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                const std::optional<ExactHit>& truth, const ToleranceOf& tolerance,
                const QuadricToleranceOf& quadricTolerance) {
  const Judging judging(oracle, ray, tolerance, quadricTolerance);
  if (!answer && !truth) return {Verdict::Correct, "both miss"};
  std::optional<PrimView> truthView;
  if (truth) truthView = judging.view(truth->prim);
  if (answer && truth && answer->prim == truth->prim) {
    // The right primitive; its t must be right within the tolerance too.
    if (nearT(answer->t, truth->t, truthView->tolerance, truthView->rel.cosine)) return {Verdict::Correct, "same triangle"};
    // A quadric's other root, or its root moved, where a move within the
    // tolerance gives it (a rim, an origin on the surface, a tangent).
    if (truthView->nearMoved(answer->t)) return {Verdict::Rounding, "the right quadric at a root a move within the tolerance gives"};
    return {Verdict::Wrong, "the right triangle at a t beyond the tolerance"};
  }
  // The true hit within the tolerance of the ray's origin (a ray leaving a
  // surface): a tracer whose rounded origin lies on the far side of the plane
  // rightly goes on to whatever lies beyond.
  const bool truthAtOrigin = truth && nearT(truth->t, 0.0, truthView->tolerance, truthView->rel.cosine);
  if (!answer) {
    if (truthView->marginal) {
      return {Verdict::Rounding, boundaryWord(*truthView, "missed a hit within the tolerance of an edge",
                                              "missed a hit within the tolerance of a silhouette or rim")};
    }
    if (truthAtOrigin) return {Verdict::Rounding, "missed a hit within the tolerance of the ray's origin"};
    return {Verdict::Wrong, "missed a hit away from any edge"};
  }
  const PrimView given = judging.view(answer->prim);
  // An origin on (or within the tolerance of) the answered primitive: a
  // tracer's t of about 0 is rounding, the exact t = 0 is no hit. (A quadric's
  // relation keeps t only for a root between its end planes.)
  if (!given.rel.hit && given.rel.t && nearT(given.rel.t->toDouble(), 0.0, given.tolerance, given.rel.cosine) &&
      (given.quadric || given.rel.boundaryDistance * given.rel.cosine >= -given.tolerance.edge)) {
    return {Verdict::Rounding, "a hit within the tolerance of the ray's origin"};
  }
  const bool givenPlausible = given.rel.hit || given.marginal;
  if (!truth) {
    if (givenPlausible) return {Verdict::Rounding, "hit a triangle the ray passes within the tolerance of"};
    return {Verdict::Wrong, "hit where the ray misses everything"};
  }
  // Another primitive than the truth's.
  if (given.rel.hit && *given.rel.t == *truthView->rel.t) return {Verdict::Tie, "another triangle at the same t"};
  if (truthAtOrigin) return {Verdict::Rounding, "passed a hit within the tolerance of the ray's origin"};
  if (givenPlausible) {
    // A triangle degenerate in the scene's floats has no plane and no exact t;
    // the tracer's own t stands in (it could only hit it as rounded). A
    // quadric the ray misses exactly: the hit of its moved surface nearest
    // the tracer's t.
    const auto [givenT, givenCosine] = given.tNear(answer->t);
    // Either crossing may move: the answered one with its primitive's slack,
    // the true one with its own (large where the ray grazes its surface).
    const double slack = tSlack(given.tolerance, givenCosine, givenT) +
                         tSlack(truthView->tolerance, truthView->rel.cosine, truth->t);
    if (std::fabs(givenT - truth->t) <= slack) {
      return {Verdict::Rounding, "another triangle within the tolerance of the same t"};
    }
    // A primitive the ray passes within the tolerance of, nearer than the
    // truth: a tracer that rounds it to a hit rightly reports it.
    if (givenT < truth->t) return {Verdict::Rounding, "a nearer triangle the ray passes within the tolerance of"};
    if (truthView->marginal) {
      return {Verdict::Rounding, boundaryWord(*truthView, "missed a nearer hit within the tolerance of an edge",
                                              "missed a nearer hit within the tolerance of a silhouette or rim")};
    }
  }
  return {Verdict::Wrong, given.rel.hit ? "a farther triangle than the closest" : "a triangle the ray misses"};
}

Judgement judgeAnyHit(const ExactOracle& oracle, const Ray& ray, const std::optional<Hit>& answer,
                      const ToleranceOf& tolerance, const QuadricToleranceOf& quadricTolerance) {
  const Judging judging(oracle, ray, tolerance, quadricTolerance);
  const std::vector<ExactHit> blockers = oracle.hitsOnSegment(ray);
  if (answer.has_value() == !blockers.empty()) return {Verdict::Correct, answer ? "both blocked" : "both clear"};
  // Whether a crossing of primitive `prim` could go either way under the tolerance.
  const auto excusable = [&](uint32_t prim) {
    const PrimView v = judging.view(prim);
    if (v.marginal) return true;
    std::vector<std::pair<double, double>> crossings;  // (t, cosine)
    if (v.rel.t) crossings.emplace_back(v.rel.t->toDouble(), v.rel.cosine);
    for (const PrimView::Moved& m : v.moved) crossings.emplace_back(m.t, m.cosine);
    return std::any_of(crossings.begin(), crossings.end(), [&](const std::pair<double, double>& c) {
      return nearT(c.first, 0.0, v.tolerance, c.second) || nearEnd(ray, c.first, v.tolerance, c.second);
    });
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
