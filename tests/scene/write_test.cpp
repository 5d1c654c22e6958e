// lancer convert's writers (scene/write.h): what they write reads back as the
// same floats, bit for bit, in the same order.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <filesystem>
#include <limits>
#include <set>
#include <utility>
#include <string>

#include "common/error.h"
#include "scene/scene.h"
#include "scene/write.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

using test::kAssimpModels;

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          (std::string("lancer_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name))
      .string();
}

bool sameBits(const glm::vec3& a, const glm::vec3& b) {
  return std::bit_cast<uint32_t>(a.x) == std::bit_cast<uint32_t>(b.x) &&
         std::bit_cast<uint32_t>(a.y) == std::bit_cast<uint32_t>(b.y) &&
         std::bit_cast<uint32_t>(a.z) == std::bit_cast<uint32_t>(b.z);
}

// Writes `scene` in every format and reads it back: the same triangles, bit
// for bit and in order; OBJ and glTF keep each triangle's material and the
// materials' colours; glTF keeps the lights.
void expectRoundTrip(const Scene& scene, const std::string& label) {
  for (const char* extension : {".obj", ".ply", ".glb"}) {
    const std::string path = temp(label + extension);
    writeScene(scene, path);
    const Scene back = loadScene(path);
    ASSERT_EQ(back.size(), scene.size()) << label << extension;
    size_t differ = 0;
    for (size_t t = 0; t < scene.size(); ++t) {
      const Triangle &a = scene.triangles[t], &b = back.triangles[t];
      if (!sameBits(a.v0, b.v0) || !sameBits(a.v1, b.v1) || !sameBits(a.v2, b.v2)) {
        if (++differ == 1) ADD_FAILURE() << label << extension << ": triangle " << t << " differs";
      }
    }
    EXPECT_EQ(differ, 0u) << label << extension;
    if (std::string(extension) == ".ply") continue;  // PLY has no materials
    // Each triangle's material, by what it holds (readers number materials
    // their own way: OBJ's default comes first, assimp adds its own last).
    std::set<std::pair<uint32_t, uint32_t>> pairs;
    for (size_t t = 0; t < scene.size(); ++t) pairs.insert({scene.materialOf[t], back.materialOf[t]});
    for (const auto& [ours, theirs] : pairs) {
      const Material &a = scene.materials[ours], &b = back.materials[theirs];
      const std::string where = label + extension + " material '" + a.name + "'";
      EXPECT_EQ(b.diffuse, a.diffuse) << where;
      EXPECT_NEAR(b.emission.r, a.emission.r, 1e-6f * std::max(1.0f, a.emission.r)) << where;
      // glTF cannot say "mirror and transmit" but as a smooth dielectric's F0:
      // a transmitting material keeps its transmission.
      if (a.transmittance == 0.0f || std::string(extension) == ".obj") {
        EXPECT_EQ(b.ks > 0.0f, a.ks > 0.0f) << where;
      }
      EXPECT_EQ(b.transmittance > 0.0f, a.transmittance > 0.0f) << where;
      if (std::string(extension) == ".obj") {
        // Its own name, when no other material has it (else m<index>).
        const auto same = std::count_if(scene.materials.begin(), scene.materials.end(),
                                        [&](const Material& other) { return other.name == a.name; });
        if (same == 1 && !a.name.empty()) {
          EXPECT_EQ(b.name, a.name) << where;
        }
        EXPECT_EQ(b.emission, a.emission) << where;
        EXPECT_EQ(b.ks, a.ks) << where;
        EXPECT_EQ(b.shine, a.shine) << where;
        EXPECT_EQ(b.ior, a.ior) << where;
      }
    }
    if (std::string(extension) == ".obj") continue;  // OBJ has no lights
    ASSERT_EQ(back.lights.size(), scene.lights.size()) << label;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
      EXPECT_EQ(back.lights[l].kind, scene.lights[l].kind) << label << " light " << l;
      EXPECT_EQ(back.lights[l].name, scene.lights[l].name) << label << " light " << l;
      if (scene.lights[l].kind != Light::Kind::Directional) {
        EXPECT_EQ(back.lights[l].position, scene.lights[l].position) << label << " light " << l;
      }
      EXPECT_EQ(back.lights[l].color, scene.lights[l].color) << label << " light " << l;
    }
  }
}

TEST(Write, CornellBoxRoundTrips) { expectRoundTrip(makeCornellBox(), "cornell"); }

TEST(Write, CorpusScenesRoundTrip) {
  for (const char* file : {"glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "BLEND/box.blend",
                           "Collada/duck.dae", "STL/Spider_binary.stl", "OBJ/spider.obj", "FBX/phong_cube.fbx"}) {
    expectRoundTrip(loadScene(kAssimpModels + "/" + file), std::filesystem::path(file).stem().string());
  }
}

// The floats that are hardest to print and read: signed zeros (kept apart),
// the smallest subnormal, the largest float, and decimals that are not floats.
TEST(Write, HardFloatsRoundTrip) {
  Scene scene;
  scene.name = "hard floats";
  const float tiny = std::numeric_limits<float>::denorm_min(), huge = std::numeric_limits<float>::max();
  scene.triangles = {{{-0.0f, 0.0f, 0.1f}, {tiny, -tiny, 1.0f / 3.0f}, {huge, -huge, 16777217.0f}},
                     {{0.0f, -0.0f, 0.1f}, {1e-38f, 3.4e38f, 0.7f}, {-1e-45f, 2.5f, 1.00000012f}}};
  scene.materials = {Material{"a"}};
  scene.materialOf = {0, 0};
  scene.computeBounds();
  expectRoundTrip(scene, "hard");
}

TEST(Write, AnUnknownFormatOrAnUnwritablePathIsAnError) {
  const Scene scene = makeCube();
  try {
    writeScene(scene, temp("x.stl"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.stl: '.stl' is not a format Lancer writes"), std::string::npos) << e.what();
  }
  try {
    writeScene(scene, "/nonexistent/dir/x.ply");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/dir/x.ply: cannot write file");
  }
}

}  // namespace
}  // namespace lancer
