#include <gtest/gtest.h>

#include <random>

#include "common/error.h"
#include "driver/quantize.h"
#include "golden/grid.h"
#include "golden/isect.h"
#include "scene/scene.h"
#include "support/test_paths.h"
#include "support/traversal_cases.h"

namespace lancer::fx {
namespace {
using namespace lancer::test;  // quantizeScene, bruteForceHit, randomLatticeRay (support/traversal_cases.h)

// Consecutive cells differ by one step on exactly one axis: the DDA never jumps
// diagonally past a cell the ray touches.
void expectFaceConnected(const GridImage& image, const std::vector<uint32_t>& cells) {
  for (size_t i = 1; i < cells.size(); ++i) {
    const int rx = image.res[0], ry = image.res[1];
    auto coords = [&](uint32_t id) {
      return std::array<int, 3>{int(id % rx), int(id / rx % ry), int(id / rx / ry)};
    };
    const auto a = coords(cells[i - 1]), b = coords(cells[i]);
    int moved = 0;
    for (int k = 0; k < 3; ++k) moved += std::abs(a[k] - b[k]);
    ASSERT_EQ(moved, 1) << "cells " << cells[i - 1] << " -> " << cells[i];
  }
}

class GoldenGridScenes : public ::testing::TestWithParam<int> {};

TEST_P(GoldenGridScenes, ClosestHitEqualsBruteForceOnTheBunny) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  const int r = GetParam();
  const GridImage image = buildGridImage(tris, r ? GridRes{r, r, r} : chooseGridResolution(tris));
  std::mt19937_64 rng(uint64_t(r) + 3);
  for (uint32_t i = 0; i < 400; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    const GridTrace trace = traverseGrid(image, ray);
    ASSERT_EQ(trace.hit, bruteForceHit(tris, ray)) << "ray " << i << " at resolution " << r;
    expectFaceConnected(image, trace.visits);
  }
}
INSTANTIATE_TEST_SUITE_P(Resolutions, GoldenGridScenes, ::testing::Values(0, 1, 2, 7, 32, 128));

TEST(GoldenGrid, HeuristicScalesWithTriangleCount) {
  const auto tris = quantizeScene(loadScene(test::kBunny));
  const GridRes res = chooseGridResolution(tris);
  const double cells = double(res[0]) * res[1] * res[2];
  EXPECT_GT(cells, 1.0 * tris.size());
  EXPECT_LT(cells, 16.0 * tris.size());
  for (int a = 0; a < 3; ++a) EXPECT_LE(res[a], kGridResMax);
}

TEST(GoldenGrid, AxisParallelRaysStepOnOneAxisOnly) {
  const auto tris = quantizeScene(makeCornellBox());
  const GridImage image = buildGridImage(tris, {8, 8, 8});
  const int64_t mid = kPosMax / 2;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      QRay ray{0, {mid, mid, mid}, {0, 0, 0}};
      ray.dir[axis] = sign * kDirMax;
      const GridTrace trace = traverseGrid(image, ray);
      EXPECT_EQ(trace.hit, bruteForceHit(tris, ray));
      expectFaceConnected(image, trace.visits);
      // Only `axis` changes along the walk.
      for (uint32_t id : trace.visits) {
        const std::array<int, 3> c{int(id % 8), int(id / 8 % 8), int(id / 64)};
        for (int k = 0; k < 3; ++k) {
          if (k != axis) {
            EXPECT_EQ(c[k], int((mid * 8) >> kPosBits));
          }
        }
      }
    }
  }
}

TEST(GoldenGrid, RaysThroughCellCornersVisitOneAxisAtATime) {
  // An empty grid (one tiny triangle far away) so the whole walk is visible.
  std::vector<QTriangle> tris{QTriangle{0, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}};
  const GridImage image = buildGridImage(tris, {4, 4, 4});
  const int64_t cell = (int64_t(1) << kPosBits) / 4;  // lattice units per cell
  // From the corner shared by cells (0,0,0)..(1,1,1) along the main diagonal.
  const QRay ray{0, {cell, cell, cell}, {kDirMax, kDirMax, kDirMax}};
  const GridTrace trace = traverseGrid(image, ray);
  const std::vector<uint32_t> expected{image.cellId({1, 1, 1}), image.cellId({2, 1, 1}), image.cellId({2, 2, 1}),
                                       image.cellId({2, 2, 2}), image.cellId({3, 2, 2}), image.cellId({3, 3, 2}),
                                       image.cellId({3, 3, 3})};
  EXPECT_EQ(trace.visits, expected);
}

