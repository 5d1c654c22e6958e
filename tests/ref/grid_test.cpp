#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/brute_force.h"
#include "ref/grid.h"
#include "scene/scene.h"
#include "support/structure_test_support.h"
#include "structure_tests.h"
#include "support/test_paths.h"

namespace lancer {
namespace {
using namespace test;  // helpers from structure_test_support.h

// ---- Grid-specific helpers.

AccelOptions gridOptions(int resolution) {
  AccelOptions o;
  o.gridResolution = resolution;
  return o;
}

// The position of voxel boundary k on axis a, as the grid computes it.
float voxelPlane(const UniformGrid& grid, int a, int k) {
  const float cell = grid.bounds().diagonal()[a] / float(grid.resolution()[a]);
  return grid.bounds().lo[a] + float(k) * cell;
}

// ---- The tests every structure passes (structure_tests.h), over the grid.

struct GridTraits {
  using Accel = UniformGrid;
  static constexpr std::string_view kName = "grid";
  static constexpr StructureSeeds kSeeds{.cornell = 1, .bunny = 2, .wuson = 3, .axisParallel = 4, .vertices = 5,
                                         .octants = 6, .tMax = 9, .faces = 13, .missing = 14, .intersectP = 15,
                                         .flat = 16, .statistics = 17};
  static constexpr size_t kAxisParallelHitDivisor = 5;
  static AccelOptions axisParallelOptions(const Scene& scene) {
    return &scene == &cornell() ? gridOptions(12) : AccelOptions{};
  }
  static AccelOptions cornerOptions() { return gridOptions(8); }
  static AccelOptions facesOptions() { return gridOptions(32); }
  static AccelOptions flatOptions() { return {}; }
  // Every eighth voxel boundary (or every one), and the one half way along.
  static std::vector<float> crossPlanes(const UniformGrid& grid, int a) {
    std::vector<float> out;
    const int res = grid.resolution()[a], step = std::max(1, res / 8);
    for (int k = 0; k <= res; k += step) out.push_back(voxelPlane(grid, a, k));
    return out;
  }
  static float midPlane(const UniformGrid& grid, int a) { return voxelPlane(grid, a, grid.resolution()[a] / 2); }
  // Every lattice point on the low faces of x and y; the low, middle and high z planes.
  static std::array<std::vector<float>, 3> cornerPlanes(const UniformGrid& grid) {
    const glm::ivec3 res = grid.resolution();
    std::array<std::vector<float>, 3> out;
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k <= res[a]; k += a == 2 ? res.z / 2 : 1) out[a].push_back(voxelPlane(grid, a, k));
    }
    return out;
  }
  static glm::vec3 cornerStep(const UniformGrid& grid) { return grid.bounds().diagonal() / glm::vec3(grid.resolution()); }
  static void expectBuilt(const UniformGrid&) {}
  static void expectFlat(const UniformGrid& grid) { EXPECT_EQ(grid.resolution().z, 1); }
  static void expectEmpty(const UniformGrid&) {}
};

INSTANTIATE_TYPED_TEST_SUITE_P(Grid, Structure, GridTraits, StructureName);

// ---- The grid's own tests.

TEST(Grid, SceneFarFromTheOrigin) {
  const Scene moved = translated(bunny(), {1000.0f, -500.0f, 250.0f});
  const UniformGrid grid(moved, {});
  EXPECT_GT(expectSameHits(grid, moved, RayMaker(7).random(moved, 4000)), 1500u);
  EXPECT_GT(expectSameHits(grid, moved, verticesAndMidpoints(moved, 300, 8)), 1500u);
}

TEST(Grid, ResolutionOneAnd256) {
  for (int res : {1, 256}) {
    const UniformGrid grid(cornell(), gridOptions(res));
    EXPECT_EQ(std::max({grid.resolution().x, grid.resolution().y, grid.resolution().z}), res);
    EXPECT_GT(expectSameHits(grid, cornell(), RayMaker(10).random(cornell(), 4000)), 1500u) << res;
    EXPECT_GT(expectSameHits(grid, cornell(), verticesAndMidpoints(cornell(), 32, 11)), 150u)
        << res;
  }
  EXPECT_EQ(UniformGrid(cornell(), gridOptions(1)).resolution(), glm::ivec3(1));
}

TEST(Grid, ResolutionFollowsExtentAndHeuristic) {
  // A long thin scene: 1024 voxels along x, proportionally few across.
  std::vector<Triangle> strip;
  for (int i = 0; i < 64; ++i) {
    const float x = 16.0f * float(i);
    strip.push_back({{x, 0, 0}, {x + 16, 0, 0}, {x, 8, 4}});
  }
  const Scene thin = fromTriangles(strip);
  const UniformGrid fine(thin, gridOptions(1024));
  EXPECT_EQ(fine.resolution().x, 1024);
  EXPECT_NEAR(fine.resolution().y, 8, 1);
  EXPECT_NEAR(fine.resolution().z, 4, 1);
  EXPECT_GT(expectSameHits(fine, thin, RayMaker(12).random(thin, 2000)), 500u);

  // The heuristic: about kCellsPerTriangle voxels per triangle, near-cubic voxels.
  const UniformGrid grid(bunny(), {});
  const glm::ivec3 res = grid.resolution();
  const double cells = double(res.x) * res.y * res.z;
  const double target = UniformGrid::kCellsPerTriangle * double(bunny().size());
  EXPECT_GT(cells, 0.5 * target);
  EXPECT_LT(cells, 2.0 * target);
  const glm::vec3 voxel = grid.bounds().diagonal() / glm::vec3(res);
  EXPECT_LT(std::max({voxel.x, voxel.y, voxel.z}) / std::min({voxel.x, voxel.y, voxel.z}), 1.5f);
}

