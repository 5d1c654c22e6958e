#include "effects/surface.h"

#include "ref/primitive.h"
#include "ref/quadric.h"

namespace lancer {

glm::vec3 effectsGeometricNormal(const Scene& scene, uint32_t prim, const glm::vec3& point) {
  const glm::vec3 n = geometricNormal(scene, prim, point);
  return scene.isQuadric(prim) && scene.quadricOf(prim).insideVisible() ? -n : n;
}

namespace {

SurfacePoint quadricSurfaceAt(const Scene& scene, const Ray& ray, const Hit& hit) {
  // The ray's point at t, in double, moved onto the surface along its normal
  // and rounded once. A tracer may trace a secondary ray from an origin moved
  // off the surface (the float reference by its offset, along the normal), so
  // the point at t of the ray the wave names can lie off the surface by about
  // that offset; the projection puts it back, as the barycentrics put a
  // triangle's hit on its plane.
  const QuadricShape shape = QuadricShape::of(scene.quadricOf(hit.prim));
  const glm::vec3 p(projectOntoQuadric(shape, glm::dvec3(ray.origin) + double(hit.t) * glm::dvec3(ray.dir)));
  const glm::vec3 d = glm::normalize(ray.dir);
  const glm::vec3 outward(quadricNormal(shape, glm::dvec3(p)));
  const glm::vec3 ng = scene.quadricOf(hit.prim).insideVisible() ? -outward : outward;
  const bool front = glm::dot(d, ng) < 0.0f;
  return {scene.materials[scene.materialOf[hit.prim]], p, d, ng, front ? ng : -ng, front, outward};
}

}  // namespace

SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit) {
  if (scene.isQuadric(hit.prim)) return quadricSurfaceAt(scene, ray, hit);
  const Triangle& tri = scene.triangles[hit.prim];
  const float w0 = 1.0f - hit.u - hit.v;
  const glm::vec3 p = w0 * tri.v0 + hit.u * tri.v1 + hit.v * tri.v2;
  const glm::vec3 d = glm::normalize(ray.dir);
  const glm::vec3 cross = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
  const float crossLength = glm::length(cross);
  const glm::vec3 ng = crossLength > 0.0f ? cross / crossLength : -d;
  const bool front = glm::dot(d, ng) < 0.0f;
  glm::vec3 ns = ng;
  if (!scene.normals.empty()) {
    const ShadingNormals& sn = scene.normals[hit.prim];
    const glm::vec3 n = w0 * sn.n0 + hit.u * sn.n1 + hit.v * sn.n2;
    if (glm::length(n) > 0.0f) ns = glm::normalize(n);
  }
  return {scene.materials[scene.materialOf[hit.prim]], p, d, ng, front ? ns : -ns, front};
}

}  // namespace lancer
