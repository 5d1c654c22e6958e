#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scene/scene.h"
#include "scene/spd.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

TEST(Scene, CornellBoxIsEmbeddedAndFramed) {
  const Scene scene = loadScene(kDefaultSceneName);
  EXPECT_EQ(scene.size(), 32u);
  EXPECT_EQ(scene.materialOf.size(), scene.size());
  ASSERT_TRUE(scene.view.has_value());
  EXPECT_FLOAT_EQ(scene.bounds.lo.x, 0.0f);
  EXPECT_FLOAT_EQ(scene.bounds.hi.x, 556.0f);
  EXPECT_FLOAT_EQ(scene.bounds.hi.y, 548.8f);
}

// The effects of the default scene, by the triangle ids docs/scenes.md lists:
// the lamp (10, 11) is its area light, the short block (12-21) glass, the tall
// block (22-31) a mirror, and a point light hangs under the lamp.
TEST(Scene, CornellBoxHasAMirrorAGlassBlockAndBothKindsOfLight) {
  const Scene scene = makeCornellBox();
  EXPECT_EQ(scene.emissiveTriangles(), (std::vector<uint32_t>{10, 11}));
  for (uint32_t t = 12; t < 32; ++t) {
    const Material& m = scene.materials[scene.materialOf[t]];
    if (t < 22) {
      EXPECT_EQ(m.name, "glass") << "triangle " << t;
      EXPECT_FLOAT_EQ(m.transmittance, 0.9f);
      EXPECT_FLOAT_EQ(m.ior, 1.5f);
    } else {
      EXPECT_EQ(m.name, "mirror") << "triangle " << t;
      EXPECT_FLOAT_EQ(m.ks, 0.8f);
      EXPECT_FLOAT_EQ(m.transmittance, 0.0f);
    }
  }
  for (uint32_t t = 0; t < 10; ++t) {
    const Material& m = scene.materials[scene.materialOf[t]];
    EXPECT_EQ(m.ks + m.transmittance, 0.0f) << "walls are diffuse: triangle " << t;
  }
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& point = scene.lights[0];
  EXPECT_EQ(point.kind, Light::Kind::Point);
  // Under the lamp's centre, below the lamp, inside the box.
  EXPECT_EQ(point.position, glm::vec3(278.0f, 538.8f, 279.5f));
  EXPECT_LT(point.position.y, scene.triangles[10].v0.y);
  EXPECT_TRUE(glm::all(glm::lessThan(scene.bounds.lo, point.position)) && glm::all(glm::lessThan(point.position, scene.bounds.hi)));
  // The glass block is closed above the floor with faces wound outwards, so a
  // ray's side of a face tells entering from leaving: every face's normal points
  // away from the block's centre.
  glm::vec3 centre(0.0f);
  for (uint32_t t = 12; t < 22; ++t) centre += (scene.triangles[t].v0 + scene.triangles[t].v1 + scene.triangles[t].v2) / 30.0f;
  for (uint32_t t = 12; t < 22; ++t) {
    const Triangle& tri = scene.triangles[t];
    const glm::vec3 normal = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    EXPECT_GT(glm::dot(normal, (tri.v0 + tri.v1 + tri.v2) / 3.0f - centre), 0.0f) << "triangle " << t;
  }
}

TEST(Scene, LoadsBunnyAndWuson) {
  const Scene bunny = loadScene(test::kBunny);
  EXPECT_EQ(bunny.size(), 3674u);
  const Scene wuson = loadScene(test::kWuson);
  EXPECT_GT(wuson.size(), 1000u);
  EXPECT_FALSE(wuson.bounds.empty());
}

TEST(Scene, TriangleOrderFollowsTheFile) {
  const auto path = std::filesystem::temp_directory_path() / "lancer_order.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                         "f 1 2 3\nf 1 3 4\nf 1 2 3 4\n";  // the quad becomes two triangles
  const Scene scene = loadScene(path.string());
  ASSERT_EQ(scene.size(), 4u);
  EXPECT_EQ(scene.triangles[0].v1, glm::vec3(1, 0, 0));
  EXPECT_EQ(scene.triangles[1].v2, glm::vec3(0, 0, 1));
}

