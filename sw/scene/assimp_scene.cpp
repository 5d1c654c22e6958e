#include "scene/assimp_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string_view>
#include <utility>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/assimp_import.h"
#include "scene/surface.h"
#include "scene/text.h"

namespace lancer {

namespace {

// ---- Which numbers a format stores ------------------------------------------------------

// Formats that store their geometry's numbers as binary floats (or integers),
// which assimp copies: exact.
constexpr std::array<std::string_view, 25> kBinaryFormats = {
    ".3d",  ".3ds", ".assbin", ".b3d",  ".blend", ".bsp", ".hmp", ".iqm", ".lwo", ".lxo", ".md2", ".md3",
    ".mdc", ".mdl", ".mesh",   ".mot", ".ms3d", ".ndo",   ".pk3", ".pmx", ".prj", ".q3o", ".q3s", ".sib", ".ter"};
// The rest of assimp 5.2's list whose geometry is decimal text (XML, STEP,
// JSON, plain text), parsed by assimp: maybe a float off.
constexpr std::array<std::string_view, 35> kTextFormats = {
    ".3mf",  ".ac",   ".ac3d", ".acc",     ".amf",      ".ase",       ".ask",    ".bvh",  ".csm",
    ".dae",  ".enff", ".ifc",  ".ifczip",  ".irr",      ".irrmesh",   ".lws",    ".md5anim", ".md5camera",
    ".md5mesh", ".off", ".ogex", ".raw",   ".smd",      ".step",      ".stp",    ".vta",  ".x3d",
    ".x3db", ".xgl",  ".xml",  ".zae",     ".zgl",      ".gltf",      ".glb",    ".uc"};
// Formats with a binary and a text form, told apart by their first bytes.
constexpr std::array<std::string_view, 5> kEitherFormats = {".fbx", ".x", ".cob", ".scn", ".dxf"};

std::string firstBytes(const std::string& path, size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(count, '\0');
  in.read(bytes.data(), std::streamsize(count));
  bytes.resize(size_t(in.gcount()));
  return bytes;
}

bool listed(std::string_view extension, auto const& list) {
  return std::find(list.begin(), list.end(), extension) != list.end();
}

// ---- Materials and lights -----------------------------------------------------------------


// assimp's row-major matrix as glm's column-major one.
glm::mat4 toMat(const aiMatrix4x4& m) {
  glm::mat4 out;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) out[col][row] = m[unsigned(row)][unsigned(col)];
  }
  return out;
}

// An aiMaterial's classic terms in Whitted terms, as MTL's are read
// (docs/scenes.md, "Formats through assimp"): the diffuse colour (or the PBR
// base colour), the emission times its intensity, an opacity d < 1 transmits
// 1 - d with the material's index of refraction, the reflectivity is the
// mirror weight, the shininess the highlight's exponent; kd is what is left.
Material readMaterial(const aiMaterial& mat, unsigned index, const std::string& path) {
  Material material;
  aiString name;
  material.name = mat.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0 ? name.C_Str()
                                                                                 : fmt::format("material {}", index);
  aiColor3D color;
  if (mat.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) {
    material.diffuse = {color.r, color.g, color.b};
  } else if (aiColor4D base; mat.Get(AI_MATKEY_BASE_COLOR, base) == AI_SUCCESS) {
    material.diffuse = {base.r, base.g, base.b};
  }
  if (mat.Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS) material.emission = {color.r, color.g, color.b};
  if (float intensity = 1.0f; mat.Get(AI_MATKEY_EMISSIVE_INTENSITY, intensity) == AI_SUCCESS) {
    material.emission *= intensity;
  }
  float opacity = 1.0f, ior = 1.0f, reflectivity = 0.0f, shininess = 0.0f;
  mat.Get(AI_MATKEY_OPACITY, opacity);
  mat.Get(AI_MATKEY_REFRACTI, ior);
  mat.Get(AI_MATKEY_REFLECTIVITY, reflectivity);
  mat.Get(AI_MATKEY_SHININESS, shininess);
  // Exporters write an opacity of 0 for "not set" as often as for "clear";
  // only one strictly between 0 and 1 is read as a transmittance.
  material.transmittance = opacity > 0.0f && opacity < 1.0f ? 1.0f - opacity : 0.0f;
  material.ks = std::clamp(std::isfinite(reflectivity) ? reflectivity : 0.0f, 0.0f, 1.0f);
  material.shine = std::isfinite(shininess) ? std::max(0.0f, shininess) : 0.0f;
  if (!(ior > 0.0f && std::isfinite(ior))) {
    if (material.transmittance > 0.0f) {
      throw InputError(fmt::format("{}: material '{}': index of refraction {} must be > 0 on a transmitting material",
                                   path, material.name, ior));
    }
    ior = 1.0f;
  }
  material.ior = ior;
  material.kd = std::max(0.0f, 1.0f - material.ks - material.transmittance);
  if (!allFinite(material.emission) || glm::any(glm::lessThan(material.emission, glm::vec3(0.0f)))) {
    throw InputError(fmt::format("{}: material '{}': emission ({}, {}, {}) must be finite and >= 0", path,
                                 material.name, material.emission.r, material.emission.g, material.emission.b));
  }
  checkMaterialTerms(material, path);
  return material;
}