TEST(Grid, CloserTriangleInTheNextVoxelWins) {
  // A 10x10x10 grid of unit voxels (the bounds are pinned by two specks). The
  // ray runs along +x from x = 0.5. Triangle 0 is a long slanted sliver whose box
  // starts in voxel x = 1 but which the ray hits at x = 5.5; triangle 1 is a small
  // wall at x = 2.5. Stopping at the first hit found (in voxel 1) would return
  // triangle 0; the right answer is triangle 1 at t = 2.
  const Scene scene = closerTriangleScene(10.0f);
  const UniformGrid grid(scene, gridOptions(10));
  ASSERT_EQ(grid.resolution(), glm::ivec3(10));
  // It stops in voxel 2 or 3 (3 if the wall's grown box spills over), not at
  // the far end of the grid; without the wall, the sliver is found at t = 5
  // after walking past it.
  expectCloserTriangleInALaterCellWins(grid, scene, 4);
}

TEST(Grid, TrianglesOnVoxelBoundaries) {
  const Scene pinned = fromTriangles(pins());
  const UniformGrid lattice(pinned, gridOptions(10));
  std::array<std::vector<float>, 3> planes;
  for (int a = 0; a < 3; ++a) {
    for (int k = 1; k < 10; ++k) planes[a].push_back(voxelPlane(lattice, a, k));
  }
  const Scene scene = latticeScene(planes);
  const UniformGrid grid(scene, gridOptions(10));
  ASSERT_EQ(grid.resolution(), lattice.resolution());
  expectLatticeSceneMatches(grid, lattice, scene, 18);
}

TEST(Grid, VisitsOnlyTheVoxelsOnTheRay) {
  const Scene scene = fromTriangles(pins());
  const UniformGrid grid(scene, gridOptions(10));
  const float centre = voxelPlane(grid, 1, 3) + 1.0f;  // inside voxel row 3
  TraversalStats stats;
  // Along x through a row of voxels: exactly the ten voxels of that row.
  EXPECT_FALSE(grid.intersect(Ray{{-5.0f, centre, centre}, {1, 0, 0}}, &stats).has_value());
  EXPECT_EQ(stats.nodesVisited, 10u);
  // The same ray stopped by tMax inside the second voxel: two voxels.
  stats = {};
  grid.intersect(Ray{{-5.0f, centre, centre}, {1, 0, 0}, 5.0f + voxelPlane(grid, 0, 1) + 1.0f},
                 &stats);
  EXPECT_EQ(stats.nodesVisited, 2u);
  // tMax a hair past the first boundary still reaches the second voxel; a hair
  // before it does not; before the box, nothing is visited.
  for (auto [tMax, voxels] :
       {std::pair{std::nextafter(5.0f + voxelPlane(grid, 0, 1), kInfinity), 2u},
        std::pair{std::nextafter(5.0f + voxelPlane(grid, 0, 1), 0.0f), 1u}, std::pair{4.0f, 0u}}) {
    stats = {};
    grid.intersect(Ray{{-5.0f, centre, centre}, {1, 0, 0}, tMax}, &stats);
    EXPECT_EQ(stats.nodesVisited, voxels) << tMax;
  }
  // A diagonal in the plane z = centre crossing x and y boundaries at distinct t:
  // one voxel plus one per boundary crossed.
  stats = {};
  const glm::vec3 o(voxelPlane(grid, 0, 0) + 1.0f, voxelPlane(grid, 1, 0) + 3.0f, centre);
  grid.intersect(Ray{o, {1.0f, 0.5f, -0.0f}}, &stats);
  const glm::vec3 exit = o + (grid.bounds().hi.x - o.x) * glm::vec3(1.0f, 0.5f, 0.0f);
  const int crossed = 9 + int((exit.y - grid.bounds().lo.y) / (grid.bounds().diagonal().y / 10));
  EXPECT_EQ(stats.nodesVisited, uint64_t(1 + crossed));
}

TEST(Grid, InvalidOptionsThrow) {
  for (int res : {-1, 1025, 100000}) {
    EXPECT_THROW(UniformGrid(cornell(), gridOptions(res)), InputError) << res;
  }
  expectInputErrorMentioning([] { UniformGrid(cornell(), gridOptions(2000)); }, {"2000", "1..1024"});
  EXPECT_NO_THROW(UniformGrid(cornell(), gridOptions(1)));
}

}  // namespace
}  // namespace lancer
