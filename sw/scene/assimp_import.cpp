#include "scene/assimp_import.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <new>

#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/surface.h"

namespace lancer {

namespace {

// Caps the address space while assimp parses, so a file that declares absurd
// counts (assimp's invalid/OutOfMemory.off claims trillions of vertices) fails
// with bad_alloc instead of being killed by the kernel. Restored on scope exit.
class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(uint64_t fileBytes) {
    if (getrlimit(RLIMIT_AS, &saved_) != 0) return;
    long pages = 0, pageSize = sysconf(_SC_PAGESIZE);
    if (std::ifstream statm("/proc/self/statm"); !(statm >> pages)) return;
    // Generous: assimp's in-memory scene is a few hundred bytes per input byte at worst.
    const uint64_t budget = std::max<uint64_t>(uint64_t(4) << 30, fileBytes * 256);
    rlimit capped = saved_;
    capped.rlim_cur = std::min<uint64_t>(saved_.rlim_cur, uint64_t(pages) * uint64_t(pageSize) + budget);
    active_ = setrlimit(RLIMIT_AS, &capped) == 0;
  }
  ~AddressSpaceCap() {
    if (active_) setrlimit(RLIMIT_AS, &saved_);
  }

 private:
  rlimit saved_{};
  bool active_ = false;
};

}  // namespace

const aiScene* importWithAssimp(Assimp::Importer& importer, const std::string& path, unsigned flags) {
  std::error_code sizeError;
  const uint64_t fileBytes = std::filesystem::file_size(path, sizeError);
  if (sizeError) throw InputError(fmt::format("{}: cannot open file", path));
  const aiScene* ai = nullptr;
  try {
    AddressSpaceCap cap(fileBytes);
    ai = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: cannot read scene: it declares more data than fits in memory", path));
  } catch (const std::exception& e) {
    // assimp catches its own errors; a library it calls may not.
    throw InputError(fmt::format("{}: cannot read scene: {}", path, e.what()));
  }
  if (!ai || !ai->mRootNode) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(fmt::format("{}: cannot read scene: {}", path, reason.empty() ? "assimp read no scene" : reason));
  }
  return ai;
}

glm::vec3 toVec(const aiVector3D& v) { return {v.x, v.y, v.z}; }

void appendPlacedMesh(Scene& scene, const aiMesh& mesh, const glm::mat4& world, uint32_t material,
                      bool withNormals, const std::string& path, const std::string& where) {
  const bool identity = world == glm::mat4(1.0f);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
  const auto place = [&](const aiVector3D& v) {
    return identity ? toVec(v) : glm::vec3(world * glm::vec4(toVec(v), 1.0f));
  };
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // a point or line among the triangles
    if (std::any_of(face.mIndices, face.mIndices + 3, [&](unsigned i) { return i >= mesh.mNumVertices; })) {
      throw InputError(fmt::format("{}: {} face {} names a vertex beyond the mesh's {}", path, where, f,
                                   mesh.mNumVertices));
    }
    const Triangle tri{place(mesh.mVertices[face.mIndices[0]]), place(mesh.mVertices[face.mIndices[1]]),
                       place(mesh.mVertices[face.mIndices[2]])};
    if (!allFinite(tri.v0) || !allFinite(tri.v1) || !allFinite(tri.v2)) {
      throw InputError(fmt::format("{}: {} face {} has a non-finite vertex", path, where, f));
    }
    scene.triangles.push_back(tri);
    scene.materialOf.push_back(material);
    if (!withNormals) continue;
    std::array<glm::vec3, 3> normals{};
    std::array<const glm::vec3*, 3> file{};
    for (int c = 0; c < 3 && mesh.mNormals; ++c) {
      normals[c] = toVec(mesh.mNormals[face.mIndices[c]]);
      if (!identity) normals[c] = normalMatrix * normals[c];
      file[c] = &normals[c];
    }
    scene.normals.push_back(shadingNormals(tri, file));
  }
}

}  // namespace lancer
