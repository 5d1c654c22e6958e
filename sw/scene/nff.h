#pragma once

#include <istream>
#include <string>

#include "scene/scene.h"

namespace lancer {

// How NFF's curved primitives become triangles. A sphere is a cube projected
// onto it, each face a `sphereDivisions` x `sphereDivisions` grid (as the
// SPD's own tessellator does: no cusps at poles); a cone or cylinder
// `coneSlices` quads around its axis, open at both ends. The
// vertices lie on the exact surface and are shared bit for bit between
// neighbouring cells, so the tessellations are watertight; their shading
// normals are the exact surface normals. docs/scenes.md, "NFF".
//
// With `quadrics` = Native (issue #40) the spheres and cones are not
// tessellated: each becomes a Scene::quadrics entry, as read (negative radii
// kept), with its material, after every triangle in the id space (scene.h);
// the same refusals apply (the CLI's --quadrics).
struct NffOptions {
  int sphereDivisions = 8;  // 6 * 2 * 8^2 = 768 triangles a sphere
  int coneSlices = 32;
  QuadricForm quadrics = QuadricForm::Tessellate;
};

// Reads Eric Haines' Neutral File Format (the SPD's NFF.TXT): "v" (from, at,
// up, angle, hither, resolution), "b", "l" (with an optional colour), "f"
// (colour, Kd, Ks, Shine, T, index of refraction), "p" (polygons, convex or
// not, triangulated by ear clipping in their plane, winding kept), "pp" (with
// vertex normals), "s", "c", and "#" comments. Primitives take the last "f".
// Throws InputError naming the file and line for a malformed or truncated
// entity, an unknown keyword, an index of refraction <= 0, a negative T, a
// degenerate sphere or cone, or a polygon that cannot be triangulated; and a
// file with no primitive.
Scene loadNff(const std::string& path, const NffOptions& options = {});
// The same from a stream; `name` is used in messages and as the scene's name.
Scene readNff(std::istream& in, const std::string& name, const NffOptions& options = {});

}  // namespace lancer
