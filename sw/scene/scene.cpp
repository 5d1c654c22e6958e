#include "scene/scene.h"

#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <new>
#include <tuple>
#include <map>
#include <utility>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include <assimp/Importer.hpp>
#include <assimp/ObjMaterial.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/gltf.h"
#include "scene/nff.h"
#include "scene/obj.h"
#include "scene/ply.h"
#include "scene/spd.h"
#include "scene/stl.h"
#include "scene/surface.h"

namespace lancer {

void Scene::computeBounds() {
  bounds = Aabb{};
  for (const Triangle& t : triangles) bounds.extend(t.bounds());
}

std::vector<uint32_t> Scene::emissiveTriangles() const {
  std::vector<uint32_t> out;
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    if (glm::any(glm::greaterThan(materials[materialOf[t]].emission, glm::vec3(0.0f)))) out.push_back(t);
  }
  return out;
}

namespace {

glm::vec3 toVec(const aiVector3D& v) { return {v.x, v.y, v.z}; }

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

// The Whitted terms of a material in assimp's MTL keys, which it fills the same
// way for the other formats it reads (as readMtl in scene/obj.cpp does for MTL).
void readWhittedTerms(const aiMaterial& mat, const std::string& path, Material& material) {
  int illum = 2;
  mat.Get(AI_MATKEY_OBJ_ILLUM, illum);
  aiColor3D specular(0.0f, 0.0f, 0.0f);
  mat.Get(AI_MATKEY_COLOR_SPECULAR, specular);
  if (illum >= 3) material.ks = std::max({specular.r, specular.g, specular.b});
  float value = 0.0f;
  if (mat.Get(AI_MATKEY_SHININESS, value) == AI_SUCCESS) material.shine = std::max(value, 0.0f);
  if (mat.Get(AI_MATKEY_OPACITY, value) == AI_SUCCESS) material.transmittance = std::clamp(1.0f - value, 0.0f, 1.0f);
  if (mat.Get(AI_MATKEY_REFRACTI, value) == AI_SUCCESS) material.ior = value;
  if (material.ior <= 0.0f || !std::isfinite(material.ior)) {
    if (material.transmittance > 0.0f) {
      throw InputError(fmt::format("{}: material '{}': index of refraction {} must be > 0 on a transmitting material",
                                   path, material.name, material.ior));
    }
    material.ior = 1.0f;
  }
}

// glTF's metallic-roughness material in Whitted terms (docs/scenes.md, "glTF
// 2.0"). Whitted tracing has only perfect mirrors and clear refraction, so
// roughness takes away the mirror: with smoothness s = 1 - roughness and the
// dielectric's normal-incidence Fresnel reflectance F0 = ((ior-1)/(ior+1))^2
// (0.04 at glTF's default ior 1.5),
//   ks = s * (metallic + (1 - metallic) * F0)      metals mirror their all, dielectrics F0
//   T  = (1 - metallic) * transmission * (1 - F0)  what the surface does not reflect (metals never transmit)
//   kd = max(0, 1 - ks - T)                        the rest is diffuse, in the base colour
//   shine = 2 / alpha^2 - 2 with alpha = roughness^2 (the Phong exponent of the
//           microfacet lobe of that width, Walter et al. 2007), at most kMaxShine
// Factors outside [0, 1] are errors, as are a negative or non-finite emission
// (factor times strength) and an ior <= 0 on a transmitting
// material (on an opaque one it is unused and reads as 1.5). glTF's alpha is
// coverage, not transmission, and is not read.
// The core factors come through assimp, the extensions' from our JSON reader.
void readGltfTerms(const aiMaterial& mat, const GltfExtras::MaterialExtras& extras, const std::string& path,
                   Material& material) {
  constexpr float kMaxShine = 10000.0f;
  float metallic = 1.0f, roughness = 1.0f;  // glTF's defaults
  mat.Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  mat.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  const float transmission = extras.transmission;
  material.ior = extras.ior;
  for (const auto& [what, value] : {std::pair{"metallic factor", metallic}, std::pair{"roughness factor", roughness},
                                    std::pair{"transmission factor", transmission}}) {
    if (!(value >= 0.0f && value <= 1.0f)) {
      throw InputError(fmt::format("{}: material '{}': {} {} must be in [0, 1]", path, material.name, what, value));
    }
  }
  if (!allFinite(material.emission) || glm::any(glm::lessThan(material.emission, glm::vec3(0.0f)))) {
    throw InputError(fmt::format("{}: material '{}': emission ({}, {}, {}) must be finite and >= 0", path, material.name,
                                 material.emission.r, material.emission.g, material.emission.b));
  }
  if (!(material.ior > 0.0f && std::isfinite(material.ior))) {
    if (transmission > 0.0f) {
      throw InputError(fmt::format("{}: material '{}': index of refraction {} must be > 0 on a transmitting material",
                                   path, material.name, material.ior));
    }
    material.ior = 1.5f;
  }
  const float f0 = (material.ior - 1.0f) * (material.ior - 1.0f) / ((material.ior + 1.0f) * (material.ior + 1.0f));
  material.ks = (1.0f - roughness) * (metallic + (1.0f - metallic) * f0);
  material.transmittance = (1.0f - metallic) * transmission * (1.0f - f0);
  material.kd = std::max(0.0f, 1.0f - material.ks - material.transmittance);
  const float alpha = roughness * roughness;
  material.shine = alpha > 0.0f ? std::min(kMaxShine, 2.0f / (alpha * alpha) - 2.0f) : kMaxShine;
}

Scene loadWithAssimp(const std::string& path, bool isGltf) {
  if (!std::ifstream(path)) throw InputError(fmt::format("{}: cannot open file", path));
  // glTF: what assimp drops or mangles (lights' names, the camera, emissive
  // strength) comes from the JSON, read first so its errors name the light,
  // camera or material rather than assimp's parse.
  std::optional<GltfExtras> gltf;
  if (isGltf) gltf = readGltfExtras(path);
  std::error_code sizeError;
  const uint64_t fileBytes = std::filesystem::file_size(path, sizeError);
  Assimp::Importer importer;
  // Keep vertices exactly as written (no joining, no normal generation): shared
  // vertices are already shared by index in the formats we read, and any
  // re-computation would risk moving them.
  const unsigned flags = aiProcess_Triangulate | aiProcess_PreTransformVertices |
                         aiProcess_SortByPType;
  const aiScene* ai = nullptr;
  try {
    AddressSpaceCap cap(sizeError ? 0 : fileBytes);
    ai = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: cannot read scene: it declares more data than fits in memory", path));
  }
  if (!ai || !ai->mRootNode) {
    throw InputError(fmt::format("{}: cannot read scene: {}", path, importer.GetErrorString()));
  }
  Scene scene;
  scene.name = path;
  for (unsigned m = 0; m < ai->mNumMaterials; ++m) {
    const aiMaterial* mat = ai->mMaterials[m];
    Material material;
    aiString name;
    if (mat->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) material.name = name.C_Str();
    aiColor3D color;
    if (mat->Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) material.diffuse = {color.r, color.g, color.b};
    if (mat->Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS) material.emission = {color.r, color.g, color.b};
    if (gltf) {
      // assimp lists the file's materials in order, then its own default.
      const GltfExtras::MaterialExtras extras = m < gltf->materials.size() ? gltf->materials[m] : GltfExtras::MaterialExtras{};
      if (m < gltf->materials.size()) material.name = extras.name;
      material.emission *= extras.emissiveStrength;
      readGltfTerms(*mat, extras, path, material);
    } else {
      readWhittedTerms(*mat, path, material);
    }
    checkMaterialTerms(material, path);
    scene.materials.push_back(material);
  }
  if (scene.materials.empty()) scene.materials.push_back(Material{"default"});
  // Vertex normals (OBJ vn, glTF NORMAL, ...) become shading normals when any
  // triangle mesh has them; a mesh without them, and a zero or non-finite
  // normal, take the triangle's geometric normal.
  bool withNormals = false;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    withNormals |= (ai->mMeshes[m]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && ai->mMeshes[m]->mNormals;
  }
  // Triangle order: meshes in aiScene order, faces in order within a mesh.
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* mesh = ai->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const uint32_t material = mesh->mMaterialIndex < scene.materials.size() ? mesh->mMaterialIndex : 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by SortByPType
      Triangle tri{toVec(mesh->mVertices[face.mIndices[0]]), toVec(mesh->mVertices[face.mIndices[1]]),
                   toVec(mesh->mVertices[face.mIndices[2]])};
      for (const glm::vec3& v : {tri.v0, tri.v1, tri.v2}) {
        if (!allFinite(v)) {
          throw InputError(fmt::format("{}: mesh {} face {} has a non-finite vertex", path, m, f));
        }
      }
      scene.triangles.push_back(tri);
      scene.materialOf.push_back(material);
      if (withNormals) {
        std::array<glm::vec3, 3> normals{};
        std::array<const glm::vec3*, 3> file{};
        for (int k = 0; k < 3 && mesh->mNormals; ++k) {
          normals[k] = toVec(mesh->mNormals[face.mIndices[k]]);
          file[k] = &normals[k];
        }
        scene.normals.push_back(shadingNormals(tri, file));
      }
    }
  }
  if (scene.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", path));
  if (gltf) {
    scene.lights = std::move(gltf->lights);
    scene.view = gltf->view;
  }
  scene.computeBounds();
  return scene;
}

}  // namespace

