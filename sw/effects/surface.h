#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// A ray's hit as the integrators shade it: the point, the normals, the side.
struct SurfacePoint {
  const Material& material;
  glm::vec3 point;      // triangle: from the barycentrics, on its plane to float rounding; quadric: below
  glm::vec3 dir;        // the ray's unit direction
  glm::vec3 geometric;  // unit geometric normal (-dir for a degenerate triangle; effectsGeometricNormal)
  glm::vec3 normal;     // shading normal, turned to the side the ray arrives on
  bool front;           // the ray arrives on the geometric normal's side
  glm::vec3 outward{0.0f};  // a quadric's unit normal out of its solid (zero on a triangle)

  // The side of the geometric normal a ray leaving here along `d` leaves on
  // (WaveRay::side): +1 front, -1 back; exactly in the plane, the side the
  // arriving ray came from.
  int8_t sideOf(const glm::vec3& d) const {
    const float side = glm::dot(d, geometric);
    return side > 0.0f ? 1 : side < 0.0f ? -1 : (front ? 1 : -1);
  }
  // A ray leaving a quadric here along `d` goes into its solid, where the
  // quadric's far side may be its next hit (WaveRay::intoSolid); never on a triangle.
  bool intoSolid(const glm::vec3& d) const { return glm::dot(d, outward) < 0.0f; }
};

// The shading normal is Scene::normals interpolated with the hit's
// barycentrics (NFF `pp`, tessellated spheres and cones), else the geometric
// normal (SPD rule 3); both are turned to the side the ray arrives on, so an
// opaque triangle hit from behind shades as if two-sided (docs/effects.md).
// A native quadric's hit (docs/effects.md, "Native quadrics"): the point is
// the ray's at hit.t moved onto the surface along its normal
// (projectOntoQuadric: a tracer may have traced the ray from an origin moved
// off the one it names), the geometric normal effectsGeometricNormal() there,
// and the shading normal the geometric one.
SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit);

// The geometric normal the effects give quadric `prim` at `point` (its
// SurfacePoint::geometric; WaveRay::side is relative to it): the unit normal
// out of its solid, turned inwards on an NFF inside-visible quadric (a
// negative radius), as the NFF reader winds such a quadric's tessellation, so
// its visible inside is its front.
glm::vec3 effectsGeometricNormal(const Scene& scene, uint32_t prim, const glm::vec3& point);

}  // namespace lancer
