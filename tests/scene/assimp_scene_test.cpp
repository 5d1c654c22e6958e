// The formats read through assimp (scene/assimp_scene.h): which numbers each
// is flagged with, its lights and materials, and its errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.h"
#include "scene/assimp_scene.h"
#include "scene/scene.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

using test::kAssimpModels;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Binary formats are exact, text formats assimp's, a format with both forms
// by its first bytes; Lancer's own formats are not assimp's business.
TEST(AssimpScene, FormatsAreFlaggedByHowTheyStoreNumbers) {
  const std::string m = kAssimpModels + "/";
  EXPECT_EQ(assimpSceneNumbers(m + "BLEND/box.blend"), SceneNumbers::Exact);
  EXPECT_EQ(assimpSceneNumbers(m + "3DS/fels.3ds"), SceneNumbers::Exact);
  EXPECT_EQ(assimpSceneNumbers(m + "Collada/duck.dae"), SceneNumbers::AssimpText);
  EXPECT_EQ(assimpSceneNumbers(m + "IFC/AC14-FZK-Haus.ifc"), SceneNumbers::AssimpText);
  EXPECT_EQ(assimpSceneNumbers(m + "FBX/box.fbx"), SceneNumbers::Exact);                         // Kaydara FBX Binary
  EXPECT_EQ(assimpSceneNumbers(m + "FBX/cubes_with_names.fbx"), SceneNumbers::AssimpText);       // ; FBX 7.5.0 project
  EXPECT_EQ(assimpSceneNumbers(m + "X/test_cube_binary.x"), SceneNumbers::Exact);                // xof 0303bin
  EXPECT_EQ(assimpSceneNumbers(m + "X/test_cube_text.x"), SceneNumbers::AssimpText);             // xof 0303txt
  EXPECT_EQ(assimpSceneNumbers(m + "COB/dwarf.cob"), SceneNumbers::Exact);                       // Caligari ...BLH
  EXPECT_EQ(assimpSceneNumbers(m + "COB/dwarf_ascii.cob"), SceneNumbers::AssimpText);            // Caligari ...ALH
  EXPECT_EQ(assimpSceneNumbers("scene.jt"), std::nullopt);
  EXPECT_EQ(toString(SceneNumbers::Exact), std::string("exact"));
  EXPECT_EQ(toString(SceneNumbers::CorrectlyRounded), std::string("correctly_rounded"));
  EXPECT_EQ(toString(SceneNumbers::AssimpText), std::string("assimp_text"));
  // Lancer's readers say which they were.
  EXPECT_EQ(loadScene(m + "OBJ/box.obj").numbers, SceneNumbers::CorrectlyRounded);
  EXPECT_EQ(loadScene(m + "STL/Spider_binary.stl").numbers, SceneNumbers::Exact);
  EXPECT_EQ(loadScene(m + "STL/Spider_ascii.stl").numbers, SceneNumbers::CorrectlyRounded);
  EXPECT_EQ(loadScene(kDefaultSceneName).numbers, SceneNumbers::CorrectlyRounded);
}

// A Blender file: exact, no warning, its lamp where Blender's default scene
// puts it (4.07625, 1.00545, 5.90386), its cube's 12 triangles.
TEST(AssimpScene, BlendIsExactWithItsLamp) {
  const Scene scene = loadScene(kAssimpModels + "/BLEND/BlenderDefault_276.blend");
  EXPECT_EQ(scene.numbers, SceneNumbers::Exact);
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_EQ(scene.size(), 12u);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].name, "Lamp");
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::Point);
  EXPECT_NEAR(scene.lights[0].position.x, 4.07625f, 1e-5f);
  EXPECT_NEAR(scene.lights[0].position.y, 1.00545f, 1e-5f);
  EXPECT_NEAR(scene.lights[0].position.z, 5.90386f, 1e-5f);
}

