#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace lancer {

// Lancer's STL reader (docs/scenes.md, "STL"). A binary STL (an 80-byte
// header, a triangle count, 50 bytes a triangle), recognised by its size, is
// read exactly; an ASCII STL ("solid", then "facet normal nx ny nz", "outer
// loop", three "vertex x y z", "endloop", "endfacet" for each triangle, then
// "endsolid"; several solids one after the other) correctly rounded
// (scene/text.h). Keywords may be in any case. The facet normal is the
// triangle's shading normal at its three corners (where it is zero or not
// finite, the geometric normal), as assimp gave it. Triangle ids follow the
// facets in file order; the scene has one material, Lancer's default.
//
// Throws InputError naming the file and line (ASCII) or triangle (binary):
// neither a binary STL's size nor an ASCII STL's "solid" at the start, a
// keyword out of place, a facet without three vertices, a malformed number, a
// vertex beyond float range, a file that ends inside a facet, and "scene has
// no triangles".
Scene loadStl(const std::string& path);
// The same from the file's bytes; `name` names it in messages and the scene.
Scene readStl(std::string_view bytes, const std::string& name);

}  // namespace lancer