// MTL's Whitted terms: illum >= 3 reflects with Ks, d < 1 transmits with Ni,
// illum 2's Ks is a highlight only, Ni 0 on an opaque material is unused.
TEST(Scene, ReadsTheWhittedTermsOfMtlMaterials) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_whitted.mtl") << "newmtl mirror\nKd 0.1 0.1 0.1\nKs 0.8 0.7 0.6\nNs 50\nillum 3\n"
                                               "newmtl glass\nKd 0 0 0\nd 0.25\nNi 1.5\nillum 7\n"
                                               "newmtl plastic\nKd 1 0 0\nKs 0.9 0.9 0.9\nNi 0\nillum 2\n";
  std::ofstream(dir / "lancer_whitted.obj") << "mtllib lancer_whitted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                               "usemtl mirror\nf 1 2 3\nusemtl glass\nf 1 2 3\n"
                                               "usemtl plastic\nf 1 2 3\n";
  const Scene scene = loadScene((dir / "lancer_whitted.obj").string());
  ASSERT_EQ(scene.size(), 3u);
  const Material& mirror = scene.materials[scene.materialOf[0]];
  EXPECT_EQ(mirror.name, "mirror");
  EXPECT_FLOAT_EQ(mirror.ks, 0.8f);
  EXPECT_FLOAT_EQ(mirror.shine, 50.0f);
  EXPECT_FLOAT_EQ(mirror.transmittance, 0.0f);
  const Material& glass = scene.materials[scene.materialOf[1]];
  EXPECT_FLOAT_EQ(glass.transmittance, 0.75f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  const Material& plastic = scene.materials[scene.materialOf[2]];
  EXPECT_FLOAT_EQ(plastic.ks, 0.0f);
  EXPECT_FLOAT_EQ(plastic.ior, 1.0f);
  // A transmitting material without a usable index of refraction is an error naming it.
  std::ofstream(dir / "lancer_whitted.mtl") << "newmtl badglass\nd 0.5\nNi 0\n";
  std::ofstream(dir / "lancer_whitted.obj") << "mtllib lancer_whitted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                               "usemtl badglass\nf 1 2 3\n";
  try {
    loadScene((dir / "lancer_whitted.obj").string());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material 'badglass': index of refraction 0 must be > 0"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(dir / "lancer_whitted.mtl");
  std::filesystem::remove(dir / "lancer_whitted.obj");
}

// Found by tests/fuzz/fuzz_mtl: NaN, infinite and negative MTL terms were
// loaded as they stood. Each is now an error naming the file and material.
TEST(Scene, NonFiniteOrNegativeMtlTermsAreErrors) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_bad_terms.obj") << "mtllib lancer_bad_terms.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                 "usemtl m\nf 1 2 3\n";
  for (const auto& [terms, needle] : {std::pair{"Ks -5 -5 -5\nillum 3", "specular weight (Ks) -5"},
                                      std::pair{"Ks nan 0 0\nillum 3", "specular weight (Ks) nan"},
                                      std::pair{"Ns 1e39", "shininess (Ns) inf"},
                                      std::pair{"d nan", "transmittance (1 - d) nan"},
                                      std::pair{"Kd inf 0 0", "diffuse colour (Kd) (inf, 0, 0) is not finite"},
                                      std::pair{"Ke 1e39 1 1", "emission (Ke) (inf, 1, 1) is not finite"}}) {
    std::ofstream(dir / "lancer_bad_terms.mtl") << "newmtl m\n" << terms << "\n";
    try {
      loadScene((dir / "lancer_bad_terms.obj").string());
      ADD_FAILURE() << "expected an error for " << terms;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("lancer_bad_terms.mtl:1: material 'm': " + std::string(needle)),
                std::string::npos)
          << e.what();
    }
  }
  std::filesystem::remove(dir / "lancer_bad_terms.mtl");
  std::filesystem::remove(dir / "lancer_bad_terms.obj");
}

// Found by tests/fuzz/fuzz_mtl: these 8 bytes as an MTL file crashed assimp 5.2
// (SIGSEGV in its MTL parser), which read MTL files before Lancer's own reader.
// OBJ and MTL files with a NUL byte are refused, naming the line.
TEST(Scene, ObjOrMtlWithANulByteIsAnErrorNotACrash) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_nul.obj") << "mtllib lancer_nul.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  std::ofstream(dir / "lancer_nul.mtl", std::ios::binary) << std::string("\x01\0a\0< 1<", 8);
  try {
    loadScene((dir / "lancer_nul.obj").string());
    ADD_FAILURE() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lancer_nul.mtl:1: a NUL byte"), std::string::npos) << e.what();
  }
  std::filesystem::remove(dir / "lancer_nul.mtl");
  std::filesystem::remove(dir / "lancer_nul.obj");
}

// Found by fuzz_mtl in a 15-minute run: a statement before the first newmtl
// made assimp 5.2 write through its null current material (SIGSEGV) when it
// is an anisotropy `a` (the 9 bytes of the fuzzer's file, line 2) or a texture
// map. Such a statement has no material to apply to in any reader: refused,
// naming the line; comments and blank lines before newmtl (exporters write
// them), CRLF line ends and a byte-order mark are fine.
TEST(Scene, MtlStatementBeforeNewmtlIsAnErrorNotACrash) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_pre.obj") << "mtllib lancer_pre.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  for (const auto& [mtl, line] : {std::pair<std::string, int>{"# a#  n\na", 2},
                                  {"# header\n\n  map_Kd t.png\nnewmtl m\n", 3},
                                  {"bump b.png\r\nnewmtl m\r\n", 1},
                                  {"#\r\n\f\tdisp d.png\nnewmtl m\n", 2}}) {
    std::ofstream(dir / "lancer_pre.mtl", std::ios::binary) << mtl;
    try {
      loadScene((dir / "lancer_pre.obj").string());
      ADD_FAILURE() << "expected an error for " << mtl;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fmt::format("lancer_pre.mtl:{}: a statement before the first newmtl", line)),
                std::string::npos)
          << e.what();
    }
  }
  std::ofstream(dir / "lancer_pre.mtl", std::ios::binary)
      << "\xEF\xBB\xBF# Blender MTL File: 'a.blend'\r\n# Material Count: 1\r\n\r\n  newmtl m\r\nKd 0.5 0.5 0.5\r\n";
  const Scene scene = loadScene((dir / "lancer_pre.obj").string());
  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_EQ(scene.materials.at(scene.materialOf[0]).name, "m");
  std::filesystem::remove(dir / "lancer_pre.mtl");
  std::filesystem::remove(dir / "lancer_pre.obj");
}

// ---- glTF 2.0 ------------------------------------------------------------------------

