#pragma once

// The tests every reference structure (sw/ref: UniformGrid, Octree) must pass,
// written once as a GoogleTest type-parameterized suite over a structure's test
// traits. Each structure's test file defines its traits and instantiates the
// suite (INSTANTIATE_TYPED_TEST_SUITE_P(Grid, Structure, ...)), beside the tests
// that are its own (the DDA's voxel counts, the octree's child order, options).
//
// A traits class T provides:
//   using Accel = ...;                        the structure under test
//   static constexpr std::string_view kName;  Accel::name()
//   static constexpr StructureSeeds kSeeds;   the seed of each test's rays
//   static constexpr size_t kAxisParallelHitDivisor;  at least size / this rays hit
//   static AccelOptions axisParallelOptions(const Scene&);  the build for each test
//   static AccelOptions cornerOptions();      (on the Cornell box)
//   static AccelOptions facesOptions();
//   static AccelOptions flatOptions();
//   static std::vector<float> crossPlanes(const Accel&, int axis);  cell boundaries
//                                             on an axis the axis-parallel rays start on
//   static float midPlane(const Accel&, int axis);  an interior boundary plane
//   static std::array<std::vector<float>, 3> cornerPlanes(const Accel&);  the lattice of
//                                             cell corners the corner rays start from
//   static glm::vec3 cornerStep(const Accel&);  a cell's diagonal, for those rays
//   static void expectBuilt(const Accel&);    extra checks of the default Cornell build
//   static void expectFlat(const Accel&);     of the build over a flat scene
//   static void expectEmpty(const Accel&);    of the build over no triangles

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "ref/accel.h"
#include "ref/brute_force.h"
#include "scene/scene.h"
#include "support/structure_test_support.h"

namespace lancer::test {

// The seed of the rays of each shared test (each structure keeps its own, so
// its cases stay what they were when it had the test to itself).
struct StructureSeeds {
  uint32_t cornell, bunny, wuson, axisParallel, vertices, octants, tMax, faces, missing, intersectP, flat,
      statistics;
};

template <class T>
class Structure : public ::testing::Test {};

TYPED_TEST_SUITE_P(Structure);

TYPED_TEST_P(Structure, MatchesBruteForceOnCornellBox) {
  const typename TypeParam::Accel accel(cornell(), {});
  EXPECT_EQ(accel.name(), TypeParam::kName);
  TypeParam::expectBuilt(accel);
  const size_t hits =
      expectSameHits(accel, cornell(), RayMaker(TypeParam::kSeeds.cornell).random(cornell(), 20000));
  EXPECT_GT(hits, 8000u);
}

TYPED_TEST_P(Structure, MatchesBruteForceOnBunny) {
  const typename TypeParam::Accel accel(bunny(), {});
  const size_t hits = expectSameHits(accel, bunny(), RayMaker(TypeParam::kSeeds.bunny).random(bunny(), 5000));
  EXPECT_GT(hits, 2000u);
}

TYPED_TEST_P(Structure, MatchesBruteForceOnWuson) {
  const typename TypeParam::Accel accel(wuson(), {});
  const size_t hits = expectSameHits(accel, wuson(), RayMaker(TypeParam::kSeeds.wuson).random(wuson(), 5000));
  EXPECT_GT(hits, 2000u);
}

TYPED_TEST_P(Structure, AxisParallelRaysOnCellBoundaries) {
  // Origins where the cell boundary planes of the other two axes cross: outside
  // the box on the travel axis, and on an interior boundary plane of it, with +0
  // and -0 zero components; plus origins on the walls' planes (rays lying in a
  // wall).
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const typename TypeParam::Accel accel(*scene, TypeParam::axisParallelOptions(*scene));
    std::vector<Ray> rays;
    for (int axis = 0; axis < 3; ++axis) {
      const int p = (axis + 1) % 3, q = (axis + 2) % 3;
      for (float x : TypeParam::crossPlanes(accel, p)) {
        for (float y : TypeParam::crossPlanes(accel, q)) {
          glm::vec3 o;
          o[p] = x;
          o[q] = y;
          o[axis] = accel.bounds().lo[axis] - 0.25f * accel.bounds().diagonal()[axis];
          addAxisParallel(rays, o, axis);
          o[axis] = TypeParam::midPlane(accel, axis);  // inside, on a plane too
          addAxisParallel(rays, o, axis);
        }
      }
    }
    RayMaker maker(TypeParam::kSeeds.axisParallel);
    for (int i = 0; i < 250; ++i) {
      glm::vec3 o = maker.inBox(scene->bounds);
      const int axis = i % 3;
      o[(axis + 1) % 3] =
          i % 2 ? scene->bounds.lo[(axis + 1) % 3] : scene->bounds.hi[(axis + 1) % 3];
      addAxisParallel(rays, o, axis);
    }
    EXPECT_GT(expectSameHits(accel, *scene, rays), rays.size() / TypeParam::kAxisParallelHitDivisor)
        << scene->name;
  }
}