// A COLLADA file: assimp's text, one warning naming the file, and each kind of
// light at its node (a point lamp, a directional sun, a spot with its cone;
// assimp reads Blender's area lamp as a point).
TEST(AssimpScene, ColladaIsAssimpTextWithAWarningAndItsLights) {
  const std::string path = kAssimpModels + "/Collada/lights.dae";
  const Scene scene = loadScene(path);
  EXPECT_EQ(scene.numbers, SceneNumbers::AssimpText);
  // The text warning, and the hemisphere light Lancer does not trace.
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_TRUE(contains(scene.warnings[0], path) && contains(scene.warnings[0], "may be a float off"))
      << scene.warnings[0];
  EXPECT_TRUE(contains(scene.warnings[1], "light 'Hemi'")) << scene.warnings[1];
  ASSERT_EQ(scene.lights.size(), 4u);
  EXPECT_EQ(scene.lights[0].name, "Lamp");
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::Point);
  EXPECT_EQ(scene.lights[1].name, "Sun");
  EXPECT_EQ(scene.lights[1].kind, Light::Kind::Directional);
  EXPECT_NEAR(glm::length(scene.lights[1].direction), 1.0f, 1e-6f);
  EXPECT_EQ(scene.lights[2].name, "Spot");
  EXPECT_EQ(scene.lights[2].kind, Light::Kind::Spot);
  EXPECT_GE(scene.lights[2].innerConeCos, scene.lights[2].outerConeCos);
  EXPECT_GE(scene.lights[2].outerConeCos, 0.0f);
}

// Materials: a 3DS file's alpha transmits, an FBX's Phong material reflects,
// transmits and emits, and every term is in range.
TEST(AssimpScene, MaterialsComeThroughAsWhittedTerms) {
  const Scene alpha = loadScene(kAssimpModels + "/3DS/cubes_with_alpha.3DS");
  EXPECT_TRUE(std::any_of(alpha.materials.begin(), alpha.materials.end(),
                          [](const Material& m) { return m.transmittance > 0.0f && m.kd < 1.0f; }));
  const Scene phong = loadScene(kAssimpModels + "/FBX/phong_cube.fbx");
  ASSERT_EQ(phong.materials.size(), 1u);
  const Material& m = phong.materials[0];
  EXPECT_GT(m.ks, 0.0f);
  EXPECT_GT(m.transmittance, 0.0f);
  EXPECT_EQ(phong.emissiveTriangles().size(), phong.size());
  for (const Scene* scene : {&alpha, &phong}) {
    for (const Material& material : scene->materials) {
      EXPECT_GE(material.kd, 0.0f);
      EXPECT_LE(material.ks + material.transmittance, 1.0f + 1e-6f) << material.name;
      EXPECT_GT(material.ior, 0.0f);
    }
  }
}

// A malformed file in a format read through assimp: one line naming the file
// and assimp's reason.
TEST(AssimpScene, MalformedFilesNameTheFileAndAssimpsReason) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto write = [&](const char* name, const std::string& bytes) {
    const std::string path = (dir / (std::string("lancer_AssimpScene_") + name)).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  for (const std::string& path : {write("cut.blend", "BLENDER-v276 and then nothing"),
                                  write("cut.dae", "<?xml version=\"1.0\"?><COLLADA><library_geometries>"),
                                  write("empty.3ds", "")}) {
    try {
      loadScene(path);
      ADD_FAILURE() << path << ": expected an InputError";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.starts_with(path + ": ")) << what;
      EXPECT_TRUE(contains(what, "cannot read scene: ") || contains(what, "scene has no triangles")) << what;
      EXPECT_FALSE(contains(what, "\n")) << what;
    }
  }
  try {
    loadScene((dir / "lancer_AssimpScene_missing.fbx").string());
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "missing.fbx: cannot open file")) << e.what();
  }
}

// glTF 1.0 is assimp's (Lancer reads glTF 2.0); the version is read from the file.
TEST(AssimpScene, GltfOneGoesThroughAssimp) {
  const Scene scene = loadScene(kAssimpModels + "/glTF/TwoBoxes/TwoBoxes.gltf");
  EXPECT_EQ(scene.numbers, SceneNumbers::AssimpText);
  EXPECT_GT(scene.size(), 0u);
}

}  // namespace
}  // namespace lancer