// One triangle (0,0,0) (1,0,0) (0,1,0) as a data-URI buffer, the geometry every
// glTF test shares; the tests vary the lights, materials, cameras and nodes.
nlohmann::json gltfWithOneTriangle() {
  return nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "triangle", "mesh": 0}],
    "materials": [{"name": "plain"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "buffers": [{"byteLength": 36,
                 "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}]
  })");
}

// The test's own file name (CTest runs the tests in parallel): lancer_<test>.gltf.
std::string gltfName(const char* extension = ".gltf") {
  return std::string("lancer_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + extension;
}

std::filesystem::path writeGltf(const nlohmann::json& gltf) {
  const auto path = std::filesystem::temp_directory_path() / gltfName();
  std::ofstream(path) << gltf.dump(2);
  return path;
}

// The message of the InputError loading `path` throws (the test fails if none).
std::string loadError(const std::filesystem::path& path) {
  try {
    loadScene(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << ": expected an InputError";
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A scene with each kind of KHR_lights_punctual light, placed by nested nodes.
nlohmann::json gltfWithLights() {
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::parse(R"([
    {"name": "bulb", "type": "point", "color": [1, 0.5, 0.25], "intensity": 2},
    {"name": "spotty", "type": "spot", "intensity": 3, "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
    {"type": "directional", "intensity": 4}
  ])");
  // Node 2 turns the spot (which shines along its local -z) straight down; the
  // sun hangs under a translated and rotated parent and shines along world -x.
  for (const char* node : {
           R"({"name": "bulb node", "translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}})",
           R"({"name": "spot node", "translation": [0, 5, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
               "extensions": {"KHR_lights_punctual": {"light": 1}}})",
           R"({"name": "parent", "translation": [10, 0, 0], "rotation": [0, 0.70710678, 0, 0.70710678], "children": [4]})",
           R"({"name": "sun node", "extensions": {"KHR_lights_punctual": {"light": 2}}})"}) {
    gltf["nodes"].push_back(nlohmann::json::parse(node));
  }
  gltf["scenes"][0]["nodes"] = {0, 1, 2, 3};
  return gltf;
}

void expectNear(const glm::vec3& got, const glm::vec3& want, const char* what) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-5f) << what << " component " << i;
}

TEST(Gltf, PunctualLightsTakeTheirNodesWorldTransforms) {
  const Scene scene = loadScene(writeGltf(gltfWithLights()).string());
  ASSERT_EQ(scene.lights.size(), 3u);
  const Light& bulb = scene.lights[0];
  EXPECT_EQ(bulb.kind, Light::Kind::Point);
  EXPECT_EQ(bulb.name, "bulb");
  expectNear(bulb.position, {1, 2, 3}, "bulb position");
  expectNear(bulb.color, {2, 1, 0.5f}, "bulb colour times intensity");
  const Light& spot = scene.lights[1];
  EXPECT_EQ(spot.kind, Light::Kind::Spot);
  EXPECT_EQ(spot.name, "spotty");
  expectNear(spot.position, {0, 5, 0}, "spot position");
  expectNear(spot.direction, {0, -1, 0}, "spot direction");
  expectNear(spot.color, glm::vec3(3), "spot colour (white by default)");
  EXPECT_FLOAT_EQ(spot.innerConeCos, std::cos(0.25f));
  EXPECT_FLOAT_EQ(spot.outerConeCos, std::cos(0.5f));
  const Light& sun = scene.lights[2];
  EXPECT_EQ(sun.kind, Light::Kind::Directional);
  EXPECT_EQ(sun.name, "light 2");  // unnamed: its index
  expectNear(sun.direction, {-1, 0, 0}, "sun direction");
  expectNear(sun.position, {10, 0, 0}, "sun position (unused)");
  expectNear(sun.color, glm::vec3(4), "sun colour");
  // The default spot cone is pi/4 outside, 0 inside.
  nlohmann::json gltf = gltfWithLights();
  gltf["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"] = nlohmann::json::object();
  const Scene defaults = loadScene(writeGltf(gltf).string());
  EXPECT_FLOAT_EQ(defaults.lights[1].innerConeCos, 1.0f);
  EXPECT_FLOAT_EQ(defaults.lights[1].outerConeCos, std::cos(std::numbers::pi_v<float> / 4));
}

TEST(Gltf, TheFirstPerspectiveCameraIsTheView) {
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["cameras"] = nlohmann::json::parse(R"([
    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}},
    {"name": "eye", "type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1}}
  ])");
  // The orthographic camera comes first in node order and is skipped; the
  // perspective one sits under a parent that lifts it and turns it to look along -x.
  gltf["nodes"].push_back({{"camera", 0}});
  gltf["nodes"].push_back({{"translation", {0, 1, 0}}, {"children", {3}}});
  gltf["nodes"].push_back({{"translation", {5, 0, 0}}, {"rotation", {0, 0.70710678, 0, 0.70710678}}, {"camera", 1}});
  gltf["scenes"][0]["nodes"] = {0, 1, 2};
  const Scene scene = loadScene(writeGltf(gltf).string());
  ASSERT_TRUE(scene.view.has_value());
  expectNear(scene.view->eye, {5, 1, 0}, "eye");
  expectNear(scene.view->target, {4, 1, 0}, "target: one unit along the camera's -z");
  expectNear(scene.view->up, {0, 1, 0}, "up");
  EXPECT_NEAR(scene.view->fovYDegrees, 0.5f * 180.0f / std::numbers::pi_v<float>, 1e-4f);
  // Without a camera there is no view (the camera frames the scene itself).
  EXPECT_FALSE(loadScene(writeGltf(gltfWithOneTriangle()).string()).view.has_value());
}

