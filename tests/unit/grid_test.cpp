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
#include "structure_test_support.h"
#include "test_paths.h"

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

// ---- Tests.

TEST(Grid, MatchesBruteForceOnCornellBox) {
  const UniformGrid grid(cornell(), {});
  EXPECT_EQ(grid.name(), "grid");
  const size_t hits = expectSameHits(grid, cornell(), RayMaker(1).random(cornell(), 20000));
  EXPECT_GT(hits, 8000u);
}

TEST(Grid, MatchesBruteForceOnBunny) {
  const UniformGrid grid(bunny(), {});
  const size_t hits = expectSameHits(grid, bunny(), RayMaker(2).random(bunny(), 5000));
  EXPECT_GT(hits, 2000u);
}

TEST(Grid, MatchesBruteForceOnWuson) {
  const UniformGrid grid(wuson(), {});
  const size_t hits = expectSameHits(grid, wuson(), RayMaker(3).random(wuson(), 5000));
  EXPECT_GT(hits, 2000u);
}

TEST(Grid, AxisParallelRaysOnVoxelBoundaries) {
  // Origins on the lattice of voxel boundary planes: outside the grid on the
  // travel axis, and at interior lattice points; plus origins on the walls'
  // planes (rays lying in a wall).
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const UniformGrid grid(*scene, scene == &cornell() ? gridOptions(12) : AccelOptions{});
    const glm::ivec3 res = grid.resolution();
    std::vector<Ray> rays;
    for (int axis = 0; axis < 3; ++axis) {
      const int p = (axis + 1) % 3, q = (axis + 2) % 3;
      const int stepP = std::max(1, res[p] / 8), stepQ = std::max(1, res[q] / 8);
      for (int i = 0; i <= res[p]; i += stepP) {
        for (int j = 0; j <= res[q]; j += stepQ) {
          glm::vec3 o;
          o[p] = voxelPlane(grid, p, i);
          o[q] = voxelPlane(grid, q, j);
          o[axis] = grid.bounds().lo[axis] - 0.25f * grid.bounds().diagonal()[axis];
          addAxisParallel(rays, o, axis);
          o[axis] = voxelPlane(grid, axis, res[axis] / 2);  // inside, on a plane too
          addAxisParallel(rays, o, axis);
        }
      }
    }
    RayMaker maker(4);
    for (int i = 0; i < 250; ++i) {
      glm::vec3 o = maker.inBox(scene->bounds);
      const int axis = i % 3;
      o[(axis + 1) % 3] =
          i % 2 ? scene->bounds.lo[(axis + 1) % 3] : scene->bounds.hi[(axis + 1) % 3];
      addAxisParallel(rays, o, axis);
    }
    const size_t hits = expectSameHits(grid, *scene, rays);
    EXPECT_GT(hits, rays.size() / 5) << scene->name;
  }
}

TEST(Grid, RaysThroughVoxelEdgesAndCorners) {
  const UniformGrid grid(cornell(), gridOptions(8));
  const glm::ivec3 res = grid.resolution();
  std::vector<Ray> rays;
  // From every lattice point on the low faces, along voxel diagonals (through
  // corners) and face diagonals (through edges), in all sign combinations.
  for (int i = 0; i <= res.x; ++i) {
    for (int j = 0; j <= res.y; ++j) {
      for (int k = 0; k <= res.z; k += res.z / 2) {
        const glm::vec3 o(voxelPlane(grid, 0, i), voxelPlane(grid, 1, j), voxelPlane(grid, 2, k));
        const glm::vec3 cell = grid.bounds().diagonal() / glm::vec3(res);
        for (int s = 0; s < 8; ++s) {
          const glm::vec3 sign(s & 4 ? -1 : 1, s & 2 ? -1 : 1, s & 1 ? -1 : 1);
          rays.push_back(Ray{o, sign * cell});
          rays.push_back(Ray{o, sign * glm::vec3(cell.x, cell.y, 0.0f)});
          rays.push_back(Ray{o, sign * glm::vec3(0.0f, cell.y, cell.z)});
          rays.push_back(Ray{o, sign * glm::vec3(cell.x, -0.0f, cell.z)});
        }
      }
    }
  }
  EXPECT_GT(expectSameHits(grid, cornell(), rays), rays.size() / 4);
}

TEST(Grid, RaysAtVerticesAndEdgeMidpoints) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const UniformGrid grid(*scene, {});
    const auto rays = verticesAndMidpoints(*scene, 600, 5);
    EXPECT_GT(expectSameHits(grid, *scene, rays), rays.size() * 9 / 10) << scene->name;
  }
}

TEST(Grid, AllEightOctants) {
  const UniformGrid grid(bunny(), {});
  RayMaker maker(6);
  for (int octant = 0; octant < 8; ++octant) {
    std::vector<Ray> rays;
    for (const Ray& r : maker.random(bunny(), 600)) {
      Ray m = r;
      for (int a = 0; a < 3; ++a)
        m.dir[a] = ((octant >> a) & 1 ? -1.0f : 1.0f) * std::abs(r.dir[a]);
      rays.push_back(m);
    }
    EXPECT_GT(expectSameHits(grid, bunny(), rays), 30u) << "octant " << octant;
  }
}

