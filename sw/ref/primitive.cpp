#include "ref/primitive.h"

namespace lancer {

glm::vec3 geometricNormal(const Scene& scene, uint32_t prim, const glm::vec3& point) {
  if (scene.isQuadric(prim)) return glm::vec3(quadricNormal(QuadricShape::of(scene.quadricOf(prim)), glm::dvec3(point)));
  const Triangle& t = scene.triangles[prim];
  const glm::vec3 c = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
  const float l = glm::length(c);
  return l > 0.0f ? c / l : glm::vec3(0.0f);
}

}  // namespace lancer
