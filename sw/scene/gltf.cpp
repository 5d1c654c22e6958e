#include "scene/gltf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>


#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scene/assimp_import.h"
#include "scene/surface.h"
#include "scene/text.h"

namespace lancer {

namespace {

using Json = nlohmann::json;

// ---- The container -------------------------------------------------------------------

// A .glb starts with a 12-byte header (magic "glTF", version 2, total length),
// then chunks of (length, type, data); the first chunk is the JSON.
constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF", little-endian
constexpr uint32_t kGlbChunkJson = 0x4E4F534A;  // "JSON"

// A JSON number as a float; beyond float's range it is infinite (caught where
// it matters), rather than the undefined behaviour of a narrowing cast.
float toFloat(const Json& value) {
  const double d = value.get<double>();
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  if (std::abs(d) > double(std::numeric_limits<float>::max())) return d > 0 ? kInfinity : -kInfinity;
  return float(d);
}

// nlohmann reads a number to the double nearest to its text, and a double
// cast to float rounds a second time: a decimal just off the midpoint of two
// floats lands on the midpoint as a double, then on the even float, which can
// be the wrong one. So the DOM is built by nlohmann's own DOM builder with
// every such double replaced by the float the text rounds to
// (scene/text.h), which toFloat then returns exactly. (json_sax_dom_parser is
// in nlohmann's detail namespace; Debian 12 pins 3.11.2.)
class CorrectlyRoundedDom : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  using json_sax_dom_parser::json_sax_dom_parser;
  // Hides the base's: sax_parse calls it on this type, not through a virtual.
  bool number_float(double value, const std::string& text) {
    const std::optional<float> nearest = parseFloat(text);
    if (nearest && std::isfinite(*nearest) && float(value) != *nearest) value = double(*nearest);
    return json_sax_dom_parser::number_float(value, text);
  }
};

uint32_t readU32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | uint8_t(bytes[at + size_t(i)]);
  return value;
}

// The glTF JSON text of a .gltf file, or of a .glb container's JSON chunk.
std::string jsonText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open file", path));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 4 || readU32(bytes, 0) != kGlbMagic) return bytes;
  if (bytes.size() < 20) throw InputError(fmt::format("{}: truncated glTF binary container (header)", path));
  if (const uint32_t version = readU32(bytes, 4); version != 2) {
    throw InputError(fmt::format("{}: glTF binary container version {} (only 2 is read)", path, version));
  }
  const uint64_t total = readU32(bytes, 8), chunk = readU32(bytes, 12);
  if (total > bytes.size() || 20 + chunk > total) {
    throw InputError(fmt::format("{}: truncated glTF binary container: it declares {} bytes, its JSON chunk {}, the file has {}",
                                 path, total, chunk, bytes.size()));
  }
  if (readU32(bytes, 16) != kGlbChunkJson) {
    throw InputError(fmt::format("{}: glTF binary container: the first chunk is not JSON", path));
  }
  return bytes.substr(20, chunk);
}

// ---- The reader -----------------------------------------------------------------------

class Reader {
 public:
  Reader(std::string path, Json doc) : path_(std::move(path)), doc_(std::move(doc)) {}

  GltfExtras read() {
    readMaterials();
    readLightDefinitions();
    readCameraDefinitions();
    readMeshes();
    const Json& nodes = array(doc_, "nodes", kTopLevel);
    visited_.assign(nodes.size(), false);
    const std::vector<size_t> rootList = roots(nodes);
    out_.rootCount = rootList.size();
    for (size_t r = 0; r < rootList.size(); ++r) walk(nodes, rootList[r], glm::mat4(1.0f), {r});
    return std::move(out_);
  }

 private:
  // The file's own fields have no owner to name.
  static inline const std::string kTopLevel;
  [[noreturn]] void fail(const std::string& owner, const std::string& what) const {
    throw InputError(owner.empty() ? fmt::format("{}: {}", path_, what) : fmt::format("{}: {}: {}", path_, owner, what));
  }

