#pragma once

// Stimulus and the brute-force answer shared by the tests of the golden
// traversal units (golden_grid_test.cpp, golden_octree_test.cpp).

#include <optional>
#include <random>
#include <vector>

#include "driver/quantize.h"
#include "golden/isect.h"
#include "scene/scene.h"

namespace lancer::test {

// The scene's triangles on the lattice of its bounds (id = index), as the driver quantizes them.
inline std::vector<fx::QTriangle> quantizeScene(const Scene& scene) {
  return Quantizer(scene.bounds).quantize(scene);
}

// The closest hit over every triangle: what any traversal must return.
inline std::optional<fx::IsectResult> bruteForce(const std::vector<fx::QTriangle>& tris, const fx::QRay& ray) {
  std::optional<fx::IsectResult> best;
  for (const fx::QTriangle& t : tris) {
    const fx::IsectResult r = fx::intersect(ray, t);
    if (r.hit && (!best || fx::closerResult(r, *best))) best = r;
  }
  return best;
}

// A random lattice ray, normalized like the driver: the dominant component is exactly +-kDirMax.
inline fx::QRay randomRay(std::mt19937_64& rng, uint32_t id) {
  std::uniform_int_distribution<int64_t> pos(0, fx::kPosMax), dir(-fx::kDirMax, fx::kDirMax);
  fx::QRay r{id, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}};
  const int k = fx::dominantAxis(r.dir);
  r.dir[k] = r.dir[k] < 0 ? -fx::kDirMax : fx::kDirMax;
  return r;
}

}  // namespace lancer::test
