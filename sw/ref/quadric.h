#pragma once

// The float reference's ray-quadric test (issue #40): an NFF sphere or open
// cone against a ray, in double. The exact arbiter (sw/oracle/exact.h)
// decides the same questions without rounding; this is the tracer it judges
// (docs/oracle.md, "Quadrics in the exact arbiter and the float reference").

#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// A quadric's geometry in double: the scene's (the floats as they are, radii
// |r|: the sign of an NFF radius says which side is visible, not where the
// surface is), or that surface moved by a tolerance (the arbiter's leeway).
// A sphere uses base and baseRadius; a cone is the surface at distance
// R(h) = baseRadius + (apexRadius - baseRadius) h / |apex - base| from the
// axis, 0 <= h <= |apex - base| (open ends, rims included).
struct QuadricShape {
  Quadric::Kind kind = Quadric::Kind::Sphere;
  glm::dvec3 base{0.0}, apex{0.0};
  double baseRadius = 0.0, apexRadius = 0.0;  // >= 0; a cone's not both 0

  static QuadricShape of(const Quadric& quadric);
};

// A ray-quadric hit: `hit` as intersectTriangle returns it (prim, t rounded to
// float; u = 0 entering, 1 leaving, as the golden model's u_num; v = 0), the
// root in double, the side and the outward normal.
struct QuadricHit {
  Hit hit;
  double t = 0.0;           // the root before rounding (hit.t is this rounded to float)
  bool entering = false;    // the ray passes from outside the solid (farther from the center
                            // or axis than the surface) to inside; a tangent counts as entering
  glm::dvec3 normal{0.0};   // the unit geometric normal at the hit, pointing out of the solid
                            // whatever the sign of the NFF radius
};

// Closest hit of `ray` on the quadric: the nearer root whose float t is in
// (0, ray.tMax] and whose point lies between the cone's end planes, else the
// farther such root (a ray in through an open end hits the inside wall), else
// nullopt. Robust: the roots are taken from the line's point nearest the
// quadric's center (no cancellation of large terms for a ray from far away),
// by the quadratic formula's two forms (no cancellation between -B and the
// square root), with |d_perp|^2 - k^2 h_d^2 and rho^2 - R^2 as products of a
// difference and a sum; a ray along a cylinder's axis (A = B = 0) misses, one
// parallel to a cone's side (A = 0) has its single root -C / 2B.
std::optional<QuadricHit> intersectQuadric(const Ray& ray, const QuadricShape& shape, uint32_t prim);
std::optional<QuadricHit> intersectQuadric(const Ray& ray, const Quadric& quadric, uint32_t prim);

// The unit outward normal of the quadric's surface (or of the quadric
// surface through `point` of the same family) at `point`: the gradient of
// rho^2 - R(h)^2. At a pointed apex, the axis.
glm::dvec3 quadricNormal(const QuadricShape& shape, const glm::dvec3& point);

// `point` moved along the surface's normal onto it: a sphere's nearest point
// (center + r (p - c) / |p - c|), a cone's by the one step that is exact for
// its linear radius (rho - R(h) removed along the normal of the point's
// meridian; the end planes do not bound it). For a point near the surface, a
// hit whose ray started a little off the line it is named by (an offset
// secondary origin). A point on a sphere's center or a cone's axis is
// returned as it is.
glm::dvec3 projectOntoQuadric(const QuadricShape& shape, const glm::dvec3& point);

}  // namespace lancer
