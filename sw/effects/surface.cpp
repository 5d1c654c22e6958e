#include "effects/surface.h"

namespace lancer {

SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit) {
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
