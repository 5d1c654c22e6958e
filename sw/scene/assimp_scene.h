#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace lancer {

// The formats assimp 5.2 imports that Lancer has no reader of its own for
// (docs/scenes.md, "Formats through assimp"). Binary formats store floats,
// which assimp hands over as they are: their scenes' numbers are
// SceneNumbers::Exact. Text formats are parsed by assimp, whose decimal
// reading can be a float off: SceneNumbers::AssimpText. A format with both
// forms (FBX, .x, COB, DXF) is told by its first bytes. A file without an
// extension is left to assimp's detection, its numbers taken to be text.
// nullopt: not a format assimp imports.
std::optional<SceneNumbers> assimpSceneNumbers(const std::string& path);

// Reads a scene through assimp: every node's meshes placed at the node's world
// transform (composed in float; an identity keeps the file's floats), polygons
// triangulated, points and lines dropped; vertex normals as shading normals;
// each material's colour, emission, opacity, index of refraction,
// reflectivity and shininess as Whitted terms; point, spot and directional
// lights at their nodes. `numbers` is what assimpSceneNumbers said; a text
// format adds a warning saying its numbers may be a float off. Throws
// InputError naming the file: assimp's own reason when it reads nothing, a
// non-finite vertex, a material or light term out of range, no triangles.
Scene loadAssimpScene(const std::string& path, SceneNumbers numbers);

}  // namespace lancer
