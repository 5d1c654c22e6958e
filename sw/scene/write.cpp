#include "scene/write.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scene/text.h"

namespace lancer {

namespace {

// ---- Vertices shared by their bits -------------------------------------------------------

// The scene's vertices, each distinct bit pattern once (so -0 and +0 stay
// apart), and each triangle's three indices into them.
struct IndexedMesh {
  std::vector<glm::vec3> vertices;
  std::vector<std::array<uint32_t, 3>> faces;
};

IndexedMesh indexed(const Scene& scene) {
  IndexedMesh mesh;
  std::map<std::array<uint32_t, 3>, uint32_t> index;
  const auto id = [&](const glm::vec3& v) {
    const std::array<uint32_t, 3> bits{std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y),
                                       std::bit_cast<uint32_t>(v.z)};
    const auto [it, fresh] = index.try_emplace(bits, uint32_t(mesh.vertices.size()));
    if (fresh) mesh.vertices.push_back(v);
    return it->second;
  };
  for (const Triangle& t : scene.triangles) mesh.faces.push_back({id(t.v0), id(t.v1), id(t.v2)});
  return mesh;
}

std::ofstream openOutput(const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(fmt::format("{}: cannot write file", path.string()));
  return out;
}

void finish(std::ofstream& out, const std::filesystem::path& path) {
  out.flush();
  if (!out) throw InputError(fmt::format("{}: write failed", path.string()));
}

// ---- OBJ and MTL -----------------------------------------------------------------------------

// A float at 9 significant digits: enough for every float to read back as
// itself through a correctly rounded reader.
std::string exact(float value) { return fmt::format("{:.9g}", value); }

// Each material's MTL name: its own where Lancer's reader gives it back
// as it is (the rest of the line, blanks trimmed) and no other material has
// it, else m<index>.
std::vector<std::string> mtlNames(const std::vector<Material>& materials) {
  std::map<std::string, int> uses;
  for (const Material& m : materials) ++uses[m.name];
  std::vector<std::string> out;
  for (size_t i = 0; i < materials.size(); ++i) {
    const std::string& name = materials[i].name;
    const bool generated = name.size() > 1 && name[0] == 'm' &&
                           std::all_of(name.begin() + 1, name.end(), [](char c) { return c >= '0' && c <= '9'; });
    const bool plain = !name.empty() && trimmed(name) == name && name.find_first_of("\n\r") == std::string::npos &&
                       !generated && uses[name] == 1;
    out.push_back(plain ? name : fmt::format("m{}", i));
  }
  return out;
}

void writeObj(const Scene& scene, const std::filesystem::path& path) {
  const IndexedMesh mesh = indexed(scene);
  const std::filesystem::path mtlPath = std::filesystem::path(path).replace_extension(".mtl");
  const std::vector<std::string> names = mtlNames(scene.materials);
  {
    std::ofstream mtl = openOutput(mtlPath);
    mtl << "# written by lancer convert from " << scene.name << "\n";
    for (size_t m = 0; m < scene.materials.size(); ++m) {
      const Material& mat = scene.materials[m];
      mtl << fmt::format("\nnewmtl {}\n", names[m]);
      mtl << fmt::format("Kd {} {} {}\n", exact(mat.diffuse.r), exact(mat.diffuse.g), exact(mat.diffuse.b));
      mtl << fmt::format("Ke {} {} {}\n", exact(mat.emission.r), exact(mat.emission.g), exact(mat.emission.b));
      // illum 3 reflects with Ks's weight; 2 is a highlight only.
      mtl << fmt::format("Ks {0} {0} {0}\nillum {1}\n", exact(mat.ks), mat.ks > 0.0f ? 3 : 2);
      mtl << fmt::format("Ns {}\nNi {}\nd {}\n", exact(mat.shine), exact(mat.ior), exact(1.0f - mat.transmittance));
    }
    finish(mtl, mtlPath);
  }
  std::ofstream out = openOutput(path);
  out << "# written by lancer convert from " << scene.name << " (" << scene.size() << " triangles)\n";
  out << "mtllib " << mtlPath.filename().string() << "\n";
  for (const glm::vec3& v : mesh.vertices) out << "v " << exact(v.x) << ' ' << exact(v.y) << ' ' << exact(v.z) << '\n';
  std::optional<uint32_t> current;
  for (size_t t = 0; t < mesh.faces.size(); ++t) {
    if (scene.materialOf[t] != current) {
      current = scene.materialOf[t];
      out << "usemtl " << names[*current] << '\n';
    }
    const auto& f = mesh.faces[t];
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  }
  finish(out, path);
}

// ---- PLY ---------------------------------------------------------------------------------------

template <typename T>
void putLittle(std::string& bytes, T value) {
  static_assert(std::endian::native == std::endian::little, "the writers assume a little-endian host");
  const size_t at = bytes.size();
  bytes.resize(at + sizeof(T));
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

void writePly(const Scene& scene, const std::filesystem::path& path) {
  const IndexedMesh mesh = indexed(scene);
  std::string bytes = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment written by lancer convert from {}\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
      scene.name.empty() ? "a scene" : scene.name, mesh.vertices.size(),
      mesh.faces.size());
  for (const glm::vec3& v : mesh.vertices) {
    putLittle(bytes, v.x);
    putLittle(bytes, v.y);
    putLittle(bytes, v.z);
  }
  for (const auto& f : mesh.faces) {
    putLittle(bytes, uint8_t(3));
    for (const uint32_t i : f) putLittle(bytes, i);
  }
  std::ofstream out = openOutput(path);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  finish(out, path);
}

// ---- glTF 2.0 binary ---------------------------------------------------------------------------

using Json = nlohmann::json;

// Whitted terms back to metallic-roughness factors, the inverse of loadGltf's
// mapping where one exists (docs/scenes.md, "glTF 2.0"): a mirror is a smooth
// metal, a transmitting material a smooth dielectric, a diffuse one rough.
Json gltfMaterial(const Material& m) {
  const float f0 = (m.ior - 1.0f) * (m.ior - 1.0f) / ((m.ior + 1.0f) * (m.ior + 1.0f));
  float metallic = 0.0f, roughness = 1.0f, transmission = 0.0f;
  if (m.transmittance > 0.0f) {
    roughness = 0.0f;
    transmission = std::min(1.0f, m.transmittance / (1.0f - f0));
  } else if (m.ks > 0.0f) {
    roughness = 0.0f;
    metallic = m.ks > f0 ? std::min(1.0f, (m.ks - f0) / (1.0f - f0)) : 0.0f;
    if (m.ks < f0) roughness = 1.0f - m.ks / f0;
  }
  Json material = {{"name", m.name},
                   {"pbrMetallicRoughness",
                    {{"baseColorFactor", {m.diffuse.r, m.diffuse.g, m.diffuse.b, 1.0f}},
                     {"metallicFactor", metallic},
                     {"roughnessFactor", roughness}}}};
  // glTF's emissive factor is at most 1: the rest goes to the strength.
  const float strength = std::max({1.0f, m.emission.r, m.emission.g, m.emission.b});
  if (glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f)))) {
    material["emissiveFactor"] = {m.emission.r / strength, m.emission.g / strength, m.emission.b / strength};
    if (strength > 1.0f) material["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
  }
  if (transmission > 0.0f) {
    material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", transmission}};
    material["extensions"]["KHR_materials_ior"] = {{"ior", m.ior}};
  }
  return material;
}