  // ---- Typed fields, each error naming what it belongs to ----
  const Json& array(const Json& object, const char* key, const std::string& owner) const {
    static const Json kEmpty = Json::array();
    if (!object.contains(key)) return kEmpty;
    if (!object[key].is_array()) fail(owner, fmt::format("'{}' must be an array", key));
    return object[key];
  }
  const Json* object(const Json& parent, const char* key, const std::string& owner) const {
    if (!parent.contains(key)) return nullptr;
    if (!parent[key].is_object()) fail(owner, fmt::format("'{}' must be an object", key));
    return &parent[key];
  }
  float number(const Json& object, const char* key, float fallback, const std::string& owner) const {
    if (!object.contains(key)) return fallback;
    if (!object[key].is_number()) fail(owner, fmt::format("'{}' must be a number", key));
    return toFloat(object[key]);
  }
  std::vector<float> numbers(const Json& object, const char* key, size_t count, std::vector<float> fallback,
                             const std::string& owner) const {
    if (!object.contains(key)) return fallback;
    const Json& value = object[key];
    if (!value.is_array() || value.size() != count ||
        !std::all_of(value.begin(), value.end(), [](const Json& v) { return v.is_number(); })) {
      fail(owner, fmt::format("'{}' must be an array of {} numbers", key, count));
    }
    std::vector<float> out;
    for (const Json& v : value) out.push_back(toFloat(v));
    return out;
  }
  size_t index(const Json& object, const char* key, size_t limit, const std::string& owner, const char* what) const {
    if (!object[key].is_number_unsigned() || object[key].get<uint64_t>() >= limit) {
      fail(owner, fmt::format("'{}' must name one of the file's {} {}", key, limit, what));
    }
    return object[key].get<size_t>();
  }
  std::string name(const Json& object, const std::string& fallback) const {
    return object.contains("name") && object["name"].is_string() ? object["name"].get<std::string>() : fallback;
  }

  // ---- Materials: name and emissive strength ----
  void readMaterials() {
    const Json& materials = array(doc_, "materials", kTopLevel);
    for (size_t i = 0; i < materials.size(); ++i) {
      GltfExtras::MaterialExtras extras;
      extras.name = name(materials[i], fmt::format("{}", i));
      const std::string owner = fmt::format("material '{}'", extras.name);
      if (const Json* ext = object(materials[i], "extensions", owner)) {
        if (const Json* strength = object(*ext, "KHR_materials_emissive_strength", owner)) {
          extras.emissiveStrength = number(*strength, "emissiveStrength", 1.0f, owner);
          if (!(extras.emissiveStrength >= 0.0f && std::isfinite(extras.emissiveStrength))) {
            fail(owner, fmt::format("emissive strength {} must be a finite number >= 0", extras.emissiveStrength));
          }
        }
        // Ranges are checked with the other factors (readGltfTerms in scene.cpp).
        if (const Json* transmission = object(*ext, "KHR_materials_transmission", owner)) {
          extras.transmission = number(*transmission, "transmissionFactor", 0.0f, owner);
        }
        if (const Json* ior = object(*ext, "KHR_materials_ior", owner)) extras.ior = number(*ior, "ior", 1.5f, owner);
      }
      out_.materials.push_back(extras);
    }
  }

