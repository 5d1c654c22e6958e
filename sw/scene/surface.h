#pragma once

#include <array>
#include <string>

#include "scene/scene.h"

namespace lancer {

// What every mesh reader (OBJ, PLY, glTF) does with a triangle's vertex
// normals and a material's terms, so the formats agree.

// A triangle's unit shading normals: each corner's normal from the file,
// normalised, or the triangle's geometric normal (zero for a degenerate
// triangle) where the corner has none (nullptr) or the file's is zero or not
// finite.
ShadingNormals shadingNormals(const Triangle& tri, const std::array<const glm::vec3*, 3>& fileNormals);

// Every term of a loaded material finite, the weights >= 0: a NaN, an infinity
// (1e39 reads as one) or a negative Ks in a file would reach the shader as NaN
// or negative light (found by tests/fuzz/fuzz_mtl). Throws InputError
// "<where>: material '<name>': ...".
void checkMaterialTerms(const Material& m, const std::string& where);

}  // namespace lancer