// ---- The node tree --------------------------------------------------------------------------

struct Instance {
  const aiNode* node;
  glm::mat4 world;
};

// Every node with its world transform (its parents' times its own, in float),
// depth-first, children in order. assimp 5.2's RAW importer counts children
// it never makes: a missing child is skipped.
void walk(const aiNode* node, const glm::mat4& parent, std::vector<Instance>& out) {
  const glm::mat4 world = parent * toMat(node->mTransformation);
  out.push_back({node, world});
  for (unsigned c = 0; node->mChildren && c < node->mNumChildren; ++c) {
    if (node->mChildren[c]) walk(node->mChildren[c], world, out);
  }
}

std::string nodeLabel(const aiNode* node) { return fmt::format("node '{}'", node->mName.C_Str()); }

}  // namespace

std::optional<SceneNumbers> assimpSceneNumbers(const std::string& path) {
  std::string extension = lowercase(std::filesystem::path(path).extension().string());
  if (lowercase(path).ends_with(".mesh.xml")) extension = ".xml";
  // A file without an extension: assimp tells its format by its content, and
  // Lancer cannot tell its numbers, so they are taken to be text.
  if (extension.empty()) return SceneNumbers::AssimpText;
  if (listed(extension, kBinaryFormats)) return SceneNumbers::Exact;
  if (listed(extension, kTextFormats)) return SceneNumbers::AssimpText;
  if (!listed(extension, kEitherFormats)) return std::nullopt;
  const std::string head = firstBytes(path, 32);
  bool binary = false;
  if (extension == ".fbx") {
    binary = head.starts_with("Kaydara FBX Binary");
  } else if (extension == ".x") {
    // "xof 0303txt 0032": the format at bytes 8 to 11 (txt, bin, tzip, bzip).
    binary = head.size() >= 12 && (head.substr(8, 4) == "bin " || head.substr(8, 4) == "bzip");
  } else if (extension == ".cob" || extension == ".scn") {
    // "Caligari V00.01ALH": A for ASCII, B for binary.
    binary = head.starts_with("Caligari ") && head.size() > 15 && head[15] == 'B';
  } else if (extension == ".dxf") {
    binary = head.starts_with("AutoCAD Binary DXF");
  }
  return binary ? SceneNumbers::Exact : SceneNumbers::AssimpText;
}