// Each mapped material term against docs/scenes.md's formulas. The file does not
// list its extensions in "extensionsUsed" (assimp would then skip them): they are read anyway.
TEST(Gltf, MetallicRoughnessTransmissionIorAndEmissionMapOntoWhittedTerms) {
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["materials"] = nlohmann::json::parse(R"([
    {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}, "KHR_materials_ior": {"ior": 1.7}}},
    {"name": "brushed", "pbrMetallicRoughness": {"metallicFactor": 0.25, "roughnessFactor": 0.5}},
    {"name": "lamp", "emissiveFactor": [0.1, 0.2, 0.3], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}}},
    {"name": "defaults"}
  ])");
  for (int m = 1; m < 4; ++m) {
    gltf["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"material", m}});
  }
  const Scene scene = loadScene(writeGltf(gltf).string());
  ASSERT_EQ(scene.size(), 4u);
  // assimp orders the merged meshes by material: find each triangle by its material.
  auto material = [&](const std::string& name) {
    for (uint32_t t = 0; t < scene.size(); ++t) {
      if (scene.materials[scene.materialOf[t]].name == name) return std::pair{t, scene.materials[scene.materialOf[t]]};
    }
    ADD_FAILURE() << "no triangle of material " << name;
    return std::pair{UINT32_MAX, Material{}};
  };
  const Material glass = material("glass").second;
  EXPECT_EQ(glass.name, "glass");
  expectNear(glass.diffuse, {0.9f, 0.8f, 0.7f}, "base colour");
  const float f0 = (0.7f / 2.7f) * (0.7f / 2.7f);
  EXPECT_FLOAT_EQ(glass.ior, 1.7f);
  EXPECT_FLOAT_EQ(glass.ks, f0);
  EXPECT_FLOAT_EQ(glass.transmittance, 0.5f * (1 - f0));
  EXPECT_FLOAT_EQ(glass.kd, 1 - f0 - 0.5f * (1 - f0));
  EXPECT_FLOAT_EQ(glass.shine, 10000.0f);  // a perfectly smooth surface: the cap
  const Material brushed = material("brushed").second;
  EXPECT_FLOAT_EQ(brushed.ior, 1.5f);  // glTF's default
  EXPECT_FLOAT_EQ(brushed.ks, 0.5f * (0.25f + 0.75f * 0.04f));
  EXPECT_FLOAT_EQ(brushed.transmittance, 0.0f);
  EXPECT_FLOAT_EQ(brushed.kd, 1 - brushed.ks);
  EXPECT_FLOAT_EQ(brushed.shine, 2.0f / (0.25f * 0.25f) - 2.0f);
  const auto [lampTriangle, lamp] = material("lamp");
  expectNear(lamp.emission, {0.5f, 1.0f, 1.5f}, "emissive factor times strength");
  const Material defaults = material("defaults").second;  // glTF's defaults: a rough metal, diffuse in Whitted terms
  EXPECT_FLOAT_EQ(defaults.ks, 0.0f);
  EXPECT_FLOAT_EQ(defaults.kd, 1.0f);
  EXPECT_EQ(defaults.emission, glm::vec3(0.0f));
  EXPECT_EQ(scene.emissiveTriangles(), std::vector<uint32_t>{lampTriangle});
}

// The same file as a binary container: the JSON chunk, then the buffer as the BIN chunk.
TEST(Gltf, ReadsTheBinaryContainer) {
  nlohmann::json gltf = gltfWithLights();
  gltf["buffers"][0].erase("uri");
  std::string json = gltf.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string bin(reinterpret_cast<const char*>(vertices), sizeof vertices);
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string glb = "glTF" + u32(2) + u32(uint32_t(12 + 8 + json.size() + 8 + bin.size())) + u32(uint32_t(json.size())) +
                          "JSON" + json + u32(uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + bin;
  const auto path = std::filesystem::temp_directory_path() / gltfName(".glb");
  std::ofstream(path, std::ios::binary) << glb;
  const Scene scene = loadScene(path.string());
  EXPECT_EQ(scene.size(), 1u);
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[1].name, "spotty");
  // A container cut short names the file.
  std::ofstream(path, std::ios::binary) << glb.substr(0, 40);
  EXPECT_TRUE(contains(loadError(path), gltfName(".glb") + ": truncated glTF binary container")) << loadError(path);
}

// `gltf` written with every string "@N" replaced by the raw JSON text raws[N]:
// numbers exactly as a file would hold them (nlohmann would print the double).
std::filesystem::path writeGltfRaw(const nlohmann::json& gltf, const std::vector<std::string>& raws) {
  std::string text = gltf.dump();
  for (size_t i = 0; i < raws.size(); ++i) {
    const std::string tag = fmt::format("\"@{}\"", i);
    text.replace(text.find(tag), tag.size(), raws[i]);
  }
  const auto path = std::filesystem::temp_directory_path() / gltfName();
  std::ofstream(path) << text;
  return path;
}