  // ---- KHR_lights_punctual: the definitions, placed later by their nodes ----
  void readLightDefinitions() {
    const Json* ext = object(doc_, "extensions", kTopLevel);
    const Json* punctual = ext ? object(*ext, "KHR_lights_punctual", kTopLevel) : nullptr;
    if (!punctual) return;
    const Json& lights = array(*punctual, "lights", "KHR_lights_punctual");
    for (size_t i = 0; i < lights.size(); ++i) {
      const Json& def = lights[i];
      Light light;
      light.name = name(def, fmt::format("light {}", i));
      const std::string owner = fmt::format("light '{}'", light.name);
      if (!def.is_object()) fail(owner, "must be an object");
      const std::string type = def.contains("type") && def["type"].is_string() ? def["type"].get<std::string>() : "";
      if (type == "point") {
        light.kind = Light::Kind::Point;
      } else if (type == "spot") {
        light.kind = Light::Kind::Spot;
      } else if (type == "directional") {
        light.kind = Light::Kind::Directional;
      } else {
        fail(owner, fmt::format("type '{}' is not point, spot or directional", type));
      }
      const std::vector<float> color = numbers(def, "color", 3, {1.0f, 1.0f, 1.0f}, owner);
      const float intensity = number(def, "intensity", 1.0f, owner);
      if (!(intensity >= 0.0f && std::isfinite(intensity))) {
        fail(owner, fmt::format("intensity {} must be a finite number >= 0", intensity));
      }
      for (const float c : color) {
        if (!(c >= 0.0f && std::isfinite(c))) {
          fail(owner, fmt::format("colour component {} must be a finite number >= 0", c));
        }
      }
      light.color = glm::vec3(color[0], color[1], color[2]) * intensity;
      if (light.kind == Light::Kind::Spot) {
        const Json* spot = object(def, "spot", owner);
        if (!spot) fail(owner, "a spot light needs 'spot' (its cone)");
        const float inner = number(*spot, "innerConeAngle", 0.0f, owner);
        const float outer = number(*spot, "outerConeAngle", std::numbers::pi_v<float> / 4.0f, owner);
        if (!(inner >= 0.0f && inner < outer && outer <= std::numbers::pi_v<float> / 2.0f)) {
          fail(owner, fmt::format("cone angles inner {} and outer {} must satisfy 0 <= inner < outer <= pi/2", inner, outer));
        }
        light.innerConeCos = std::cos(inner);
        light.outerConeCos = std::cos(outer);
      }
      lightDefs_.push_back(light);
    }
  }

  // ---- Cameras: perspective ones become views (orthographic ones are skipped) ----
  void readCameraDefinitions() {
    const Json& cameras = array(doc_, "cameras", kTopLevel);
    for (size_t i = 0; i < cameras.size(); ++i) {
      const std::string owner = fmt::format("camera '{}'", name(cameras[i], fmt::format("{}", i)));
      const std::string type =
          cameras[i].contains("type") && cameras[i]["type"].is_string() ? cameras[i]["type"].get<std::string>() : "";
      std::optional<float> yfov;
      if (type == "perspective") {
        const Json* perspective = object(cameras[i], "perspective", owner);
        if (!perspective || !perspective->contains("yfov")) fail(owner, "a perspective camera needs 'yfov'");
        yfov = number(*perspective, "yfov", 0.0f, owner);
        if (!(*yfov > 0.0f && *yfov < std::numbers::pi_v<float>)) {
          fail(owner, fmt::format("yfov {} must be in (0, pi) radians", *yfov));
        }
      } else if (type != "orthographic") {
        fail(owner, fmt::format("type '{}' is not perspective or orthographic", type));
      }
      cameraFov_.push_back(yfov);
      cameraNames_.push_back(owner);
    }
  }

  // ---- Meshes: their primitives' materials ----
  void readMeshes() {
    const Json& meshes = array(doc_, "meshes", kTopLevel);
    for (size_t m = 0; m < meshes.size(); ++m) {
      const std::string owner = fmt::format("mesh {}", m);
      if (!meshes[m].is_object()) fail(owner, "must be an object");
      const Json& primitives = array(meshes[m], "primitives", owner);
      std::vector<std::optional<size_t>> materials;
      for (size_t p = 0; p < primitives.size(); ++p) {
        const std::string primitive = fmt::format("mesh {} primitive {}", m, p);
        if (!primitives[p].is_object()) fail(primitive, "must be an object");
        materials.push_back(primitives[p].contains("material")
                                ? std::optional(index(primitives[p], "material", out_.materials.size(), primitive,
                                                      "materials"))
                                : std::nullopt);
      }
      out_.primitiveMaterials.push_back(std::move(materials));
    }
  }