TEST(GoldenGrid, RayInThePlaneBetweenCellsAndAlongAnEdge) {
  const auto tris = quantizeScene(makeCornellBox());
  const GridImage image = buildGridImage(tris, {4, 4, 4});
  const int64_t boundary = (int64_t(1) << kPosBits) / 2;  // between cells 1 and 2
  for (const QRay& ray : {QRay{0, {boundary, 100, 5}, {0, kDirMax / 3, kDirMax}},
                          QRay{1, {boundary, boundary, 0}, {0, 0, kDirMax}},
                          QRay{2, {boundary, boundary, kPosMax}, {0, -0, -kDirMax}}}) {
    const GridTrace trace = traverseGrid(image, ray);
    EXPECT_EQ(trace.hit, bruteForceHit(tris, ray)) << ray.id;
    expectFaceConnected(image, trace.visits);
  }
}

TEST(GoldenGrid, TinyComponentCrossesTheGridWithoutSteppingOnItsAxis) {
  std::vector<QTriangle> tris{QTriangle{0, {{{kPosMax, 0, 0}, {kPosMax, kPosMax, 0}, {kPosMax, 0, kPosMax}}}}};
  const GridImage image = buildGridImage(tris, {16, 16, 16});
  const QRay ray{0, {0, 10, 10}, {kDirMax, 1, 0}};
  const GridTrace trace = traverseGrid(image, ray);
  ASSERT_EQ(trace.visits.size(), 16u);  // straight along x
  EXPECT_EQ(trace.hit, bruteForceHit(tris, ray));
  ASSERT_TRUE(trace.hit.has_value());
}

TEST(GoldenGrid, EarlyTerminationWaitsForACloserHitInTheNextCell) {
  // A large slanted triangle spans many cells and is hit far beyond the first
  // cell, but is listed in it; a small triangle in the second cell is closer.
  const int64_t s = int64_t(1) << kPosBits;
  const QTriangle big{0, {{{0, 0, s / 2}, {kPosMax, 0, s / 2 + s / 8}, {0, kPosMax, s / 2 + s / 8}}}};
  const QTriangle small{1, {{{s / 8 + 10, 0, s / 8 + 300}, {s / 8 + 10, s / 4, s / 8 + 300}, {s / 8 + 10, 0, s / 8 - 300}}}};
  const GridImage image = buildGridImage({big, small}, {8, 8, 8});
  // Along +x at y, z inside the first z-slab: crosses the small triangle at x = s/8 + 10.
  const QRay ray{0, {0, 100, s / 8}, {kDirMax, 0, kDirMax / 64}};
  const GridTrace trace = traverseGrid(image, ray);
  const auto expected = bruteForceHit(std::vector<QTriangle>{big, small}, ray);
  ASSERT_TRUE(expected.has_value());
  EXPECT_EQ(trace.hit, expected);
}

TEST(GoldenGrid, ExtremeResolutionsAndCrowdedCells) {
  const auto tris = quantizeScene(makeCornellBox());
  const GridImage one = buildGridImage(tris, {1, 1, 1});
  EXPECT_EQ(one.cells.size(), 1u);
  EXPECT_EQ(one.cells[0].count, tris.size());
  const GridImage fine = buildGridImage(tris, {256, 256, 256});
  EXPECT_EQ(fine.cells.size(), size_t(256) * 256 * 256);
  std::mt19937_64 rng(9);
  for (uint32_t i = 0; i < 50; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    EXPECT_EQ(traverseGrid(fine, ray).hit, bruteForceHit(tris, ray));
    EXPECT_EQ(traverseGrid(one, ray).hit, bruteForceHit(tris, ray));
  }
  // Thousands of triangles in one cell (the lower z half; at narrow formats
  // several share a plane, and the tie goes to the lowest id).
  std::vector<QTriangle> crowd;
  const int64_t planes = std::min<int64_t>(3000, (kPosMax + 1) / 2 - 100);
  for (uint32_t i = 0; i < 3000; ++i) {
    const int64_t z = 100 + int64_t(i) % planes;
    crowd.push_back(QTriangle{i, {{{10, 10, z}, {200, 10, z}, {10, 200, z}}}});
  }
  const GridImage crowded = buildGridImage(crowd, {2, 2, 2});
  const QRay ray{7, {20, 20, 0}, {0, 0, kDirMax}};
  const GridTrace trace = traverseGrid(crowded, ray);
  ASSERT_TRUE(trace.hit.has_value());
  EXPECT_EQ(trace.hit->primId, 0u);
  EXPECT_EQ(trace.tests, 3000u);
}

TEST(GoldenGrid, BadConfigurationsAreErrors) {
  const auto tris = quantizeScene(makeCornellBox());
  EXPECT_THROW(buildGridImage(tris, {0, 4, 4}), InputError);
  EXPECT_THROW(buildGridImage(tris, {4, 257, 4}), InputError);
  // Two triangles covering the whole lattice at 256^3 need 2 * 2^24 index entries.
  if (kMemAddrBits <= 24) {
    const QTriangle all{0, {{{0, 0, 0}, {kPosMax, 0, kPosMax}, {0, kPosMax, kPosMax}}}};
    QTriangle all2 = all;
    all2.id = 1;
    try {
      buildGridImage({all, all2}, {256, 256, 256});
      FAIL() << "expected the image not to fit";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("address width"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace lancer::fx