Scene loadScene(const std::string& nameOrPath) {
  if (nameOrPath == kDefaultSceneName || nameOrPath == "cornell") return makeCornellBox();
  if (nameOrPath == "builtin:cube") return makeCube();
  if (nameOrPath.starts_with("builtin:spd-")) return makeSpdScene(nameOrPath.substr(12));
  if (nameOrPath.starts_with("builtin:")) {
    throw InputError(fmt::format("unknown built-in scene '{}' (available: {}, builtin:cube, builtin:spd-tetra, builtin:spd-gears)", nameOrPath,
                                 kDefaultSceneName));
  }
  // NFF by our own reader: assimp's drops Ks, T and the index of refraction;
  // OBJ, PLY and STL by our own: assimp's do not round numbers correctly
  // (docs/scenes.md).
  std::string extension = std::filesystem::path(nameOrPath).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".nff") return loadNff(nameOrPath);
  if (extension == ".obj") return loadObj(nameOrPath);
  if (extension == ".ply") return loadPly(nameOrPath);
  if (extension == ".stl") return loadStl(nameOrPath);
  // glTF through assimp plus our reader of what assimp drops (lights, camera, extensions).
  return loadWithAssimp(nameOrPath, extension == ".gltf" || extension == ".glb");
}

Scene makeIcosphere(int levels) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  std::vector<std::array<uint32_t, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    // Each edge's midpoint is made once, so both faces sharing it use the same bits.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = midpoints.try_emplace(key, uint32_t(v.size()));
      if (fresh) v.push_back(glm::normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& f : faces) {
      const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.insert(next.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    faces = std::move(next);
  }
  Scene scene;
  scene.name = "icosphere";
  for (const auto& f : faces) scene.triangles.push_back({v[f[0]], v[f[1]], v[f[2]]});
  scene.materials.push_back(Material{});
  scene.materialOf.assign(scene.size(), 0);
  scene.computeBounds();
  return scene;
}