  // ---- The node graph ----
  // The default scene's root nodes ("scene", else scene 0); a file without
  // scenes: every node no other node lists as a child.
  std::vector<size_t> roots(const Json& nodes) const {
    std::vector<size_t> out;
    const Json& scenes = array(doc_, "scenes", kTopLevel);
    if (!scenes.empty()) {
      const size_t s = doc_.contains("scene") ? index(doc_, "scene", scenes.size(), kTopLevel, "scenes") : 0;
      const std::string owner = fmt::format("scene {}", s);
      const Json& list = array(scenes[s], "nodes", owner);
      for (size_t k = 0; k < list.size(); ++k) {
        if (!list[k].is_number_unsigned() || list[k].get<uint64_t>() >= nodes.size()) {
          fail(owner, fmt::format("node {} must name one of the file's {} nodes", list[k].dump(), nodes.size()));
        }
        out.push_back(list[k].get<size_t>());
      }
      return out;
    }
    std::vector<bool> child(nodes.size(), false);
    for (size_t n = 0; n < nodes.size(); ++n) {
      for (const Json& c : array(nodes[n], "children", nodeLabel(nodes, n))) {
        if (c.is_number_unsigned() && c.get<uint64_t>() < nodes.size()) child[c.get<size_t>()] = true;
      }
    }
    for (size_t n = 0; n < nodes.size(); ++n) {
      if (!child[n]) out.push_back(n);
    }
    return out;
  }

  std::string nodeLabel(const Json& nodes, size_t n) const {
    return nodes[n].is_object() && nodes[n].contains("name") && nodes[n]["name"].is_string()
               ? fmt::format("node {} '{}'", n, nodes[n]["name"].get<std::string>())
               : fmt::format("node {}", n);
  }

  // A node's local transform: its matrix (column-major), or T * R * S.
  glm::mat4 localTransform(const Json& node, const std::string& owner) const {
    if (node.contains("matrix")) return glm::make_mat4(numbers(node, "matrix", 16, {}, owner).data());
    const std::vector<float> t = numbers(node, "translation", 3, {0.0f, 0.0f, 0.0f}, owner);
    const std::vector<float> r = numbers(node, "rotation", 4, {0.0f, 0.0f, 0.0f, 1.0f}, owner);  // x y z w
    const std::vector<float> s = numbers(node, "scale", 3, {1.0f, 1.0f, 1.0f}, owner);
    const glm::mat4 rotation = glm::mat4_cast(glm::normalize(glm::quat(r[3], r[0], r[1], r[2])));
    return glm::translate(glm::mat4(1.0f), glm::vec3(t[0], t[1], t[2])) * rotation *
           glm::scale(glm::mat4(1.0f), glm::vec3(s[0], s[1], s[2]));
  }

  void walk(const Json& nodes, size_t n, const glm::mat4& parent, const std::vector<size_t>& treePath) {
    const std::string owner = nodeLabel(nodes, n);
    if (visited_[n]) fail(kTopLevel, fmt::format("{} is reached twice: the node graph must be a tree", owner));
    visited_[n] = true;
    const Json& node = nodes[n];
    if (!node.is_object()) fail(owner, "must be an object");
    const glm::mat4 world = parent * localTransform(node, owner);
    const glm::vec3 origin(world[3]);
    const glm::vec3 forward = glm::normalize(glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)));
    if (const Json* ext = object(node, "extensions", owner)) {
      if (const Json* punctual = object(*ext, "KHR_lights_punctual", owner)) {
        if (!punctual->contains("light")) fail(owner, "KHR_lights_punctual needs 'light'");
        Light light = lightDefs_[index(*punctual, "light", lightDefs_.size(), owner, "lights")];
        light.position = origin;
        light.direction = forward;
        const bool placed = light.kind != Light::Kind::Directional, aimed = light.kind != Light::Kind::Point;
        const bool badPosition = placed && !allFinite(light.position);
        if (badPosition || (aimed && !allFinite(light.direction))) {
          const glm::vec3 v = badPosition ? light.position : light.direction;
          fail(kTopLevel, fmt::format("light '{}' on {}: its world {} ({}, {}, {}) is not finite", light.name, owner,
                           badPosition ? "position" : "direction", v.x, v.y, v.z));
        }
        out_.lights.push_back(light);
      }
    }
    if (node.contains("mesh")) {
      out_.meshInstances.push_back(
          {index(node, "mesh", out_.primitiveMaterials.size(), owner, "meshes"), world, owner, treePath});
    }
    if (node.contains("camera")) {
      const size_t c = index(node, "camera", cameraFov_.size(), owner, "cameras");
      if (cameraFov_[c] && !out_.view) {
        View view;
        view.eye = origin;
        view.target = origin + forward;
        view.up = glm::normalize(glm::vec3(world * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));
        view.fovYDegrees = glm::degrees(*cameraFov_[c]);
        if (!allFinite(view.eye) || !allFinite(view.target) || !allFinite(view.up)) {
          fail(kTopLevel, fmt::format("{} on {}: its world position or orientation is not finite", cameraNames_[c], owner));
        }
        out_.view = view;
      }
    }
    const Json& children = array(node, "children", owner);
    for (size_t k = 0; k < children.size(); ++k) {
      const Json& c = children[k];
      if (!c.is_number_unsigned() || c.get<uint64_t>() >= nodes.size()) {
        fail(owner, fmt::format("child {} must name one of the file's {} nodes", c.dump(), nodes.size()));
      }
      std::vector<size_t> childPath = treePath;
      childPath.push_back(k);
      walk(nodes, c.get<size_t>(), world, childPath);
    }
  }

  std::string path_;
  Json doc_;
  std::vector<Light> lightDefs_;
  std::vector<std::optional<float>> cameraFov_;  // yfov in radians; nullopt: orthographic
  std::vector<std::string> cameraNames_;
  std::vector<bool> visited_;
  GltfExtras out_;
};

