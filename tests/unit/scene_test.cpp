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