TEST(Grid, SceneFarFromTheOrigin) {
  const Scene moved = translated(bunny(), {1000.0f, -500.0f, 250.0f});
  const UniformGrid grid(moved, {});
  EXPECT_GT(expectSameHits(grid, moved, RayMaker(7).random(moved, 4000)), 1500u);
  EXPECT_GT(expectSameHits(grid, moved, verticesAndMidpoints(moved, 300, 8)), 1500u);
}

TEST(Grid, TMaxLimitsHits) {
  const UniformGrid grid(bunny(), {});
  const BruteForce brute(bunny());
  std::vector<Ray> rays;
  size_t shortened = 0;
  for (Ray r : RayMaker(9).random(bunny(), 1500)) {
    r.tMax = kInfinity;
    const auto hit = brute.intersect(r);
    if (!hit) continue;
    // At the hit, one ulp short of it, and half way. The triangle test decides
    // t <= tMax before its final division, so one ulp short may still keep the
    // hit (BruteForce agrees, which expectSameHits checks); half way may not.
    for (float tMax : {hit->t, std::nextafter(hit->t, 0.0f), 0.5f * hit->t}) {
      r.tMax = tMax;
      rays.push_back(r);
    }
    const auto half = grid.intersect(r);
    if (half) {
      EXPECT_LE(half->t, r.tMax) << describe(r);
      EXPECT_NE(half->prim, hit->prim) << describe(r);
    }
    shortened += !half;
  }
  EXPECT_GT(shortened, 250u);
  expectSameHits(grid, bunny(), rays);
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

TEST(Grid, OriginsOnBoundsFaces) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const UniformGrid grid(*scene, gridOptions(32));
    RayMaker maker(13);
    std::vector<Ray> rays;
    for (const Aabb& box : {scene->bounds, grid.bounds()}) {
      for (int i = 0; i < 1200; ++i) {
        Ray r;
        r.origin = maker.inBox(box);
        r.origin[i % 3] = (i / 3) % 2 ? box.hi[i % 3] : box.lo[i % 3];
        r.dir = i % 4 ? maker.direction()
                      : maker.pointOn(scene->triangles[maker.index(scene->size())]) - r.origin;
        rays.push_back(r);
      }
    }
    EXPECT_GT(expectSameHits(grid, *scene, rays), rays.size() / 5) << scene->name;
  }
}

TEST(Grid, RaysMissingTheScene) {
  const UniformGrid grid(bunny(), {});
  const Aabb b = bunny().bounds;
  const glm::vec3 size = b.diagonal();
  RayMaker maker(14);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    const int a = i % 3;
    r.origin = maker.inBox(grow(b, 0.5f));
    // Beside the box on axis a, moving parallel to that face or away from it.
    r.origin[a] = b.hi[a] + maker.uniform(0.01f, 1.0f) * size[a];
    r.dir = maker.direction();
    r.dir[a] = i % 2 ? std::abs(r.dir[a]) : (i % 4 ? 0.0f : -0.0f);
    rays.push_back(r);
  }
  // Rays pointing away from a box they start in front of.
  for (int i = 0; i < 500; ++i) {
    Ray r;
    r.origin = b.lo - size * maker.uniform(0.01f, 1.0f);
    r.dir = -glm::abs(maker.direction());
    rays.push_back(r);
  }
  EXPECT_EQ(expectSameHits(grid, bunny(), rays), 0u);
  for (const Ray& r : rays) EXPECT_FALSE(grid.intersect(r).has_value());
}

TEST(Grid, IntersectPAgreesWithIntersect) {
  const UniformGrid grid(wuson(), {});
  size_t hits = 0;
  for (const Ray& r : RayMaker(15).random(wuson(), 4000)) {
    const bool any = grid.intersectP(r);
    EXPECT_EQ(any, grid.intersect(r).has_value()) << describe(r);
    hits += any;
  }
  EXPECT_GT(hits, 1500u);
}

