#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "scene/scene.h"
#include "test_paths.h"

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
      EXPECT_NE(std::string(e.what()).find("lancer_bad_terms.obj: material 'm': " + std::string(needle)),
                std::string::npos)
          << e.what();
    }
  }
  std::filesystem::remove(dir / "lancer_bad_terms.mtl");
  std::filesystem::remove(dir / "lancer_bad_terms.obj");
}

// Found by tests/fuzz/fuzz_mtl: these 8 bytes as an MTL file crash assimp 5.2
// (SIGSEGV in its MTL parser). OBJ and MTL files with a NUL byte are refused.
TEST(Scene, ObjOrMtlWithANulByteIsAnErrorNotACrash) {
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "lancer_nul.obj") << "mtllib lancer_nul.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
  std::ofstream(dir / "lancer_nul.mtl", std::ios::binary) << std::string("\x01\0a\0< 1<", 8);
  try {
    loadScene((dir / "lancer_nul.obj").string());
    ADD_FAILURE() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lancer_nul.mtl has a NUL byte"), std::string::npos) << e.what();
  }
  std::filesystem::remove(dir / "lancer_nul.mtl");
  std::filesystem::remove(dir / "lancer_nul.obj");
}

TEST(Scene, BadFilesAreClearErrors) {
  EXPECT_THROW(loadScene("/nonexistent/scene.obj"), InputError);
  EXPECT_THROW(loadScene(test::kAssimpModels + "/invalid/malformed.obj"), InputError);
  EXPECT_THROW(loadScene(test::kAssimpModels + "/invalid/empty.obj"), InputError);
  EXPECT_THROW(loadScene("builtin:nothing"), InputError);
  try {
    loadScene(test::kAssimpModels + "/invalid/empty.ply");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("empty.ply"), std::string::npos) << e.what();
  }
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
