#pragma once

#include <filesystem>

#include "scene/scene.h"

namespace lancer {

// Writes what Lancer read, by the file's extension (docs/scenes.md, "lancer
// convert"), so that loadScene reads back the same triangles, bit for bit, in
// the same order (the same triangle ids):
//   .obj  vertices at 9 significant digits (every float round-trips through
//         Lancer's correctly rounded reader), shared by their bits, faces in
//         order, and the materials in an MTL file beside it (<name>.mtl);
//   .ply  binary little-endian floats, faces in order; PLY has no materials;
//   .glb  glTF 2.0: one node with no transform (the floats stay as written),
//         one primitive per run of triangles of one material, the materials'
//         colour, emission and Whitted terms as metallic-roughness factors,
//         and the point, spot and directional lights (KHR_lights_punctual).
// Shading normals and the view are not written. Throws InputError naming the
// file when it cannot be written or its extension is none of these.
void writeScene(const Scene& scene, const std::filesystem::path& path);

// What writeScene writes, for messages and help.
inline constexpr const char* kWrittenFormats = "OBJ (.obj, with its .mtl), PLY (.ply) or glTF 2.0 binary (.glb)";

}  // namespace lancer
