#include "ref/shade.h"

#include <cmath>

#include "ref/primitive.h"

namespace lancer {

Image shadeHits(const Scene& scene, std::span<const Ray> rays, std::span<const std::optional<Hit>> hits,
                int width, int height) {
  Image image(width, height);
  const glm::vec3 background(0.05f, 0.05f, 0.08f);
  // Light from the centroid of the emitters when the scene has any (the Cornell
  // box's ceiling lamp), else from the eye. A cosine only: no shadow rays.
  glm::vec3 emitterSum(0.0f);
  int emitters = 0;
  for (size_t t = 0; t < scene.size(); ++t) {
    if (scene.materials[scene.materialOf[t]].emission == glm::vec3(0.0f)) continue;
    const Triangle& e = scene.triangles[t];
    emitterSum += (e.v0 + e.v1 + e.v2) / 3.0f;
    ++emitters;
  }
  for (size_t i = 0; i < hits.size() && i < size_t(width) * size_t(height); ++i) {
    if (!hits[i] || hits[i]->prim >= scene.primitiveCount()) {
      image.set(i, background.r, background.g, background.b);
      continue;
    }
    const uint32_t prim = hits[i]->prim;
    const Material& material = scene.materials[scene.materialOf[prim]];
    const glm::vec3 point = rays[i].origin + hits[i]->t * rays[i].dir;
    glm::vec3 normal;  // any length: only the cosine counts
    if (scene.isQuadric(prim)) {
      normal = geometricNormal(scene, prim, point);
    } else {
      const Triangle& tri = scene.triangles[prim];
      normal = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    }
    const glm::vec3 light = emitters ? emitterSum / float(emitters) : rays[i].origin;
    const glm::vec3 toLight = light - point;
    const float lengths = glm::length(normal) * glm::length(toLight);
    const float cosine = lengths > 0.0f ? std::abs(glm::dot(normal, toLight)) / lengths : 0.0f;
    const glm::vec3 color = material.diffuse * (0.15f + 0.85f * cosine) + glm::min(material.emission, glm::vec3(1.0f));
    image.set(i, color.r, color.g, color.b);
  }
  return image;
}

}  // namespace lancer