// assimp 5.2 reads a node's numbers through double (a second rounding) and
// takes a world transform within 0.01 of the identity for the identity: a
// node translated by 0.005 was not moved. Lancer places the meshes from its
// own correctly rounded JSON numbers; nodes come in walk order, and every node
// of a mesh places a copy of it.
TEST(Gltf, NodesPlaceMeshesWithCorrectlyRoundedNumbers) {
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["nodes"][0]["translation"] = {"@0", "@1", "@2"};
  gltf["nodes"].push_back({{"mesh", 0}, {"scale", {"@3", 2, 1}}});
  gltf["scenes"][0]["nodes"] = {1, 0};
  const Scene scene = loadScene(
      writeGltfRaw(gltf, {"0.005", "1.00000005960464477539062500001", "3.1377567211166024e-10", "1e-45"}).string());
  ASSERT_EQ(scene.size(), 2u);
  EXPECT_EQ(scene.triangles[0].v1, glm::vec3(0x1p-149f, 0.0f, 0.0f));  // node 1 first: (1, 0, 0) scaled
  EXPECT_EQ(scene.triangles[0].v2, glm::vec3(0.0f, 2.0f, 0.0f));
  EXPECT_EQ(scene.triangles[1].v0, glm::vec3(std::strtof("0.005", nullptr), 0x1.000002p+0f, 0x1.59p-32f));
  EXPECT_EQ(fmt::format("{:a}", scene.triangles[1].v0.z), "0x1.59p-32");
}

// assimp numbers meshes and materials in the order its reader first meets
// them, not the file's: here the scene's first root names mesh 1 (two
// primitives) and material 1 before mesh 0 and material 0. Each node still
// gets its own mesh's triangles, and each triangle its own material with the
// extensions' factors (2CylinderEngine.glb read 499,131 triangles for 121,496
// when Lancer took assimp's meshes in the file's order).
TEST(Gltf, MeshesAndMaterialsFollowTheFileNotAssimpsOrder) {
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["materials"] = nlohmann::json::parse(R"([
    {"name": "red", "emissiveFactor": [1, 0, 0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}},
    {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 1]}}])");
  gltf["meshes"].push_back(nlohmann::json::parse(R"({"primitives": [
    {"attributes": {"POSITION": 0}, "material": 1}, {"attributes": {"POSITION": 0}, "material": 1}]})"));
  gltf["nodes"] = nlohmann::json::parse(R"([
    {"name": "one", "mesh": 0, "translation": [10, 0, 0]},
    {"name": "two", "mesh": 1, "translation": [20, 0, 0]}])");
  gltf["scenes"][0]["nodes"] = {1, 0};
  const Scene scene = loadScene(writeGltf(gltf).string());
  ASSERT_EQ(scene.size(), 3u);
  for (size_t t = 0; t < 3; ++t) {
    const bool two = t < 2;  // node 1 first, in the scene's order
    EXPECT_EQ(scene.triangles[t].v1, glm::vec3(two ? 21.0f : 11.0f, 0.0f, 0.0f)) << "triangle " << t;
    const Material& material = scene.materials[scene.materialOf[t]];
    EXPECT_EQ(material.name, two ? "blue" : "red") << "triangle " << t;
    EXPECT_EQ(material.emission, two ? glm::vec3(0.0f) : glm::vec3(2.0f, 0.0f, 0.0f)) << "triangle " << t;
    EXPECT_EQ(material.diffuse, two ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f)) << "triangle " << t;
  }
}

// A glTF whose translations are scaled by 2^k and whose nodes scale by 2^k
// places every vertex at exactly 2^k times the unscaled one.
TEST(Gltf, ScaledByAPowerOfTwoPlacesExactlyThatMultiple) {
  const auto load = [](int k) {
    nlohmann::json gltf = gltfWithOneTriangle();
    gltf["nodes"][0]["translation"] = {"@0", "@1", "@2"};
    gltf["nodes"][0]["scale"] = {std::ldexp(1.0, k), std::ldexp(1.0, k), std::ldexp(1.0, k)};
    std::vector<std::string> raws;
    for (const double t : {1234.567890123456789, -3.1377567211166024e-10, 0.1}) raws.push_back(fmt::format("{:.17g}", std::ldexp(t, k)));
    return loadScene(writeGltfRaw(gltf, raws).string());
  };
  const Scene base = load(0);
  for (const int k : {-60, -40, 40, 60}) {
    const Scene scaled = load(k);
    const Triangle &a = base.triangles[0], &b = scaled.triangles[0];
    for (const auto& [p, q] : {std::pair{a.v0, b.v0}, std::pair{a.v1, b.v1}, std::pair{a.v2, b.v2}}) {
      for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(q[axis], std::ldexp(p[axis], k)) << "2^" << k;
    }
  }
}

// A light's node is read as correctly rounded as a mesh's: through double, the
// decimal just above the midpoint between 1 and 1 + 2^-23 would be 1.
TEST(Gltf, LightPositionsAreCorrectlyRounded) {
  nlohmann::json gltf = gltfWithLights();
  gltf["nodes"][1]["translation"] = {"@0", 0, "@1"};
  const Scene scene = loadScene(writeGltfRaw(gltf, {"1.0000000596046447753906250000001", "3.1377567211166024e-10"}).string());
  EXPECT_EQ(scene.lights[0].position, glm::vec3(0x1.000002p+0f, 0.0f, 0x1.59p-32f));
}

