#include "ref/quadric.h"

#include <array>
#include <cmath>

namespace lancer {

QuadricShape QuadricShape::of(const Quadric& q) {
  return {q.kind, glm::dvec3(q.base), glm::dvec3(q.apex), std::fabs(double(q.baseRadius)),
          std::fabs(double(q.apexRadius))};
}

namespace {

// The cone's frame: unit axis, length, slope of the radius.
struct ConeFrame {
  glm::dvec3 axis;  // unit, base to apex
  double length;
  double slope;     // k = (apexRadius - baseRadius) / length
};

ConeFrame frameOf(const QuadricShape& s) {
  const glm::dvec3 w = s.apex - s.base;
  const double length = glm::length(w);
  return {w / length, length, (s.apexRadius - s.baseRadius) / length};
}

// x^2 - y^2 as (|x| - |y|)(|x| + |y|): no cancellation of the squares.
double diffOfSquares(double x, double y) { return (std::fabs(x) - std::fabs(y)) * (std::fabs(x) + std::fabs(y)); }

}  // namespace

glm::dvec3 quadricNormal(const QuadricShape& s, const glm::dvec3& p) {
  if (s.kind == Quadric::Kind::Sphere) {
    const glm::dvec3 n = p - s.base;
    const double l = glm::length(n);
    return l > 0.0 ? n / l : glm::dvec3(0.0, 0.0, 1.0);
  }
  const ConeFrame f = frameOf(s);
  const glm::dvec3 x = p - s.base;
  const double h = glm::dot(x, f.axis);
  const glm::dvec3 radial = x - h * f.axis;
  // grad (rho^2 - R(h)^2) / 2 = radial - R(h) k axis.
  const glm::dvec3 n = radial - (s.baseRadius + f.slope * h) * f.slope * f.axis;
  const double l = glm::length(n);
  return l > 0.0 ? n / l : (f.slope <= 0.0 ? f.axis : -f.axis);
}

glm::dvec3 projectOntoQuadric(const QuadricShape& s, const glm::dvec3& p) {
  if (s.kind == Quadric::Kind::Sphere) {
    const glm::dvec3 x = p - s.base;
    const double l = glm::length(x);
    return l > 0.0 ? s.base + (s.baseRadius / l) * x : p;
  }
  // With u the unit radial direction and d = (rho - R(h)) / (1 + k^2), the
  // point p - d u + d k axis has rho' = rho - d and R(h') = R(h) + k^2 d: on the cone.
  const ConeFrame f = frameOf(s);
  const glm::dvec3 x = p - s.base;
  const double h = glm::dot(x, f.axis);
  const glm::dvec3 radial = x - h * f.axis;
  const double rho = glm::length(radial);
  if (!(rho > 0.0)) return p;
  const double d = (rho - (s.baseRadius + f.slope * h)) / (1.0 + f.slope * f.slope);
  return p - (d / rho) * radial + (d * f.slope) * f.axis;
}

std::optional<QuadricHit> intersectQuadric(const Ray& ray, const QuadricShape& s, uint32_t prim) {
  const glm::dvec3 o(ray.origin), d(ray.dir);
  const double dd = glm::dot(d, d);
  if (!(dd > 0.0)) return std::nullopt;
  // Step 1: restart the line at its point nearest the quadric's center (the
  // sphere's center, the cone's axis midpoint): lambda = lambda0 + s. Its
  // coefficients are then of the size of the quadric, not of the distance.
  const glm::dvec3 center = s.kind == Quadric::Kind::Sphere ? s.base : 0.5 * (s.base + s.apex);
  const double lambda0 = glm::dot(center - o, d) / dd;
  const glm::dvec3 p0 = o + lambda0 * d;

  // Step 2: F(p0 + s d) = A s^2 + 2 B s + C, F = rho^2 - R^2 for a cone (rho
  // the distance from the axis, R the radius at the point's height) and
  // |x - c|^2 - r^2 for a sphere; F < 0 inside the solid.
  double a = 0.0, b = 0.0, c = 0.0;
  ConeFrame frame{};
  double hm = 0.0, hd = 0.0;  // the cone: heights above the base of p0 and of d
  if (s.kind == Quadric::Kind::Sphere) {
    const glm::dvec3 m = p0 - s.base;
    a = dd;
    b = glm::dot(m, d);
    c = diffOfSquares(glm::length(m), s.baseRadius);
  } else {
    frame = frameOf(s);
    const glm::dvec3 m = p0 - s.base;
    hm = glm::dot(m, frame.axis);
    hd = glm::dot(d, frame.axis);
    const glm::dvec3 mPerp = m - hm * frame.axis, dPerp = d - hd * frame.axis;
    const double rm = s.baseRadius + frame.slope * hm;  // R at p0's height (negative past a point)
    a = diffOfSquares(glm::length(dPerp), frame.slope * hd);
    b = glm::dot(mPerp, dPerp) - frame.slope * hd * rm;
    c = diffOfSquares(glm::length(mPerp), rm);
  }

  // Step 3: the roots. disc < 0: the line misses the surface. A = B = 0: a
  // line along a cylinder's axis, never crossing its wall (or lying in it).
  // Otherwise q = -(B + sgn(B) sqrt(disc)) adds two terms of one sign, and the
  // roots are q / A and C / q (their product C / A); A = 0 (parallel to a
  // cone's side) leaves C / q = -C / 2B. The root q / A is entering (F falls
  // through 0: A s + B = -sgn(B) sqrt(disc) < 0) when B >= 0, C / q when
  // B < 0; a tangent (disc = 0) counts as entering.
  const double disc = b * b - a * c;
  if (!(disc >= 0.0) || (a == 0.0 && b == 0.0)) return std::nullopt;
  const double root = std::sqrt(disc);
  const double q = -(b + std::copysign(root, b));
  struct Root {
    double s;
    bool entering;
  };
  std::array<Root, 2> roots{};
  int count = 0;
  if (q == 0.0) {
    roots[count++] = {-b / a, true};  // B = 0 = disc: the tangent point p0 itself
  } else {
    if (a != 0.0) roots[count++] = {q / a, b >= 0.0 || disc == 0.0};
    roots[count++] = {c / q, b < 0.0 || disc == 0.0};
    if (count == 2 && roots[1].s < roots[0].s) std::swap(roots[0], roots[1]);
  }

  // Step 4: the nearer root ahead of the origin whose point lies between the
  // end planes, else the farther one; then the segment's end. Ahead means its
  // float t is > 0, the triangles' rule (a root that rounds to 0 is at the origin).
  for (int i = 0; i < count; ++i) {
    const double lambda = lambda0 + roots[i].s;
    const float t = static_cast<float>(lambda);
    if (!(t > 0.0f)) continue;
    if (s.kind == Quadric::Kind::Cone) {
      const double h = hm + roots[i].s * hd;
      if (!(h >= 0.0 && h <= frame.length)) continue;
    }
    if (!(t <= ray.tMax)) return std::nullopt;
    QuadricHit hit;
    hit.hit = Hit{prim, t, roots[i].entering ? 0.0f : 1.0f, 0.0f};
    hit.t = lambda;
    hit.entering = roots[i].entering;
    hit.normal = quadricNormal(s, o + lambda * d);
    return hit;
  }
  return std::nullopt;
}

std::optional<QuadricHit> intersectQuadric(const Ray& ray, const Quadric& quadric, uint32_t prim) {
  return intersectQuadric(ray, QuadricShape::of(quadric), prim);
}

}  // namespace lancer
