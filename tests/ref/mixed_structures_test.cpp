// The float structures over native quadrics (issue #40): the grid, the octree
// and the BVH built over triangles, spheres and cones in one id space, each
// against brute force bit for bit on random mixed scenes (support/mixed_scenes.h)
// and on hand-made cases (a scene of quadrics only, exact ties, a quadric
// spanning many cells); the BVH's leaves list quadric ids, so the driver's
// candidates (bvhCandidates, exactCandidates) hold every hit primitive.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <vector>

#include "driver/candidates.h"
#include "ref/brute_force.h"
#include "ref/bvh.h"
#include "ref/grid.h"
#include "ref/octree.h"
#include "ref/primitive.h"
#include "support/mixed_scenes.h"
#include "support/structure_test_support.h"

namespace lancer {
namespace {

using test::expectSameHits;
using test::mixedScene;
using test::RandomScenes;

// Every float structure, at its defaults and at builds that stress the binning
// of large boxes (a fine grid, a deep octree with one-primitive leaves, BVH
// leaves of 1 and 16).
std::vector<std::unique_ptr<Accel>> structures(const Scene& scene) {
  std::vector<std::unique_ptr<Accel>> out;
  AccelOptions fine;
  fine.gridResolution = 64;
  fine.octreeMaxDepth = 8;
  fine.octreeLeafSize = 1;
  AccelOptions leaf1, leaf16;
  leaf1.bvhLeafSize = 1;
  leaf16.bvhLeafSize = 16;
  out.push_back(std::make_unique<UniformGrid>(scene, AccelOptions{}));
  out.push_back(std::make_unique<UniformGrid>(scene, fine));
  out.push_back(std::make_unique<Octree>(scene, AccelOptions{}));
  out.push_back(std::make_unique<Octree>(scene, fine));
  out.push_back(std::make_unique<Bvh>(scene, AccelOptions{}));
  out.push_back(std::make_unique<Bvh>(scene, leaf1));
  out.push_back(std::make_unique<Bvh>(scene, leaf16));
  return out;
}

TEST(MixedStructures, EveryStructureMatchesBruteForceOnRandomMixedScenes) {
  RandomScenes random;
  random.rng.seed(4042);
  size_t total = 0, hits = 0, quadricHits = 0;
  for (int s = 0; s < 8; ++s) {
    // One scene of quadrics only, the others mixed; more primitives than the
    // exact arbiter's tests use, so the structures have depth.
    const Scene scene = random.scene(s == 0 ? 0 : 40, 40);
    std::vector<Ray> rays;
    for (int k = 0; k < 1500; ++k) rays.push_back(random.ray(scene));
    const BruteForce brute(scene);
    for (const Ray& ray : rays) {
      const auto hit = brute.intersect(ray);
      hits += hit.has_value();
      quadricHits += hit && scene.isQuadric(hit->prim);
    }
    total += rays.size();
    for (const auto& accel : structures(scene)) {
      SCOPED_TRACE(testing::Message() << "scene " << s << ", " << accel->name());
      expectSameHits(*accel, scene, rays);
    }
  }
  EXPECT_GT(hits, total / 2);
  EXPECT_GT(quadricHits, total / 5);
}

TEST(MixedStructures, AxisParallelRaysThroughQuadrics) {
  RandomScenes random;
  random.rng.seed(4043);
  const Scene scene = random.scene(20, 30);
  test::RayMaker maker(4044);
  std::vector<Ray> rays;
  for (int i = 0; i < 600; ++i) {
    // Through a random quadric's box, so most of them meet something.
    const Aabb box = scene.quadrics[size_t(i) % scene.quadrics.size()].bounds();
    test::addAxisParallel(rays, maker.inBox(test::grow(box, 0.5f)), i % 3);
  }
  for (const auto& accel : structures(scene)) {
    SCOPED_TRACE(accel->name());
    EXPECT_GT(expectSameHits(*accel, scene, rays), rays.size() / 4);
  }
}

TEST(MixedStructures, ExactTiesGoToTheLowestIdAndBigQuadricsSpanCells) {
  // Two equal spheres (ids 2 and 3: the tie to 2), a triangle through the
  // spheres' nearest point (id 1 at t = 4: the tie to the triangle), a speck
  // pinning the box, and a cylinder as long as the scene, in every cell
  // along its axis.
  const std::vector<Triangle> tris = {{{-50, -50, -50}, {-49.5f, -50, -50}, {-50, -49.5f, -50}},
                                      {{-3, -3, -2}, {3, -3, -2}, {0, 3, -2}}};
  const Scene scene = mixedScene(tris, {Quadric::sphere({0, 0, 0}, 2), Quadric::sphere({0, 0, 0}, 2),
                                        Quadric::cone({-40, 10, 10}, 1, {40, 10, 10}, 1)});
  const Ray onAxis{{0, 0, -6}, {0, 0, 1}};
  const BruteForce brute(scene);
  ASSERT_EQ(brute.intersect(onAxis)->prim, 1u);
  ASSERT_EQ(brute.intersect(onAxis)->t, 4.0f);
  const Ray beside{{0.5f, 0, 6}, {0, 0, -1}};  // from the other side, missing the triangle's plane first
  ASSERT_EQ(brute.intersect(beside)->prim, 2u);
  std::vector<Ray> rays = {onAxis, beside};
  for (float x = -45.0f; x <= 45.0f; x += 0.75f) {
    rays.push_back({{x, 10, -5}, {0, 0, 1}});         // across the cylinder: hits from x = -40 to 40
    rays.push_back({{x, 12, 10}, {0.01f, -1, 0}});     // down onto it
  }
  for (const auto& accel : structures(scene)) {
    SCOPED_TRACE(accel->name());
    EXPECT_GT(expectSameHits(*accel, scene, rays), 150u);
    EXPECT_EQ(accel->intersect(onAxis)->prim, 1u);
    EXPECT_EQ(accel->intersect(beside)->prim, 2u);
  }
}

TEST(MixedStructures, StatsCountQuadricTestsApart) {
  // A triangle far from a sphere: a ray at each tests it, counted by kind.
  const Scene scene = mixedScene({{{7, -3, 0}, {13, -3, 0}, {10, 3, 0}}}, {Quadric::sphere({0, 0, 0}, 1)});
  const Ray atSphere{{0, 0, -6}, {0, 0, 1}}, atTriangle{{10, 0, -6}, {0, 0, 1}};
  for (const auto& accel : structures(scene)) {
    SCOPED_TRACE(accel->name());
    TraversalStats sphere, triangle;
    ASSERT_EQ(accel->intersect(atSphere, &sphere)->prim, 1u);
    ASSERT_EQ(accel->intersect(atTriangle, &triangle)->prim, 0u);
    EXPECT_GE(sphere.quadricTests, 1u);
    EXPECT_GE(triangle.triangleTests, 1u);
    EXPECT_EQ(sphere.quadricTests + sphere.triangleTests + triangle.quadricTests + triangle.triangleTests,
              2u + sphere.triangleTests + triangle.quadricTests);
  }
  TraversalStats brute;
  BruteForce(scene).intersect(atSphere, &brute);
  EXPECT_EQ(brute.quadricTests, 1u);
  EXPECT_EQ(brute.triangleTests, 1u);
}

TEST(MixedStructures, BvhLeavesListQuadricIdsForTheDriversCandidates) {
  RandomScenes random;
  random.rng.seed(4045);
  const Scene scene = random.scene(30, 30);
  for (const int leafSize : {1, 4, 16}) {
    AccelOptions options;
    options.bvhLeafSize = leafSize;
    const Bvh bvh(scene, options);
    // Every primitive once, in the scene's id space; every leaf's box holds its primitives' boxes.
    std::vector<uint32_t> ids = bvh.primIds();
    std::sort(ids.begin(), ids.end());
    ASSERT_EQ(ids.size(), scene.primitiveCount());
    for (uint32_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], i);
    for (const BvhNode& node : bvh.nodes()) {
      if (!node.isLeaf()) continue;
      for (uint32_t i = node.index; i < node.index + node.count; ++i) {
        const Aabb box = primitiveBounds(scene, bvh.primIds()[i]);
        EXPECT_TRUE(glm::all(glm::lessThanEqual(node.lo, box.lo)) && glm::all(glm::greaterThanEqual(node.hi, box.hi)));
      }
    }
    // The hit primitive is among the host's candidates, quadrics included.
    const TriangleCandidates candidates = exactCandidates(bvh, scene.bounds);
    const BruteForce brute(scene);
    size_t quadricHits = 0;
    std::vector<uint32_t> list;
    for (int k = 0; k < 1000; ++k) {
      const Ray ray = random.ray(scene);
      const auto hit = brute.intersect(ray);
      if (!hit) continue;
      list.clear();
      candidates(ray, list);
      EXPECT_NE(std::find(list.begin(), list.end(), hit->prim), list.end()) << "ray " << k;
      quadricHits += scene.isQuadric(hit->prim);
    }
    EXPECT_GT(quadricHits, 100u);
  }
}

}  // namespace
}  // namespace lancer