TYPED_TEST_P(Structure, RaysThroughCellEdgesAndCorners) {
  // From every point of a lattice of cell corners, along cell diagonals (through
  // corners) and face diagonals (through edges), in all sign combinations.
  const typename TypeParam::Accel accel(cornell(), TypeParam::cornerOptions());
  const std::array<std::vector<float>, 3> planes = TypeParam::cornerPlanes(accel);
  const glm::vec3 cell = TypeParam::cornerStep(accel);
  std::vector<Ray> rays;
  for (float x : planes[0]) {
    for (float y : planes[1]) {
      for (float z : planes[2]) {
        const glm::vec3 o(x, y, z);
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
  EXPECT_GT(expectSameHits(accel, cornell(), rays), rays.size() / 4);
}

TYPED_TEST_P(Structure, RaysAtVerticesAndEdgeMidpoints) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const typename TypeParam::Accel accel(*scene, {});
    const auto rays = verticesAndMidpoints(*scene, 600, TypeParam::kSeeds.vertices);
    EXPECT_GT(expectSameHits(accel, *scene, rays), rays.size() * 9 / 10) << scene->name;
  }
}

TYPED_TEST_P(Structure, AllEightOctants) {
  const typename TypeParam::Accel accel(bunny(), {});
  RayMaker maker(TypeParam::kSeeds.octants);
  for (int octant = 0; octant < 8; ++octant) {
    std::vector<Ray> rays;
    for (const Ray& r : maker.random(bunny(), 600)) {
      Ray m = r;
      for (int a = 0; a < 3; ++a)
        m.dir[a] = ((octant >> a) & 1 ? -1.0f : 1.0f) * std::abs(r.dir[a]);
      rays.push_back(m);
    }
    EXPECT_GT(expectSameHits(accel, bunny(), rays), 30u) << "octant " << octant;
  }
}

TYPED_TEST_P(Structure, TMaxLimitsHits) {
  const typename TypeParam::Accel accel(bunny(), {});
  const BruteForce brute(bunny());
  std::vector<Ray> rays;
  size_t shortened = 0;
  for (Ray r : RayMaker(TypeParam::kSeeds.tMax).random(bunny(), 1500)) {
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
    const auto half = accel.intersect(r);
    if (half) {
      EXPECT_LE(half->t, r.tMax) << describe(r);
      EXPECT_NE(half->prim, hit->prim) << describe(r);
    }
    shortened += !half;
  }
  EXPECT_GT(shortened, 250u);
  expectSameHits(accel, bunny(), rays);
}

TYPED_TEST_P(Structure, OriginsOnBoundsFaces) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const typename TypeParam::Accel accel(*scene, TypeParam::facesOptions());
    RayMaker maker(TypeParam::kSeeds.faces);
    std::vector<Ray> rays;
    for (const Aabb& box : {scene->bounds, accel.bounds()}) {
      for (int i = 0; i < 1200; ++i) {
        Ray r;
        r.origin = maker.inBox(box);
        r.origin[i % 3] = (i / 3) % 2 ? box.hi[i % 3] : box.lo[i % 3];
        r.dir = i % 4 ? maker.direction()
                      : maker.pointOn(scene->triangles[maker.index(scene->size())]) - r.origin;
        rays.push_back(r);
      }
    }
    EXPECT_GT(expectSameHits(accel, *scene, rays), rays.size() / 5) << scene->name;
  }
}

