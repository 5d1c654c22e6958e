#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace lancer {

// Lancer's Wavefront OBJ and MTL reader (docs/scenes.md, "OBJ and MTL").
// Numbers are read correctly rounded (scene/text.h), so a coordinate is the
// float nearest to what the file says and a scene scaled by a power of two
// reads as exactly that multiple.
//
// OBJ: "v" (x y z; a w or vertex colours after them are read as numbers and
// not used), "vn", "vt" (counted, not used), "f" with v, v/vt, v//vn or
// v/vt/vn corners and indices from 1 or negative (counted back from the last
// one defined before the face), "usemtl", "mtllib" (one or more files, relative
// to the OBJ's folder), "#" comments, and lines continued by a trailing
// backslash; "o", "g", "s", "l", "p" and every other statement are ignored.
// A quad is split in two (splitQuad), a larger face triangulated by ear
// clipping (scene/polygon.h). Triangle ids follow the faces in file order.
//
// Throws InputError naming the file and line: a malformed number, a vertex
// beyond float range, an index that is 0 or names no element defined before
// its face, a face of fewer than three vertices or one that crosses itself, a
// NUL byte; in an MTL file, a statement before the first newmtl and terms out
// of range (scene/surface.h); and "scene has no triangles". Goes on with a
// warning in Scene::warnings when an MTL file is missing (the OBJ's own name
// with .mtl is tried instead, as assimp did) or usemtl names a material no MTL
// file defines (it is drawn with the default material).
Scene loadObj(const std::string& path);
// The same from the file's text; `name` names it in messages and the scene,
// and MTL files are looked for in `folder`.
Scene readObj(std::string_view text, const std::string& name, const std::filesystem::path& folder);

// The materials of one MTL file in the order of their newmtl, as Whitted
// terms (docs/scenes.md, "Whitted terms of MTL materials"). Throws as above,
// naming `name` and the line.
std::vector<Material> readMtl(std::string_view text, const std::string& name);

}  // namespace lancer