// ---- The scene: assimp's meshes at the JSON's nodes ------------------------------------


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

}  // namespace

GltfExtras readGltfExtras(const std::string& path) {
  Json doc;
  try {
    CorrectlyRoundedDom dom(doc);
    Json::sax_parse(jsonText(path), &dom);
  } catch (const Json::parse_error& e) {
    throw InputError(fmt::format("{}: malformed glTF JSON: {}", path, e.what()));
  }
  if (!doc.is_object()) throw InputError(fmt::format("{}: malformed glTF: the JSON is not an object", path));
  return Reader(path, std::move(doc)).read();
}

int gltfMajorVersion(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(8, '\0');
  if (!in.read(head.data(), 8)) return 2;
  if (readU32(head, 0) == kGlbMagic) return int(readU32(head, 4));
  in.seekg(0);
  const Json doc = Json::parse(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()),
                               nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object() || !doc.contains("asset") || !doc["asset"].is_object() || !doc["asset"].contains("version")) {
    return 2;
  }
  // glTF 1.0 files wrote the version as a string or a number.
  const Json& version = doc["asset"]["version"];
  if (version.is_number()) return version.get<double>() < 2.0 ? 1 : 2;
  return version.is_string() && version.get<std::string>().starts_with("1") ? 1 : 2;
}

