#include "scene/surface.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

ShadingNormals shadingNormals(const Triangle& tri, const std::array<const glm::vec3*, 3>& fileNormals) {
  const glm::vec3 cross = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
  const float area = glm::length(cross);
  const glm::vec3 geometric = area > 0.0f && std::isfinite(area) ? cross / area : glm::vec3(0.0f);
  std::array<glm::vec3, 3> n{geometric, geometric, geometric};
  for (int k = 0; k < 3; ++k) {
    if (!fileNormals[k]) continue;
    const float length = glm::length(*fileNormals[k]);
    if (length > 0.0f && std::isfinite(length)) n[k] = *fileNormals[k] / length;
  }
  return {n[0], n[1], n[2]};
}

void checkMaterialTerms(const Material& m, const std::string& where) {
  for (const auto& [term, c] : {std::pair{"diffuse colour (Kd)", m.diffuse}, std::pair{"emission (Ke)", m.emission}}) {
    if (!allFinite(c)) {
      throw InputError(
          fmt::format("{}: material '{}': {} ({}, {}, {}) is not finite", where, m.name, term, c.x, c.y, c.z));
    }
  }
  for (const auto& [term, w] : {std::pair{"specular weight (Ks)", m.ks}, std::pair{"shininess (Ns)", m.shine},
                                std::pair{"transmittance (1 - d)", m.transmittance}}) {
    if (!(w >= 0.0f) || !std::isfinite(w)) {
      throw InputError(fmt::format("{}: material '{}': {} {} must be finite and >= 0", where, m.name, term, w));
    }
  }
}

}  // namespace lancer
