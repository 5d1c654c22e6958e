#include "effects/lights.h"

#include <algorithm>
#include <cmath>

#include "common/ray.h"

namespace lancer {

std::vector<Emitter> emittersOf(const Scene& scene) {
  std::vector<Emitter> emitters;
  for (uint32_t t = 0; t < scene.size(); ++t) {
    const Material& m = scene.materials[scene.materialOf[t]];
    if (m.emission == glm::vec3(0.0f)) continue;
    const Triangle& tri = scene.triangles[t];
    const glm::vec3 c = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    const float twice = glm::length(c);
    if (twice == 0.0f) continue;  // a degenerate emitter has no area to sample
    emitters.push_back({t, c / twice, 0.5f * twice, m.emission});
  }
  return emitters;
}

std::optional<LightPath> pathToLight(const Light& l, const glm::vec3& point) {
  LightPath p{glm::vec3(0.0f), kInfinity, l.color};
  if (l.kind == Light::Kind::Directional) {
    p.dir = -glm::normalize(l.direction);
    return p;
  }
  const glm::vec3 toLight = l.position - point;
  p.distance = glm::length(toLight);
  if (!(p.distance > 0.0f)) return std::nullopt;
  p.dir = toLight / p.distance;
  if (l.kind == Light::Kind::Spot) {
    const float c = glm::dot(-p.dir, glm::normalize(l.direction));
    if (c <= l.outerConeCos) return std::nullopt;  // outside the cone no light arrives
    if (l.innerConeCos > l.outerConeCos) {
      p.color *= std::clamp((c - l.outerConeCos) / (l.innerConeCos - l.outerConeCos), 0.0f, 1.0f);
    }
  }
  return p;
}

}  // namespace lancer
