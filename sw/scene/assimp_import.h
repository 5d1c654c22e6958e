#pragma once

#include <string>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

namespace lancer {

// assimp's reading of a scene file with the given post-processing, owned by
// `importer`. The address space is capped while assimp parses, so a file that
// declares absurd counts fails with an error instead of being killed by the
// kernel. Throws InputError "<path>: cannot read scene: <assimp's reason>".
const aiScene* importWithAssimp(Assimp::Importer& importer, const std::string& path, unsigned flags);

}  // namespace lancer
