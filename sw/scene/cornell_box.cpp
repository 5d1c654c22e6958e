// The embedded default scene: the Cornell box as measured at Cornell
// (units are millimetres; y up; the open side faces -z where the camera stands).
#include <array>

#include "scene/scene.h"

namespace lancer {

namespace {

using Quad = std::array<glm::vec3, 4>;

enum MaterialId : uint32_t { kWhite, kRed, kGreen, kLight };

struct Part {
  MaterialId material;
  Quad quad;
};

// Each quad is split into (q0,q1,q2) and (q0,q2,q3); consecutive quads of a
// block share edges with bit-identical corners, so the blocks are closed.
constexpr Part kParts[] = {
    // Floor, ceiling, back wall.
    {kWhite, {{{552.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 559.2f}, {549.6f, 0.0f, 559.2f}}}},
    {kWhite, {{{556.0f, 548.8f, 0.0f}, {556.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 0.0f}}}},
    {kWhite, {{{549.6f, 0.0f, 559.2f}, {0.0f, 0.0f, 559.2f}, {0.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}}}},
    // Right wall (green) and left wall (red), as seen from the camera.
    {kGreen, {{{0.0f, 0.0f, 559.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 548.8f, 0.0f}, {0.0f, 548.8f, 559.2f}}}},
    {kRed, {{{552.8f, 0.0f, 0.0f}, {549.6f, 0.0f, 559.2f}, {556.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 0.0f}}}},
    // The light, half a millimetre below the ceiling so it never ties with it.
    {kLight, {{{343.0f, 548.3f, 227.0f}, {343.0f, 548.3f, 332.0f}, {213.0f, 548.3f, 332.0f}, {213.0f, 548.3f, 227.0f}}}},
    // Short block.
    {kWhite, {{{130.0f, 165.0f, 65.0f}, {82.0f, 165.0f, 225.0f}, {240.0f, 165.0f, 272.0f}, {290.0f, 165.0f, 114.0f}}}},
    {kWhite, {{{290.0f, 0.0f, 114.0f}, {290.0f, 165.0f, 114.0f}, {240.0f, 165.0f, 272.0f}, {240.0f, 0.0f, 272.0f}}}},
    {kWhite, {{{130.0f, 0.0f, 65.0f}, {130.0f, 165.0f, 65.0f}, {290.0f, 165.0f, 114.0f}, {290.0f, 0.0f, 114.0f}}}},
    {kWhite, {{{82.0f, 0.0f, 225.0f}, {82.0f, 165.0f, 225.0f}, {130.0f, 165.0f, 65.0f}, {130.0f, 0.0f, 65.0f}}}},
    {kWhite, {{{240.0f, 0.0f, 272.0f}, {240.0f, 165.0f, 272.0f}, {82.0f, 165.0f, 225.0f}, {82.0f, 0.0f, 225.0f}}}},
    // Tall block.
    {kWhite, {{{423.0f, 330.0f, 247.0f}, {265.0f, 330.0f, 296.0f}, {314.0f, 330.0f, 456.0f}, {472.0f, 330.0f, 406.0f}}}},
    {kWhite, {{{423.0f, 0.0f, 247.0f}, {423.0f, 330.0f, 247.0f}, {472.0f, 330.0f, 406.0f}, {472.0f, 0.0f, 406.0f}}}},
    {kWhite, {{{472.0f, 0.0f, 406.0f}, {472.0f, 330.0f, 406.0f}, {314.0f, 330.0f, 456.0f}, {314.0f, 0.0f, 456.0f}}}},
    {kWhite, {{{314.0f, 0.0f, 456.0f}, {314.0f, 330.0f, 456.0f}, {265.0f, 330.0f, 296.0f}, {265.0f, 0.0f, 296.0f}}}},
    {kWhite, {{{265.0f, 0.0f, 296.0f}, {265.0f, 330.0f, 296.0f}, {423.0f, 330.0f, 247.0f}, {423.0f, 0.0f, 247.0f}}}},
};

}  // namespace

Scene makeCornellBox() {
  Scene scene;
  scene.name = kDefaultSceneName;
  scene.materials = {
      Material{"white", glm::vec3(0.73f, 0.73f, 0.73f)},
      Material{"red", glm::vec3(0.65f, 0.05f, 0.05f)},
      Material{"green", glm::vec3(0.12f, 0.45f, 0.15f)},
      Material{"light", glm::vec3(0.78f), glm::vec3(15.0f)},
  };
  for (const Part& part : kParts) {
    const Quad& q = part.quad;
    scene.triangles.push_back({q[0], q[1], q[2]});
    scene.triangles.push_back({q[0], q[2], q[3]});
    scene.materialOf.insert(scene.materialOf.end(), 2, part.material);
  }
  scene.computeBounds();
  scene.view = View{{278.0f, 273.0f, -800.0f}, {278.0f, 273.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 39.3f};
  return scene;
}

}  // namespace lancer
