#include "scene/gltf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"

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
    const Json& nodes = array(doc_, "nodes", kTopLevel);
    visited_.assign(nodes.size(), false);
    for (const size_t root : roots(nodes)) walk(nodes, root, glm::mat4(1.0f));
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

  void walk(const Json& nodes, size_t n, const glm::mat4& parent) {
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
    for (const Json& c : array(node, "children", owner)) {
      if (!c.is_number_unsigned() || c.get<uint64_t>() >= nodes.size()) {
        fail(owner, fmt::format("child {} must name one of the file's {} nodes", c.dump(), nodes.size()));
      }
      walk(nodes, c.get<size_t>(), world);
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

}  // namespace

GltfExtras readGltfExtras(const std::string& path) {
  Json doc;
  try {
    doc = Json::parse(jsonText(path));
  } catch (const Json::parse_error& e) {
    throw InputError(fmt::format("{}: malformed glTF JSON: {}", path, e.what()));
  }
  if (!doc.is_object()) throw InputError(fmt::format("{}: malformed glTF: the JSON is not an object", path));
  return Reader(path, std::move(doc)).read();
}

}  // namespace lancer