TEST(Gltf, BadLightsMaterialsAndJsonAreErrorsNamingThem) {
  const std::string file = gltfName();
  // An index of refraction <= 0 on a transmitting material.
  for (const double ior : {0.0, -1.0}) {
    nlohmann::json gltf = gltfWithOneTriangle();
    gltf["materials"][0]["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                                          {"KHR_materials_ior", {{"ior", ior}}}};
    const std::string error = loadError(writeGltf(gltf));
    EXPECT_TRUE(contains(error, file + ": material 'plain': index of refraction")) << error;
    EXPECT_TRUE(contains(error, "must be > 0 on a transmitting material")) << error;
  }
  // A light whose world position is not a number: its parent's x scale
  // overflows float, and infinity times the child's zero x is NaN.
  {
    nlohmann::json gltf = gltfWithLights();
    gltf["nodes"].push_back({{"name", "huge"}, {"scale", {1e39, 1, 1}}, {"children", {6}}});
    gltf["nodes"].push_back({{"translation", {0, 1, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    gltf["scenes"][0]["nodes"].push_back(5);
    const std::string error = loadError(writeGltf(gltf));
    EXPECT_TRUE(contains(error, file + ": light 'bulb' on node 6: its world position (")) << error;
    EXPECT_TRUE(contains(error, "nan")) << error;
  }
  // A malformed JSON text names the file and where the parse stopped.
  {
    const auto path = std::filesystem::temp_directory_path() / file;
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "nodes": [)";
    const std::string error = loadError(path);
    EXPECT_TRUE(contains(error, file + ": malformed glTF JSON")) << error;
  }
  // Light definitions and references that cannot be.
  auto lightError = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json gltf = gltfWithLights();
    edit(gltf);
    return loadError(writeGltf(gltf));
  };
  auto lights = [](nlohmann::json& g) -> nlohmann::json& { return g["extensions"]["KHR_lights_punctual"]["lights"]; };
  std::string error = lightError([&](nlohmann::json& g) { lights(g)[0]["type"] = "area"; });
  EXPECT_TRUE(contains(error, file + ": light 'bulb': type 'area' is not point, spot or directional")) << error;
  error = lightError([&](nlohmann::json& g) { lights(g)[0]["intensity"] = -1; });
  EXPECT_TRUE(contains(error, "light 'bulb': intensity -1 must be a finite number >= 0")) << error;
  error = lightError([&](nlohmann::json& g) { lights(g)[0]["intensity"] = "bright"; });
  EXPECT_TRUE(contains(error, "light 'bulb': 'intensity' must be a number")) << error;
  error = lightError([&](nlohmann::json& g) { lights(g)[1].erase("spot"); });
  EXPECT_TRUE(contains(error, "light 'spotty': a spot light needs 'spot'")) << error;
  error = lightError([&](nlohmann::json& g) { lights(g)[1]["spot"]["innerConeAngle"] = 0.75; });
  EXPECT_TRUE(contains(error, "light 'spotty': cone angles inner 0.75 and outer 0.5")) << error;
  error = lightError([&](nlohmann::json& g) { g["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7; });
  EXPECT_TRUE(contains(error, "node 1 'bulb node': 'light' must name one of the file's 3 lights")) << error;
  error = lightError([&](nlohmann::json& g) { g["nodes"][4]["children"] = {3}; });
  EXPECT_TRUE(contains(error, "node 3 'parent' is reached twice")) << error;
  // Material factors out of range, a camera without a field of view.
  nlohmann::json gltf = gltfWithOneTriangle();
  gltf["materials"][0]["pbrMetallicRoughness"] = {{"roughnessFactor", 2}};
  error = loadError(writeGltf(gltf));
  EXPECT_TRUE(contains(error, "material 'plain': roughness factor 2 must be in [0, 1]")) << error;
  gltf = gltfWithOneTriangle();
  gltf["materials"][0]["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", -2}};
  error = loadError(writeGltf(gltf));
  EXPECT_TRUE(contains(error, "material 'plain': emissive strength -2 must be a finite number >= 0")) << error;
  gltf = gltfWithOneTriangle();
  gltf["materials"][0]["emissiveFactor"] = {1, -0.5, 0};
  error = loadError(writeGltf(gltf));
  EXPECT_TRUE(contains(error, "material 'plain': emission (1, -0.5, 0) must be finite and >= 0")) << error;
  gltf = gltfWithOneTriangle();
  gltf["cameras"] = {{{"name", "eye"}, {"type", "perspective"}, {"perspective", {{"yfov", 0}}}}};
  error = loadError(writeGltf(gltf));
  EXPECT_TRUE(contains(error, "camera 'eye': yfov 0 must be in (0, pi) radians")) << error;
}

// Vertex normals become unit shading normals; a face without them (or with a
// zero one) takes its geometric normal; a file without any leaves them empty.
TEST(Scene, VertexNormalsAreShadingNormals) {
  const auto path = std::filesystem::temp_directory_path() / "lancer_normals.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 3 4\nvn 0 0 0\n"
                         "f 1//1 2//2 3//3\nf 1 3 2\n";
  const Scene scene = loadScene(path.string());
  ASSERT_EQ(scene.size(), 2u);
  ASSERT_EQ(scene.normals.size(), 2u);
  EXPECT_EQ(scene.normals[0].n0, glm::vec3(0, 0, 1));
  expectNear(scene.normals[0].n1, {0, 0.6f, 0.8f}, "normalised");
  EXPECT_EQ(scene.normals[0].n2, glm::vec3(0, 0, 1));  // zero in the file: the geometric normal
  EXPECT_EQ(scene.normals[1].n0, glm::vec3(0, 0, -1));  // none: the geometric normal (wound the other way)
  EXPECT_EQ(scene.normals[1].n2, glm::vec3(0, 0, -1));
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_TRUE(loadScene(path.string()).normals.empty());
  std::filesystem::remove(path);
}

// MTL's Ke makes an OBJ material emissive, an area light.
TEST(Scene, MtlKeIsAnAreaLight) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_lamp.mtl") << "newmtl lamp\nKd 1 1 1\nKe 2 3 4\nnewmtl wall\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "lancer_lamp.obj") << "mtllib lancer_lamp.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                            "usemtl wall\nf 1 2 3\nusemtl lamp\nf 1 2 3\nusemtl wall\nf 1 2 3\n";
  const Scene scene = loadScene((dir / "lancer_lamp.obj").string());
  ASSERT_EQ(scene.size(), 3u);
  const std::vector<uint32_t> lamps = scene.emissiveTriangles();
  ASSERT_EQ(lamps.size(), 1u);
  EXPECT_EQ(scene.materials[scene.materialOf[lamps[0]]].name, "lamp");
  EXPECT_EQ(scene.materials[scene.materialOf[lamps[0]]].emission, glm::vec3(2, 3, 4));
  EXPECT_TRUE(scene.lights.empty());
  std::filesystem::remove(dir / "lancer_lamp.mtl");
  std::filesystem::remove(dir / "lancer_lamp.obj");
}

TEST(Scene, BadFilesAreClearErrors) {
  EXPECT_EQ(loadError("/nonexistent/scene.obj"), "/nonexistent/scene.obj: cannot open file");
  EXPECT_TRUE(contains(loadError(test::kAssimpModels + "/invalid/malformed.obj"),
                       "malformed.obj:23: face corner '12': vertex index 12 is out of range (8 before this line)"));
  EXPECT_TRUE(contains(loadError(test::kAssimpModels + "/invalid/empty.obj"), "empty.obj: scene has no triangles"));
  EXPECT_THROW(loadScene("builtin:nothing"), InputError);
  EXPECT_TRUE(contains(loadError(test::kAssimpModels + "/invalid/empty.ply"), "empty.ply:1: the header has no end_header"));
}

// builtin:spd-NAME@N is the SPD scene at size factor N (the triangles `lancer
// spd NAME --size-factor N` writes), named so in reports; a bad size factor is
// one line naming the scene.
TEST(Scene, BuiltinSpdScenesTakeASizeFactor) {
  const Scene tetra = loadScene("builtin:spd-tetra@3");
  EXPECT_EQ(tetra.name, "builtin:spd-tetra@3");
  const Scene generated = makeSpdScene("tetra", 3);
  ASSERT_EQ(tetra.size(), 64u);
  ASSERT_EQ(generated.size(), 64u);
  for (size_t t = 0; t < tetra.size(); ++t) {
    EXPECT_EQ(tetra.triangles[t].v0, generated.triangles[t].v0);
    EXPECT_EQ(tetra.triangles[t].v1, generated.triangles[t].v1);
    EXPECT_EQ(tetra.triangles[t].v2, generated.triangles[t].v2);
  }
  EXPECT_EQ(loadScene("builtin:spd-tetra").name, "builtin:spd-tetra");
  EXPECT_EQ(loadScene("builtin:spd-gears@1").size(), 2u + 2u * 142u + 144u * 2u);
  EXPECT_EQ(loadError("builtin:spd-tetra@11"), "builtin:spd-tetra@11: SPD tetra: size factor 11 out of range (1..10)");
  EXPECT_EQ(loadError("builtin:spd-gears@17"), "builtin:spd-gears@17: SPD gears: size factor 17 out of range (1..16)");
  for (const std::string factor : {"0", "", "x", "-2", "+3", "3.0", " 3", "3 ", "99999999999"}) {
    EXPECT_EQ(loadError("builtin:spd-tetra@" + factor),
              fmt::format("builtin:spd-tetra@{0}: the size factor '{0}' after '@' is not a whole number >= 1", factor));
  }
  EXPECT_EQ(loadError("builtin:spd-teapot@2"),
            "builtin:spd-teapot@2: unknown SPD scene 'teapot' (available: tetra, gears, balls, mount, rings, tree)");
  EXPECT_EQ(loadError("builtin:spd-balls@6"), "builtin:spd-balls@6: SPD balls: size factor 6 out of range (1..5)");
  EXPECT_EQ(loadError("builtin:spd-mount@8"), "builtin:spd-mount@8: SPD mount: size factor 8 out of range (1..7)");
}

// FNV-1a, 64 bits: a fingerprint of a whole generated file.
uint64_t fingerprint(std::string_view text) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) h = (h ^ uint8_t(c)) * 0x100000001b3ull;
  return h;
}

// The lines of NFF text that start with `key` ("s ", "c ", "p "): its entities of one kind.
size_t linesStartingWith(std::string_view text, std::string_view key) {
  size_t n = 0;
  for (size_t at = 0; at < text.size();) {
    n += text.substr(at, key.size()) == key;
    const size_t end = text.find('\n', at);
    if (end == std::string_view::npos) break;
    at = end + 1;
  }
  return n;
}

// At their default sizes, gears, balls, mount, rings and tree are the files
// the SPD's own programs write (`balls -r 1 > balls.nff`, ...), byte for byte
// after Lancer's comment line: the sizes and FNV-1a fingerprints below are
// those of the SPD programs' output (erich666/StandardProceduralDatabases,
// built and run as docs/effects.md says), and the counts those of the SPD's
// own headers.
TEST(Scene, SpdScenesAreTheSpdProgramsFiles) {
  struct Expected {
    const char* name;
    size_t bytes;
    uint64_t fingerprint;
    size_t spheres, cones, polygons;
  };
  for (const Expected& e : {Expected{"gears", 1335003, 0x7d0444781e9080a6ull, 0, 0, 9345},
                            Expected{"balls", 305317, 0x863d74a4c777c8cdull, 7381, 0, 1},
                            Expected{"mount", 632253, 0x5064e6fdcf1c1819ull, 4, 0, 8192},
                            Expected{"rings", 421988, 0x0702914ba86ab5efull, 4200, 4200, 1},
                            Expected{"tree", 475128, 0xa579f6e6fb2d5c8full, 4095, 4095, 1}}) {
    SCOPED_TRACE(e.name);
    const std::string text = generateSpdNff(e.name);
    ASSERT_TRUE(text.starts_with("# SPD "));
    const std::string_view spd = std::string_view(text).substr(text.find('\n') + 1);
    EXPECT_EQ(linesStartingWith(spd, "s "), e.spheres);
    EXPECT_EQ(linesStartingWith(spd, "c "), e.cones);
    EXPECT_EQ(linesStartingWith(spd, "p "), e.polygons);
    EXPECT_EQ(spd.size(), e.bytes);
    EXPECT_EQ(fingerprint(spd), e.fingerprint);
  }
  // The first objects, as the SPD's files have them: balls' root sphere and its
  // first child, tree's trunk, a ring's first tube.
  EXPECT_TRUE(contains(generateSpdNff("balls"), "\ns 0 0 0 0.5\ns 0.272166 0.272166 0.544331 0.166667\n"));
  EXPECT_TRUE(contains(generateSpdNff("tree"), "\nc 0 0 0 0.15 0 0 1 0.1005\ns 0 0 1 0.1005\n"));
  EXPECT_TRUE(contains(generateSpdNff("rings"), "\nc 0.930995 2.61313 0 0.07412 0.287693 1.7277 0 0.07412\n"));
}

// The curved scenes load through the NFF reader (spheres and cones
// tessellated until they are traced natively), their counts growing with the
// size factor as the SPD's headers give them.
TEST(Scene, CurvedSpdScenesLoadAtEverySize) {
  EXPECT_EQ(linesStartingWith(generateSpdNff("balls", 2), "s "), 91u);  // 1 + 9 + 81
  EXPECT_EQ(linesStartingWith(generateSpdNff("mount", 3), "p "), 128u);  // 2 * 4^3
  EXPECT_EQ(linesStartingWith(generateSpdNff("rings", 2), "c "), 30u * (1 + 4));  // 30 per ring set, (d + 1)^2 sets on layer d
  EXPECT_EQ(linesStartingWith(generateSpdNff("tree", 3), "s "), 15u);  // 2^(3 + 1) - 1
  for (const char* name : {"balls@1", "mount@2", "rings@1", "tree@2"}) {
    SCOPED_TRACE(name);
    const Scene scene = loadScene(std::string("builtin:spd-") + name);
    EXPECT_GT(scene.size(), 0u);
    EXPECT_FALSE(scene.lights.empty());
  }
}

// Lancer reads the formats whose numbers it reads correctly rounded
// (docs/scenes.md); any other extension is one line listing them. Extensions
// are read in any case.
TEST(Scene, ReadsEveryFormatAssimpImports) {
  // Through assimp: a COLLADA file (text: flagged) and an OFF file.
  EXPECT_EQ(loadScene(test::kAssimpModels + "/Collada/COLLADA.dae").numbers, SceneNumbers::AssimpText);
  EXPECT_EQ(loadScene(test::kAssimpModels + "/OFF/Cube.off").size(), 12u);
  // A format neither reads, by its extension.
  for (const std::string& file : {test::kAssimpModels + "/JT/conrod.jt", test::kAssimpModels + "/invalid/readme.txt"}) {
    const std::string error = loadError(file);
    EXPECT_TRUE(contains(error, file + ": ")) << error;
    EXPECT_TRUE(contains(error, "is not a scene format Lancer reads: OBJ (.obj, with its .mtl), PLY (.ply), STL (.stl), "
                                "glTF 2.0 (.gltf, .glb), NFF (.nff), every other format assimp 5.2 imports"))
        << error;
  }
  EXPECT_EQ(loadError("/nonexistent/scene"), "/nonexistent/scene: cannot open file");
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_upper.OBJ") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(loadScene((dir / "lancer_upper.OBJ").string()).size(), 1u);
  std::filesystem::remove(dir / "lancer_upper.OBJ");
}

// The scene files the repository's tests and scripts use load as Lancer's
// readers read them: the STL and PLY of scripts/regress among them.
TEST(Scene, LoadsTheRegressionsPlyAndStl) {
  EXPECT_EQ(loadScene(test::kAssimpModels + "/PLY/Wuson.ply").size(), 3732u);
  EXPECT_EQ(loadScene(test::kAssimpModels + "/STL/sphereWithHole.stl").size(), 285u);
  EXPECT_EQ(loadScene(test::kAssimpModels + "/OBJ/spider.obj").size(), 1368u);
}

TEST(Scene, SubdivisionKeepsSharedEdgesBitIdentical) {
  const Scene box = makeCornellBox();
  const Scene fine = subdivide(box, 2);
  EXPECT_EQ(fine.size(), box.size() * 16);
  // Every midpoint on an edge shared by two coarse triangles appears in both
  // triangles' children with the same bits: count distinct vertices per position.
  EXPECT_EQ(fine.bounds.lo, box.bounds.lo);
  EXPECT_EQ(fine.bounds.hi, box.bounds.hi);
}

}  // namespace
}  // namespace lancer