TEST(Grid, CloserTriangleInTheNextVoxelWins) {
  // A 10x10x10 grid of unit voxels (the bounds are pinned by two specks). The
  // ray runs along +x from x = 0.5. Triangle 0 is a long slanted sliver whose box
  // starts in voxel x = 1 but which the ray hits at x = 5.5; triangle 1 is a small
  // wall at x = 2.5. Stopping at the first hit found (in voxel 1) would return
  // triangle 0; the right answer is triangle 1 at t = 2.
  const Scene scene = fromTriangles({
      {{1.0f, 0.0f, 0.0f}, {10.0f, 1.0f, 0.0f}, {5.5f, 0.5f, 5.0f}},
      {{2.5f, 0.3f, 0.3f}, {2.5f, 0.7f, 0.4f}, {2.5f, 0.4f, 0.7f}},
      {{0.0f, 9.0f, 9.0f}, {0.0f, 9.0f, 9.1f}, {0.0f, 9.1f, 9.0f}},
      {{10.0f, 10.0f, 10.0f}, {10.0f, 9.9f, 10.0f}, {10.0f, 10.0f, 9.9f}},
  });
  const UniformGrid grid(scene, gridOptions(10));
  ASSERT_EQ(grid.resolution(), glm::ivec3(10));
  const Ray ray{{0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}};
  TraversalStats stats;
  const auto hit = grid.intersect(ray, &stats);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->prim, 1u);
  EXPECT_EQ(hit->t, 2.0f);
  // It stopped in voxel 2 or 3 (3 if the wall's grown box spills over), not at
  // the far end of the grid.
  EXPECT_LE(stats.nodesVisited, 4u);
  // Without the wall, the sliver is found at t = 5 after walking past it.
  Ray open = ray;
  open.origin.z = 2.0f;  // above the wall, still through the sliver
  const auto far = grid.intersect(open);
  ASSERT_TRUE(far.has_value());
  EXPECT_EQ(far->prim, 0u);
  expectSameHits(grid, scene, {ray, open});
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
  ASSERT_EQ(grid.bounds().lo, lattice.bounds().lo);
  ASSERT_EQ(grid.bounds().hi, lattice.bounds().hi);
  ASSERT_EQ(grid.resolution(), lattice.resolution());
  const auto rays = latticeRays(scene, 18);
  EXPECT_GT(expectSameHits(grid, scene, rays), rays.size() * 3 / 4);
}

TEST(Grid, VisitsOnlyTheVoxelsOnTheRay) {
  const UniformGrid grid(fromTriangles(pins()), gridOptions(10));
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

TEST(Grid, FlatAndEmptyScenes) {
  // All triangles in the plane z = 0: the box is as thin as the epsilon.
  std::vector<Triangle> tris;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const float x = float(i), y = float(j);
      tris.push_back({{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}});
      tris.push_back({{x, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
    }
  }
  const Scene flat = fromTriangles(tris);
  const UniformGrid grid(flat, {});
  EXPECT_EQ(grid.resolution().z, 1);
  RayMaker maker(16);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    r.origin = maker.inBox(Aabb{{-5, -5, -5}, {15, 15, 5}});
    r.dir = i % 2 ? maker.pointOn(tris[maker.index(tris.size())]) - r.origin : maker.direction();
    rays.push_back(r);
  }
  for (int i = 0; i <= 10; ++i) {
    addAxisParallel(rays, {float(i), -1.0f, 0.0f}, 1);  // in the plane, along a seam
    addAxisParallel(rays, {float(i), 0.5f, 1.0f}, 2);   // onto an edge
  }
  EXPECT_GT(expectSameHits(grid, flat, rays), 1000u);

  const Scene empty{};
  const UniformGrid none(empty, {});
  EXPECT_FALSE(none.intersect(Ray{}).has_value());
  EXPECT_FALSE(none.intersectP(Ray{}));
}

TEST(Grid, DegenerateRaysHitNothing) {
  const UniformGrid accel(cornell(), {});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 centre = cornell().bounds.center();
  for (const Ray& r :
       {Ray{centre, glm::vec3(0.0f)}, Ray{centre, glm::vec3(-0.0f)}, Ray{centre, {nan, 1, 0}},
        Ray{{nan, 0, 0}, {0, 1, 0}}, Ray{centre, {kInfinity, 1, 0}}, Ray{centre, {0, 1, 0}, nan}}) {
    EXPECT_FALSE(accel.intersect(r).has_value()) << describe(r);
    EXPECT_FALSE(accel.intersectP(r)) << describe(r);
  }
  // A valid ray from the same point does hit (the walls are closed above and below).
  EXPECT_TRUE(accel.intersect(Ray{centre, {0, 1, 0}}).has_value());
}

TEST(Grid, CountsStatistics) {
  const UniformGrid grid(bunny(), {});
  TraversalStats stats;
  size_t hits = 0;
  const auto rays = RayMaker(17).random(bunny(), 200);
  for (const Ray& r : rays) hits += grid.intersect(r, &stats).has_value();
  EXPECT_GT(hits, 50u);
  EXPECT_GT(stats.nodesVisited, rays.size());
  EXPECT_GT(stats.triangleTests, hits);
  // Far fewer tests than brute force, which is the point of the grid.
  EXPECT_LT(stats.triangleTests, rays.size() * bunny().size() / 20);
}

TEST(Grid, InvalidOptionsThrow) {
  for (int res : {-1, 1025, 100000}) {
    EXPECT_THROW(UniformGrid(cornell(), gridOptions(res)), InputError) << res;
  }
  try {
    UniformGrid(cornell(), gridOptions(2000));
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2000"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1..1024"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(UniformGrid(cornell(), gridOptions(1)));
}

}  // namespace
}  // namespace lancer
