// The built-in closed cube: a closed object whose every face lies on the
// scene's bounding box, the case the lattice's margin exists for
// (driver/quantize.h): seen from outside, each ray enters the lattice on a
// face of the cube. Each face has its own colour, so an image says which faces
// a tracer saw.
#include <array>

#include "scene/scene.h"

namespace lancer {

std::vector<Triangle> boxTriangles(const glm::vec3& lo, const glm::vec3& hi) {
  // Corner c has x from bit 0, y from bit 1, z from bit 2: each corner is one
  // float triple, copied bit-identically into every triangle that shares it.
  std::array<glm::vec3, 8> corner;
  for (int c = 0; c < 8; ++c) corner[size_t(c)] = {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
  // Faces -x, +x, -y, +y, -z, +z, each wound counter-clockwise seen from outside.
  constexpr std::array<std::array<int, 4>, 6> kFaces = {{
      {0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
  std::vector<Triangle> out;
  for (const auto& f : kFaces) {
    out.push_back({corner[size_t(f[0])], corner[size_t(f[1])], corner[size_t(f[2])]});
    out.push_back({corner[size_t(f[0])], corner[size_t(f[2])], corner[size_t(f[3])]});
  }
  return out;
}

Scene makeCube() {
  Scene scene;
  scene.name = "builtin:cube";
  scene.triangles = boxTriangles(glm::vec3(0.0f), glm::vec3(1.0f));
  scene.materials = {
      Material{"-x red", {0.75f, 0.15f, 0.12f}},  Material{"+x green", {0.15f, 0.6f, 0.2f}},
      Material{"-y grey", {0.5f, 0.5f, 0.5f}},    Material{"+y yellow", {0.85f, 0.75f, 0.2f}},
      Material{"-z blue", {0.15f, 0.3f, 0.75f}},  Material{"+z white", {0.85f, 0.85f, 0.85f}},
  };
  for (uint32_t face = 0; face < 6; ++face) scene.materialOf.insert(scene.materialOf.end(), 2, face);
  scene.computeBounds();
  // From outside, above the +x, +y, +z corner: the +x, +y and +z faces in view.
  scene.view = View{{2.6f, 2.1f, 3.0f}, {0.5f, 0.5f, 0.5f}, {0.0f, 1.0f, 0.0f}, 35.0f};
  Light point;
  point.position = {3.0f, 4.0f, 2.0f};
  point.name = "point light above the cube";
  scene.lights.push_back(point);
  return scene;
}

}  // namespace lancer
