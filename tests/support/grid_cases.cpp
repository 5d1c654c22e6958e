#include "support/grid_cases.h"

#include <algorithm>
#include <array>

#include <tuple>

#include <fmt/format.h>

#include "driver/quantize.h"

#ifndef LANCER_DATA_DIR
#error "LANCER_DATA_DIR must come from tests/CMakeLists.txt"
#endif

namespace lancer::test {

using fx::GridRes;
using fx::kDirMax;
using fx::kPosBits;
using fx::kPosMax;
using fx::QRay;
using fx::QTriangle;

const Scene& bunnyScene() {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return scene;
}

std::vector<GridCase> gridHardCases() {
  std::vector<GridCase> cases;
  const QuantizedScene bunny = quantizedCamera(bunnyScene(), 1, 1);

  {  // Axis-parallel float rays with +0 and -0 components, through the quantizer.
    const Scene& scene = bunnyScene();
    const Quantizer quantizer(scene.bounds);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    GridCase c{"axis-parallel signed zeros, bunny 16^3", fx::buildGridImage(bunny.triangles, {16, 16, 16}), {}};
    const glm::vec3 lo = scene.bounds.lo, hi = scene.bounds.hi;
    for (uint32_t i = 0; i < 300; ++i) {
      const int axis = int(i % 3);
      Ray r;
      for (int a = 0; a < 3; ++a) r.origin[a] = lo[a] + (hi[a] - lo[a]) * u(rng);
      r.origin[axis] = (i & 8) ? hi[axis] + 1.0f : lo[axis] - 1.0f;
      r.dir = glm::vec3((i & 1) ? -0.0f : 0.0f, (i & 2) ? -0.0f : 0.0f, (i & 4) ? -0.0f : 0.0f);
      r.dir[axis] = (i & 8) ? -1.0f : 1.0f;
      if (auto qr = quantizer.quantize(r, uint32_t(c.rays.size()))) c.rays.push_back(qr->q);
    }
    cases.push_back(std::move(c));
  }
  {  // A 16^3 grid whose boundaries lie on lattice points (2^P / 16 apart).
    std::mt19937_64 rng(6);
    GridCase c{"planes, edges, corners, faces, tiny components, 16^3",
               fx::buildGridImage(randomGridTriangles(rng, 300, kPosMax / 12), {16, 16, 16}), {}};
    const int64_t cell = int64_t(1) << (kPosBits - 4);
    std::uniform_int_distribution<int64_t> pick(0, 16), pos(0, kPosMax), dir(-kDirMax, kDirMax);
    auto boundary = [&] { return std::min(pick(rng) * cell, kPosMax); };
    for (uint32_t i = 0; i < 480; ++i) {
      QRay r{i, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}};
      switch (i % 6) {
        case 0:  // in a plane between voxels, moving within it
          r.org[i % 3] = boundary();
          r.dir[i % 3] = 0;
          break;
        case 1:  // along a voxel edge
          r.org[i % 3] = boundary();
          r.org[(i + 1) % 3] = boundary();
          r.dir[i % 3] = 0;
          r.dir[(i + 1) % 3] = 0;
          break;
        case 2:  // from a voxel corner along a diagonal (exact ties on all axes)
          for (int a = 0; a < 3; ++a) {
            r.org[a] = boundary();
            r.dir[a] = (dir(rng) < 0 ? -1 : 1) * kDirMax;
          }
          break;
        case 3:  // on a grid face
          r.org[i % 3] = (i & 1) ? 0 : kPosMax;
          break;
        case 4:  // from a corner of the grid
          for (int a = 0; a < 3; ++a) r.org[a] = (dir(rng) < 0) ? 0 : kPosMax;
          break;
        default:  // one component too small to ever step
          r.dir[i % 3] = (i & 1) ? 1 : -1;
          break;
      }
      if (r.dir == std::array<int64_t, 3>{0, 0, 0}) r.dir[0] = kDirMax;
      c.rays.push_back(normalizedDirection(r));
    }
    cases.push_back(std::move(c));
  }
  {  // One cell and the finest grid.
    std::mt19937_64 rng(8);
    const std::vector<QTriangle> tris = randomGridTriangles(rng, 40, kPosMax / 6);
    std::vector<QRay> rays;
    for (uint32_t i = 0; i < 50; ++i) rays.push_back(randomGridRay(rng, i));
    cases.push_back({"1x1x1", fx::buildGridImage(tris, {1, 1, 1}), rays});
    cases.push_back({"256x256x256", fx::buildGridImage(tris, {256, 256, 256}), rays});
  }
  {  // Mostly empty cells; triangles spanning many cells.
    std::mt19937_64 rng(11);
    std::vector<QTriangle> tris = randomGridTriangles(rng, 6, kPosMax / 64);
    for (QTriangle t : randomGridTriangles(rng, 6, kPosMax)) {
      t.id = uint32_t(tris.size());
      tris.push_back(t);
    }
    GridCase c{"empty cells, large triangles, 64x48x40", fx::buildGridImage(tris, {64, 48, 40}), {}};
    for (uint32_t i = 0; i < 250; ++i) c.rays.push_back(randomGridRay(rng, i));
    cases.push_back(std::move(c));
  }
  {  // Thousands of triangles in one cell; rays through it and around it.
    std::mt19937_64 rng(13);
    std::uniform_int_distribution<int64_t> in(kPosMax / 4 + 2, kPosMax / 2 - 2);
    std::vector<QTriangle> tris;
    for (uint32_t i = 0; i < 2500; ++i) {
      QTriangle t;
      t.id = i;
      for (auto& v : t.v)
        for (auto& x : v) x = in(rng);
      tris.push_back(t);
    }
    GridCase c{"crowded cell, 4^3", fx::buildGridImage(tris, {4, 4, 4}), {}};
    for (uint32_t i = 0; i < 20; ++i) {
      QRay r = randomGridRay(rng, i);
      if (i % 2 == 0) r.org = {in(rng), in(rng), in(rng)};  // starts in the crowded cell
      c.rays.push_back(r);
    }
    cases.push_back(std::move(c));
  }
  {  // Segment ends and any-hit: a wall on a cell boundary (16^3: boundaries 2^P / 16 apart) and one
     // off it, walked both ways; then bounded and any-hit variants of random rays over the bunny.
    const int64_t boundary = (int64_t(1) << fx::kPosBits) / 2;
    for (const auto& [name, zWall, zOrigin] : {std::tuple{"segment ends, wall on a cell boundary, 16^3", boundary,
                                                          kPosMax / 16 + 3},
                                               std::tuple{"segment ends, wall inside a cell, -z, 16^3",
                                                          kPosMax / 5, kPosMax - 7}}) {
      QuantizedScene wall = segmentScene(zWall, zOrigin);
      cases.push_back({name, fx::buildGridImage(wall.triangles, {16, 16, 16}), std::move(wall.rays)});
    }
    std::mt19937_64 rng(23);
    std::vector<QRay> rays;
    for (uint32_t i = 0; i < 60; ++i) rays.push_back(randomGridRay(rng, i));
    for (QRay& r : quantizedCamera(bunnyScene(), 8, 8).rays) rays.push_back(r);
    cases.push_back({"segment variants, bunny 12^3", fx::buildGridImage(bunny.triangles, {12, 12, 12}),
                     segmentVariants(bunny.triangles, rays, rays.size())});
  }
  {  // Random rays over the bunny; one cell tests every triangle per ray, so fewer rays there.
    std::mt19937_64 rng(2);
    std::vector<QRay> rays;
    for (uint32_t i = 0; i < 300; ++i) rays.push_back(randomGridRay(rng, i));
    for (const GridRes& res : {GridRes{1, 1, 1}, GridRes{3, 7, 5}, GridRes{32, 32, 32}}) {
      const size_t count = res[0] == 1 ? 40 : rays.size();
      cases.push_back({fmt::format("bunny random rays {}x{}x{}", res[0], res[1], res[2]),
                       fx::buildGridImage(bunny.triangles, res),
                       std::vector<QRay>(rays.begin(), rays.begin() + ptrdiff_t(count))});
    }
  }
  return cases;
}

}  // namespace lancer::test
