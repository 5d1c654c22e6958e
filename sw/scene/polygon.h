#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace lancer {

// Why an outline has no triangulation.
enum class PolygonFault : uint8_t { None, NoArea, CrossesItself };

// The end of a sentence that begins with the polygon ("polygon started at line
// 3 ..."): what the fault means to the person who wrote the file.
std::string_view describe(PolygonFault fault);

// A polygon cut into triangles: each triangle is three indices into the outline,
// wound as the outline is.
struct PolygonTriangles {
  std::vector<std::array<uint32_t, 3>> triangles;
  glm::vec3 normal{0.0f};  // the outline's unit Newell normal (its plane's, for a flat outline)
  PolygonFault fault = PolygonFault::None;  // not None: `triangles` is incomplete
};

// Ear clipping in the polygon's plane, for convex and concave outlines alike
// (NFF's "p", OBJ and PLY faces of more than three vertices). Collinear and
// repeated vertices are dropped without a triangle, so a triangulation never
// contains a zero-area triangle made up by the clipping.
PolygonTriangles triangulatePolygon(std::span<const glm::vec3> outline);

// A quad (an OBJ or PLY face of four vertices) as two triangles, split along
// the diagonal from its concave corner if it has one, else from corner 0, as
// assimp did. Quads of meshes are often not flat, and a twisted one can have
// no plane in which to clip ears (its outline folds onto itself there), so it
// is always two triangles, even of no area.
std::array<std::array<uint32_t, 3>, 2> splitQuad(std::span<const glm::vec3, 4> quad);

}  // namespace lancer