Scene loadAssimpScene(const std::string& path, SceneNumbers numbers) {
  Assimp::Importer importer;
  // Polygons triangulated; nothing else changed: the meshes stay in their
  // own frames, placed below (no joining, no generated normals).
  const aiScene* ai = importWithAssimp(importer, path, aiProcess_Triangulate);
  Scene scene;
  scene.name = path;
  scene.numbers = numbers;
  if (numbers == SceneNumbers::AssimpText) {
    scene.warnings.push_back(fmt::format(
        "{}: a text format read by assimp, whose decimal numbers may be a float off (scene_numbers: assimp_text)",
        path));
  }
  for (unsigned m = 0; m < ai->mNumMaterials; ++m) {
    scene.materials.push_back(ai->mMaterials[m] ? readMaterial(*ai->mMaterials[m], m, path) : Material{"default"});
  }
  if (scene.materials.empty()) scene.materials.push_back(Material{"default"});

  std::vector<Instance> instances;
  walk(ai->mRootNode, glm::mat4(1.0f), instances);
  const auto triangles = [](const aiMesh* mesh) { return (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0; };
  bool withNormals = false;
  for (const Instance& instance : instances) {
    for (unsigned k = 0; k < instance.node->mNumMeshes; ++k) {
      if (instance.node->mMeshes[k] >= ai->mNumMeshes || !ai->mMeshes[instance.node->mMeshes[k]]) {
        throw InputError(fmt::format("{}: cannot read scene: assimp's {} names mesh {} of its {}", path,
                                     nodeLabel(instance.node), instance.node->mMeshes[k], ai->mNumMeshes));
      }
      const aiMesh* mesh = ai->mMeshes[instance.node->mMeshes[k]];
      withNormals |= triangles(mesh) && mesh->mNormals;
    }
  }
  // Triangle order: nodes depth-first, a node's meshes in order, faces in order.
  for (const Instance& instance : instances) {
    for (unsigned k = 0; k < instance.node->mNumMeshes; ++k) {
      const aiMesh* mesh = ai->mMeshes[instance.node->mMeshes[k]];
      if (!triangles(mesh)) continue;
      const uint32_t material = mesh->mMaterialIndex < scene.materials.size() ? mesh->mMaterialIndex : 0;
      appendPlacedMesh(scene, *mesh, instance.world, material, withNormals, path,
                       fmt::format("{}: mesh '{}'", nodeLabel(instance.node), mesh->mName.C_Str()));
    }
  }
  if (scene.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", path));
  // assimp reads some broken files as triangles that are all points (a UTF-16
  // ASE, an OFF of collinear vertices): nothing to see or frame.
  if (std::none_of(scene.triangles.begin(), scene.triangles.end(), [](const Triangle& t) {
        return glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)) > 0.0f;
      })) {
    throw InputError(fmt::format("{}: scene has no area: assimp read {} triangles, none of them with an area", path,
                                 scene.triangles.size()));
  }

  // Lights at their nodes (assimp names a light as its node). Ambient, area
  // and undefined lights are not traced: a warning each.
  for (unsigned l = 0; l < ai->mNumLights; ++l) {
    const aiLight& source = *ai->mLights[l];
    Light light;
    light.name = source.mName.length > 0 ? source.mName.C_Str() : fmt::format("light {}", l);
    if (source.mType == aiLightSource_POINT) {
      light.kind = Light::Kind::Point;
    } else if (source.mType == aiLightSource_SPOT) {
      light.kind = Light::Kind::Spot;
    } else if (source.mType == aiLightSource_DIRECTIONAL) {
      light.kind = Light::Kind::Directional;
    } else {
      scene.warnings.push_back(fmt::format("{}: light '{}': an ambient, area or undefined light is not traced", path,
                                           light.name));
      continue;
    }
    glm::mat4 world(1.0f);
    const aiNode* node = ai->mRootNode->FindNode(source.mName);
    for (const Instance& instance : instances) {
      if (instance.node == node) world = instance.world;
    }
    light.position = glm::vec3(world * glm::vec4(toVec(source.mPosition), 1.0f));
    light.direction = glm::normalize(glm::mat3(world) * toVec(source.mDirection));
    light.color = {source.mColorDiffuse.r, source.mColorDiffuse.g, source.mColorDiffuse.b};
    if (!allFinite(light.color) || glm::any(glm::lessThan(light.color, glm::vec3(0.0f)))) {
      throw InputError(fmt::format("{}: light '{}': colour ({}, {}, {}) must be finite and >= 0", path, light.name,
                                   light.color.r, light.color.g, light.color.b));
    }
    const bool placed = light.kind != Light::Kind::Directional, aimed = light.kind != Light::Kind::Point;
    if ((placed && !allFinite(light.position)) || (aimed && !allFinite(light.direction))) {
      throw InputError(fmt::format("{}: light '{}': its world position or direction is not finite", path, light.name));
    }
    if (light.kind == Light::Kind::Spot) {
      // assimp's cone angles are whole cone angles: half of each is the
      // angle from the axis (at most a half-space).
      const float outer = std::clamp(source.mAngleOuterCone / 2.0f, 0.0f, std::numbers::pi_v<float> / 2.0f);
      const float inner = std::clamp(source.mAngleInnerCone / 2.0f, 0.0f, outer);
      light.outerConeCos = std::cos(outer);
      light.innerConeCos = std::cos(inner);
    }
    scene.lights.push_back(light);
  }
  scene.computeBounds();
  return scene;
}

}  // namespace lancer
