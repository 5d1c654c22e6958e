#pragma once

#include <cstdint>
#include <string>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace lancer {

// assimp's reading of a scene file with the given post-processing, owned by
// `importer`. The address space is capped while assimp parses, so a file that
// declares absurd counts fails with an error instead of being killed by the
// kernel. Throws InputError "<path>: cannot read scene: <assimp's reason>".
const aiScene* importWithAssimp(Assimp::Importer& importer, const std::string& path, unsigned flags);

glm::vec3 toVec(const aiVector3D& v);

// Appends `mesh`'s triangles, placed at `world`, to `scene` with `material`,
// and their shading normals when `withNormals` (the mesh's vertex normals, or
// the geometric normal). The identity keeps the file's floats as they are; any
// other transform is applied in float, so a scene scaled by a power of two is
// placed at exactly that multiple. Faces that are not triangles (points and
// lines among them) are left out. `where` names the mesh in errors ("node 'x':
// mesh 'y'"): InputError "<path>: <where> face F ..." for a vertex index beyond
// the mesh or a vertex that is not finite once placed.
void appendPlacedMesh(Scene& scene, const aiMesh& mesh, const glm::mat4& world, uint32_t material,
                      bool withNormals, const std::string& path, const std::string& where);

}  // namespace lancer
