#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace lancer {

// Lancer's PLY reader (docs/scenes.md, "PLY"): ascii, binary_little_endian and
// binary_big_endian files; the vertex element's x, y, z, of any scalar type,
// and its nx, ny, nz as shading normals when it has all three; the face
// element's vertex_indices (or vertex_index) list, a quad split in two
// (splitQuad) and a larger polygon triangulated by ear clipping
// (scene/polygon.h). Every other element and property, and any header line PLY
// does not define, is skipped. ASCII numbers are read correctly rounded
// (scene/text.h), binary ones exactly (a double or a large integer is rounded
// once to float). Triangle ids follow the faces in file order; the scene has
// one material, Lancer's default.
//
// Throws InputError naming the file and the header line, or where in the data
// (the line of an ASCII file, the byte of a binary one): not a PLY file, an
// unknown format or type, a vertex element without x, y or z, a face list of
// non-integers, counts that the file's size cannot hold, data that ends early,
// a malformed number, a vertex beyond float range, a face of fewer than three
// vertices or that crosses itself, a vertex index out of range; and "scene has
// no triangles".
Scene loadPly(const std::string& path);
// The same from the file's bytes; `name` names it in messages and the scene.
Scene readPly(std::string_view bytes, const std::string& name);

}  // namespace lancer