TYPED_TEST_P(Structure, RaysMissingTheScene) {
  const typename TypeParam::Accel accel(bunny(), {});
  const Aabb b = bunny().bounds;
  const glm::vec3 size = b.diagonal();
  RayMaker maker(TypeParam::kSeeds.missing);
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
  EXPECT_EQ(expectSameHits(accel, bunny(), rays), 0u);
  TraversalStats stats;
  for (const Ray& r : rays) EXPECT_FALSE(accel.intersect(r, &stats).has_value());
  EXPECT_EQ(stats.triangleTests, 0u);  // rejected at the structure's box
}

TYPED_TEST_P(Structure, IntersectPAgreesWithIntersect) {
  const typename TypeParam::Accel accel(wuson(), {});
  size_t hits = 0;
  for (const Ray& r : RayMaker(TypeParam::kSeeds.intersectP).random(wuson(), 4000)) {
    const bool any = accel.intersectP(r);
    EXPECT_EQ(any, accel.intersect(r).has_value()) << describe(r);
    hits += any;
  }
  EXPECT_GT(hits, 1500u);
}

TYPED_TEST_P(Structure, FlatAndEmptyScenes) {
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
  const typename TypeParam::Accel accel(flat, TypeParam::flatOptions());
  TypeParam::expectFlat(accel);
  RayMaker maker(TypeParam::kSeeds.flat);
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
  EXPECT_GT(expectSameHits(accel, flat, rays), 1000u);

  const Scene empty{};
  const typename TypeParam::Accel none(empty, {});
  TypeParam::expectEmpty(none);
  EXPECT_FALSE(none.intersect(Ray{}).has_value());
  EXPECT_FALSE(none.intersectP(Ray{}));
}

TYPED_TEST_P(Structure, DegenerateRaysHitNothing) {
  const typename TypeParam::Accel accel(cornell(), {});
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

TYPED_TEST_P(Structure, CountsStatistics) {
  const typename TypeParam::Accel accel(bunny(), {});
  TraversalStats stats;
  size_t hits = 0;
  const auto rays = RayMaker(TypeParam::kSeeds.statistics).random(bunny(), 200);
  for (const Ray& r : rays) hits += accel.intersect(r, &stats).has_value();
  EXPECT_GT(hits, 50u);
  EXPECT_GT(stats.nodesVisited, rays.size());
  EXPECT_GT(stats.triangleTests, hits);
  // Far fewer tests than brute force, which is the point of the structure.
  EXPECT_LT(stats.triangleTests, rays.size() * bunny().size() / 20);
}

REGISTER_TYPED_TEST_SUITE_P(Structure, MatchesBruteForceOnCornellBox, MatchesBruteForceOnBunny,
                            MatchesBruteForceOnWuson, AxisParallelRaysOnCellBoundaries,
                            RaysThroughCellEdgesAndCorners, RaysAtVerticesAndEdgeMidpoints, AllEightOctants,
                            TMaxLimitsHits, OriginsOnBoundsFaces, RaysMissingTheScene,
                            IntersectPAgreesWithIntersect, FlatAndEmptyScenes, DegenerateRaysHitNothing,
                            CountsStatistics);

// The name of an instantiation's one type, for the test names
// (Grid/Structure/grid.MatchesBruteForceOnBunny).
struct StructureName {
  template <class T>
  static std::string GetName(int) {
    return std::string(T::kName);
  }
};

}  // namespace lancer::test