// A node that turns glTF's -z onto `direction`.
std::array<float, 4> aim(const glm::vec3& direction) {
  const glm::quat q = glm::rotation(glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(direction));
  return {q.x, q.y, q.z, q.w};
}

void writeGlb(const Scene& scene, const std::filesystem::path& path) {
  const IndexedMesh mesh = indexed(scene);
  std::string bin;
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& v : mesh.vertices) {
    putLittle(bin, v.x);
    putLittle(bin, v.y);
    putLittle(bin, v.z);
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  const size_t indexStart = bin.size();
  for (const auto& f : mesh.faces) {
    for (const uint32_t i : f) putLittle(bin, i);
  }
  Json doc = {{"asset", {{"version", "2.0"}, {"generator", "lancer convert"}}},
              {"scene", 0},
              {"buffers", {{{"byteLength", bin.size()}}}},
              {"bufferViews",
               {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", indexStart}, {"target", 34962}},
                {{"buffer", 0}, {"byteOffset", indexStart}, {"byteLength", bin.size() - indexStart}, {"target", 34963}}}},
              {"accessors",
               {{{"bufferView", 0},
                 {"componentType", 5126},
                 {"count", mesh.vertices.size()},
                 {"type", "VEC3"},
                 {"min", {lo.x, lo.y, lo.z}},
                 {"max", {hi.x, hi.y, hi.z}}}}}};
  // One primitive per run of triangles of one material keeps the triangle order.
  Json primitives = Json::array();
  for (size_t start = 0; start < mesh.faces.size();) {
    size_t end = start;
    while (end < mesh.faces.size() && scene.materialOf[end] == scene.materialOf[start]) ++end;
    doc["accessors"].push_back({{"bufferView", 1},
                                {"byteOffset", start * 12},
                                {"componentType", 5125},
                                {"count", (end - start) * 3},
                                {"type", "SCALAR"}});
    primitives.push_back({{"attributes", {{"POSITION", 0}}},
                          {"indices", doc["accessors"].size() - 1},
                          {"material", scene.materialOf[start]},
                          {"mode", 4}});
    start = end;
  }
  doc["meshes"] = {{{"name", scene.name}, {"primitives", primitives}}};
  doc["materials"] = Json::array();
  for (const Material& m : scene.materials) doc["materials"].push_back(gltfMaterial(m));
  doc["nodes"] = {{{"name", "scene"}, {"mesh", 0}}};
  doc["scenes"] = {{{"nodes", {0}}}};
  if (!scene.lights.empty()) {
    Json lights = Json::array();
    for (size_t l = 0; l < scene.lights.size(); ++l) {
      const Light& light = scene.lights[l];
      Json def = {{"name", light.name}, {"color", {light.color.r, light.color.g, light.color.b}}, {"intensity", 1.0f}};
      Json node = {{"name", light.name}, {"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}};
      if (light.kind != Light::Kind::Directional) node["translation"] = {light.position.x, light.position.y, light.position.z};
      if (light.kind != Light::Kind::Point) node["rotation"] = aim(light.direction);
      if (light.kind == Light::Kind::Point) {
        def["type"] = "point";
      } else if (light.kind == Light::Kind::Directional) {
        def["type"] = "directional";
      } else {
        def["type"] = "spot";
        const float outer = std::acos(std::clamp(light.outerConeCos, 0.0f, 1.0f));
        const float inner = std::min(std::acos(std::clamp(light.innerConeCos, 0.0f, 1.0f)), std::nextafter(outer, 0.0f));
        def["spot"] = {{"innerConeAngle", std::max(0.0f, inner)}, {"outerConeAngle", outer}};
      }
      lights.push_back(def);
      doc["scenes"][0]["nodes"].push_back(doc["nodes"].size());
      doc["nodes"].push_back(node);
    }
    doc["extensionsUsed"] = {"KHR_lights_punctual"};
    doc["extensions"]["KHR_lights_punctual"]["lights"] = lights;
  }
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned: JSON pads with blanks
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string glb;
  putLittle(glb, uint32_t(0x46546C67));  // "glTF"
  putLittle(glb, uint32_t(2));
  putLittle(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  putLittle(glb, uint32_t(json.size()));
  putLittle(glb, uint32_t(0x4E4F534A));  // "JSON"
  glb += json;
  putLittle(glb, uint32_t(bin.size()));
  putLittle(glb, uint32_t(0x004E4942));  // "BIN\0"
  glb += bin;
  std::ofstream out = openOutput(path);
  out.write(glb.data(), std::streamsize(glb.size()));
  finish(out, path);
}

}  // namespace

void writeScene(const Scene& scene, const std::filesystem::path& path) {
  scene.requireTrianglesOnly(fmt::format("writing {}", path.string()));
  const std::string extension = lowercase(path.extension().string());
  if (extension == ".obj") return writeObj(scene, path);
  if (extension == ".ply") return writePly(scene, path);
  if (extension == ".glb") return writeGlb(scene, path);
  throw InputError(fmt::format("{}: {} is not a format Lancer writes: {}", path.string(),
                               extension.empty() ? "a file without an extension" : "'" + extension + "'",
                               kWrittenFormats));
}

}  // namespace lancer