Scene subdivide(const Scene& scene, int times) {
  Scene out = scene;
  for (int i = 0; i < times; ++i) {
    Scene next;
    next.name = out.name;
    next.materials = out.materials;
    next.triangles.reserve(out.triangles.size() * 4);
    for (size_t t = 0; t < out.triangles.size(); ++t) {
      const Triangle& tri = out.triangles[t];
      // 0.5f * (a + b) is symmetric in a and b, so both triangles sharing an edge
      // compute a bit-identical midpoint.
      const glm::vec3 m01 = 0.5f * (tri.v0 + tri.v1);
      const glm::vec3 m12 = 0.5f * (tri.v1 + tri.v2);
      const glm::vec3 m20 = 0.5f * (tri.v2 + tri.v0);
      for (const Triangle& child : {Triangle{tri.v0, m01, m20}, Triangle{m01, tri.v1, m12},
                                    Triangle{m20, m12, tri.v2}, Triangle{m01, m12, m20}}) {
        next.triangles.push_back(child);
        next.materialOf.push_back(out.materialOf[t]);
      }
    }
    out = std::move(next);
  }
  out.computeBounds();
  return out;
}

void writeObj(const Scene& scene, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw InputError(fmt::format("{}: cannot write file", path.string()));
  // Deduplicate vertices so the OBJ keeps the mesh's connectivity.
  std::map<std::tuple<float, float, float>, size_t> index;
  std::vector<glm::vec3> vertices;
  auto vertexId = [&](const glm::vec3& v) {
    auto [it, inserted] = index.try_emplace({v.x, v.y, v.z}, vertices.size() + 1);
    if (inserted) vertices.push_back(v);
    return it->second;
  };
  std::vector<std::array<size_t, 3>> faces;
  for (const Triangle& t : scene.triangles) faces.push_back({vertexId(t.v0), vertexId(t.v1), vertexId(t.v2)});
  out << "# written by lancer from " << scene.name << "\n";
  for (const glm::vec3& v : vertices) out << fmt::format("v {:.9g} {:.9g} {:.9g}\n", v.x, v.y, v.z);
  for (const auto& f : faces) out << fmt::format("f {} {} {}\n", f[0], f[1], f[2]);
  if (!out) throw InputError(fmt::format("{}: write failed", path.string()));
}

}  // namespace lancer
