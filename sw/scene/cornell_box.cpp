// The embedded default scene: the Cornell box as measured at Cornell
// (units are millimetres; y up; the open side faces -z where the camera stands),
// with a mirror and a glass block so the Whitted demo shows every effect.
// Triangle ids and materials are documented in docs/scenes.md; the geometry is
// the classic one (traces/ and the golden cycle figures depend on it), the
// effects come from materials and one point light only.
#include <array>

#include "scene/scene.h"

namespace lancer {

namespace {

using Quad = std::array<glm::vec3, 4>;

// Indices into Scene::materials (appended ones keep the earlier indices).
enum MaterialId : uint32_t { kWhite, kRed, kGreen, kLight, kMirror, kGlass };

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
    // The lamp, an area light (its material emits), half a millimetre below the
    // ceiling so it never ties with it.
    {kLight, {{{343.0f, 548.3f, 227.0f}, {343.0f, 548.3f, 332.0f}, {213.0f, 548.3f, 332.0f}, {213.0f, 548.3f, 227.0f}}}},
    // Short block: glass (its faces wind outwards, so a ray's side tells entering
    // from leaving; it stands open on the floor, which closes it).
    {kGlass, {{{130.0f, 165.0f, 65.0f}, {82.0f, 165.0f, 225.0f}, {240.0f, 165.0f, 272.0f}, {290.0f, 165.0f, 114.0f}}}},
    {kGlass, {{{290.0f, 0.0f, 114.0f}, {290.0f, 165.0f, 114.0f}, {240.0f, 165.0f, 272.0f}, {240.0f, 0.0f, 272.0f}}}},
    {kGlass, {{{130.0f, 0.0f, 65.0f}, {130.0f, 165.0f, 65.0f}, {290.0f, 165.0f, 114.0f}, {290.0f, 0.0f, 114.0f}}}},
    {kGlass, {{{82.0f, 0.0f, 225.0f}, {82.0f, 165.0f, 225.0f}, {130.0f, 165.0f, 65.0f}, {130.0f, 0.0f, 65.0f}}}},
    {kGlass, {{{240.0f, 0.0f, 272.0f}, {240.0f, 165.0f, 272.0f}, {82.0f, 165.0f, 225.0f}, {82.0f, 0.0f, 225.0f}}}},
    // Tall block: a mirror.
    {kMirror, {{{423.0f, 330.0f, 247.0f}, {265.0f, 330.0f, 296.0f}, {314.0f, 330.0f, 456.0f}, {472.0f, 330.0f, 406.0f}}}},
    {kMirror, {{{423.0f, 0.0f, 247.0f}, {423.0f, 330.0f, 247.0f}, {472.0f, 330.0f, 406.0f}, {472.0f, 0.0f, 406.0f}}}},
    {kMirror, {{{472.0f, 0.0f, 406.0f}, {472.0f, 330.0f, 406.0f}, {314.0f, 330.0f, 456.0f}, {314.0f, 0.0f, 456.0f}}}},
    {kMirror, {{{314.0f, 0.0f, 456.0f}, {314.0f, 330.0f, 456.0f}, {265.0f, 330.0f, 296.0f}, {265.0f, 0.0f, 296.0f}}}},
    {kMirror, {{{265.0f, 0.0f, 296.0f}, {265.0f, 330.0f, 296.0f}, {423.0f, 330.0f, 247.0f}, {423.0f, 0.0f, 247.0f}}}},
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
      // diffuse, emission, kd, ks, shine, transmittance, ior
      Material{"mirror", glm::vec3(0.73f), glm::vec3(0.0f), 0.2f, 0.8f, 200.0f, 0.0f, 1.0f},
      Material{"glass", glm::vec3(1.0f), glm::vec3(0.0f), 0.0f, 0.1f, 200.0f, 0.9f, 1.5f},
  };
  for (const Part& part : kParts) {
    const Quad& q = part.quad;
    scene.triangles.push_back({q[0], q[1], q[2]});
    scene.triangles.push_back({q[0], q[2], q[3]});
    scene.materialOf.insert(scene.materialOf.end(), 2, part.material);
  }
  scene.computeBounds();
  scene.view = View{{278.0f, 273.0f, -800.0f}, {278.0f, 273.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 39.3f};
  // A point light under the lamp's centre, 10 mm below the ceiling (9.5 mm below
  // the lamp, which hides it only from a ~3 mm ring of ceiling around the lamp's
  // edge): the box shows a point light's hard shadows beside the lamp's sampled
  // soft ones. Half of NFF's white light, so lamp and point light together do
  // not saturate.
  Light point;
  point.kind = Light::Kind::Point;
  point.position = {278.0f, 538.8f, 279.5f};
  point.color = glm::vec3(0.5f);
  point.name = "ceiling point light";
  scene.lights.push_back(point);
  return scene;
}

}  // namespace lancer
