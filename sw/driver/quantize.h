#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "golden/quadric.h"
#include "golden/records.h"
#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// A ray as the hardware sees it, and how to map its answers back to the scene.
struct QuantizedRay {
  fx::QRay q;
  double tEnter = 0;  // scene t at the quantized origin (where the ray entered the lattice cube)
  double tScale = 1;  // scene t per unit of lattice t: t_scene = tEnter + tScale * t_lattice
};

// Lattice units left empty between the scene's bounds and each face of the
// lattice cube. A ray from outside enters the hardware at a point on a face of
// the cube; were that face also a face of the scene's box, a triangle lying on
// it would pass through the ray's origin, at t = 0, which the pipeline's t > 0
// excludes: a closed object seen from outside would show its inside. With the
// margin every entry point lies outside the scene's box, where no triangle
// passes. Two units, not one, so that a secondary origin (a hit on the box
// moved one unit off the surface, then rounded) stays inside the cube.
inline constexpr int64_t kLatticeMarginUnits = 2;

// The driver's boundary into the hardware's fixed-point space (docs/number-formats.md):
// the scene's bounding cube (centred on its bounds, side = the longest extent)
// maps onto the lattice [m, kPosMax - m]^3 (m = kLatticeMarginUnits) by one
// uniform scale, rounding to nearest. Rays are clipped to the lattice cube
// [0, kPosMax]^3 first, so an origin outside becomes the entry point; the
// direction is scaled so its dominant component is +-kDirMax.
class Quantizer {
 public:
  // Throws InputError if the bounds are empty or not finite, or the margin is
  // negative or leaves less than half the lattice to the scene. A margin of 0
  // is the lattice before issue #21 (faces of the scene on the lattice's).
  explicit Quantizer(const Aabb& sceneBounds, int64_t marginUnits = kLatticeMarginUnits);

  // Throws InputError if a vertex lies outside the lattice cube by more than half a unit.
  fx::QTriangle quantize(const Triangle& tri, uint32_t id) const;
  // Every triangle of the scene, id = its index. Throws InputError for a scene
  // with quadrics (the structures that call it do not hold them yet).
  std::vector<fx::QTriangle> quantize(const Scene& scene) const;
  // The triangles only, of a scene that may hold quadrics (quantizeQuadrics).
  std::vector<fx::QTriangle> quantizeTriangles(const Scene& scene) const;
  // A native quadric on the lattice (docs/quadrics.md, "On the lattice"): a
  // sphere's center and a cone's base and apex rounded to the nearest lattice
  // point as a vertex is, each |radius| to the nearest unit. What the lattice
  // cannot hold is made the nearest quadric it can: a sphere's radius at least
  // 1; a cone whose radii both round to 0 keeps 1 at its wider end, and one
  // whose ends round to one point is one unit long, along its axis' dominant
  // direction. Throws InputError as for a vertex outside the lattice.
  fx::QQuadric quantize(const Quadric& quadric, uint32_t id) const;
  // Every quadric of the scene, its id its primitive id (triangles first).
  std::vector<fx::QQuadric> quantizeQuadrics(const Scene& scene) const;
  // nullopt if the ray misses the cube (or leaves it before t = 0, or before tMax).
  // The ray must already be validated (finite, non-zero direction). A finite
  // tMax inside the cube becomes the segment end (rounded down to its code:
  // formats.h); one beyond the cube, none.
  std::optional<QuantizedRay> quantize(const Ray& ray, uint32_t id) const;
  // A ray from a point given in lattice coordinates (a hardware hit moved off
  // its surface), along ray.dir, ending at ray's tMax as quantize() does; t maps
  // back to `ray`'s own parameter. The origin rounds to the nearest lattice
  // point; nullopt if that lies outside the cube.
  std::optional<QuantizedRay> quantizeFrom(const glm::dvec3& latticeOrigin, const Ray& ray, uint32_t id) const;
  glm::dvec3 toLattice(const glm::dvec3& scenePoint) const { return (scenePoint - lo_) * scale_; }

  // The hardware's ray back in scene space (what it really traces), in double.
  glm::dvec3 sceneOrigin(const fx::QRay& q) const;
  glm::dvec3 sceneDirection(const fx::QRay& q) const;
  // Scene units per lattice unit.
  double unit() const { return 1.0 / scale_; }
  const glm::dvec3& latticeOrigin() const { return lo_; }

 private:
  // The quantized direction of lattice direction d, tScale, and the segment end
  // of a ray whose origin in the lattice is o, for the lattice origin out.q.org.
  void finish(QuantizedRay& out, const glm::dvec3& o, const glm::dvec3& d, double tMax) const;
  // A scene point on the lattice (round to nearest, the half unit of slack
  // clamped); `what` names it in the error for a point outside.
  std::array<int64_t, 3> latticePoint(const glm::vec3& point, const std::string& what) const;

  glm::dvec3 lo_;
  double scale_;  // lattice units per scene unit
};

}  // namespace lancer