Scene loadGltf(const std::string& path) {
  // Read first, so that its errors name the light, camera, node or material
  // rather than assimp's parse.
  GltfExtras gltf = readGltfExtras(path);
  Assimp::Importer importer;
  // The meshes in their own frames, exactly as the buffers hold them (no
  // joining, no generated normals; no aiProcess_PreTransformVertices: the
  // nodes are placed below from the JSON).
  const aiScene* ai = importWithAssimp(importer, path, aiProcess_Triangulate);
  // Each placed node's aiMeshes, found through assimp's node tree, which has
  // the shape of the default scene's (glTF2Importer's ImportNodes): its root
  // is the scene's one root, or a node above the scene's roots. Not by the
  // mesh's index in the file: assimp numbers meshes (and materials) in the
  // order its reader first met them, which is not the file's.
  const auto aiNodeOf = [&](const GltfExtras::MeshInstance& instance) -> const aiNode* {
    const aiNode* node = ai->mRootNode;
    for (size_t depth = gltf.rootCount == 1 ? 1 : 0; node && depth < instance.treePath.size(); ++depth) {
      node = instance.treePath[depth] < node->mNumChildren ? node->mChildren[instance.treePath[depth]] : nullptr;
    }
    return node;
  };
  // Per placed node, its primitives' aiMeshes (nullptr: points or lines, not traced).
  std::vector<std::vector<const aiMesh*>> instanceMeshes;
  // assimp's material of each glTF material (assimp imports the ones its
  // reader met, then a default of its own, last).
  std::vector<std::optional<unsigned>> aiMaterialOf(gltf.materials.size());
  std::vector<std::optional<size_t>> gltfMaterialOf(ai->mNumMaterials);
  for (const GltfExtras::MeshInstance& instance : gltf.meshInstances) {
    const std::vector<std::optional<size_t>>& primitives = gltf.primitiveMaterials[instance.mesh];
    const aiNode* node = aiNodeOf(instance);
    if (!node || node->mNumMeshes != primitives.size()) {
      throw InputError(fmt::format("{}: cannot read scene: assimp's node tree does not match the file's at {} (mesh {}, "
                                   "{} primitives)", path, instance.node, instance.mesh, primitives.size()));
    }
    std::vector<const aiMesh*>& meshes = instanceMeshes.emplace_back();
    for (size_t p = 0; p < primitives.size(); ++p) {
      if (node->mMeshes[p] >= ai->mNumMeshes) {
        throw InputError(fmt::format("{}: cannot read scene: assimp's {} names mesh {} of its {}", path, instance.node,
                                     node->mMeshes[p], ai->mNumMeshes));
      }
      const aiMesh* mesh = ai->mMeshes[node->mMeshes[p]];
      meshes.push_back(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE ? mesh : nullptr);
      // The primitive's glTF material and assimp's must pair one to one.
      const unsigned aiMaterial = mesh->mMaterialIndex;
      const std::optional<size_t> material = primitives[p];
      const bool paired =
          aiMaterial < ai->mNumMaterials &&
          (!material || !aiMaterialOf[*material] || *aiMaterialOf[*material] == aiMaterial) &&
          (!gltfMaterialOf[aiMaterial] || (material && *gltfMaterialOf[aiMaterial] == *material));
      if (!paired) {
        throw InputError(fmt::format("{}: cannot read scene: assimp's materials do not match the file's at {} mesh {} "
                                     "primitive {}", path, instance.node, instance.mesh, p));
      }
      if (material) {
        aiMaterialOf[*material] = aiMaterial;
        gltfMaterialOf[aiMaterial] = *material;
      }
    }
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
    // A material no placed primitive uses, and assimp's default, keep the
    // extensions' defaults.
    const GltfExtras::MaterialExtras extras =
        gltfMaterialOf[m] ? gltf.materials[*gltfMaterialOf[m]] : GltfExtras::MaterialExtras{};
    if (gltfMaterialOf[m]) material.name = extras.name;
    material.emission *= extras.emissiveStrength;
    readGltfTerms(*mat, extras, path, material);
    checkMaterialTerms(material, path);
    scene.materials.push_back(material);
  }
  if (scene.materials.empty()) scene.materials.push_back(Material{"default"});
  // Vertex normals (NORMAL) become shading normals when any placed triangle
  // mesh has them; a mesh without them, and a zero or non-finite normal, take
  // the triangle's geometric normal.
  bool withNormals = false;
  for (const std::vector<const aiMesh*>& meshes : instanceMeshes) {
    for (const aiMesh* mesh : meshes) withNormals |= mesh && mesh->mNormals;
  }
  // Triangle order: nodes in walk order, a mesh's primitives in order, faces in order.
  for (size_t i = 0; i < gltf.meshInstances.size(); ++i) {
    const GltfExtras::MeshInstance& instance = gltf.meshInstances[i];
    for (size_t p = 0; p < instanceMeshes[i].size(); ++p) {
      const aiMesh* mesh = instanceMeshes[i][p];
      if (!mesh) continue;
      const uint32_t material = mesh->mMaterialIndex < scene.materials.size() ? mesh->mMaterialIndex : 0;
      appendPlacedMesh(scene, *mesh, instance.world, material, withNormals, path,
                       fmt::format("{}: mesh {} primitive {}", instance.node, instance.mesh, p));
    }
  }
  if (scene.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", path));
  // The buffers' floats are exact; a node's transform is decimal text, read
  // correctly rounded.
  const bool placedAsStored = std::all_of(gltf.meshInstances.begin(), gltf.meshInstances.end(),
                                          [](const auto& instance) { return instance.world == glm::mat4(1.0f); });
  scene.numbers = placedAsStored ? SceneNumbers::Exact : SceneNumbers::CorrectlyRounded;
  scene.lights = std::move(gltf.lights);
  scene.view = gltf.view;
  scene.computeBounds();
  return scene;
}

}  // namespace lancer
