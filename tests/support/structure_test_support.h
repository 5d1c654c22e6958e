#pragma once

// Rays, scenes and comparisons shared by the reference-structure tests
// (grid_test.cpp, octree_test.cpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/brute_force.h"
#include "scene/scene.h"
#include "support/test_paths.h"

namespace lancer::test {


// ---- Helpers shared by grid_test.cpp and octree_test.cpp.

inline uint32_t bitsOf(float f) { return std::bit_cast<uint32_t>(f); }

inline std::string describe(const Ray& r) {
  return fmt::format("origin ({:a}, {:a}, {:a}) dir ({:a}, {:a}, {:a}) tMax {:a}", r.origin.x,
                     r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tMax);
}

inline std::string describe(const std::optional<Hit>& h) {
  if (!h) return "miss";
  return fmt::format("prim {} t {:a} u {:a} v {:a}", h->prim, h->t, h->u, h->v);
}

inline bool sameHit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->prim == b->prim && bitsOf(a->t) == bitsOf(b->t) &&
                bitsOf(a->u) == bitsOf(b->u) && bitsOf(a->v) == bitsOf(b->v));
}

// Checks every ray against BruteForce: the same hit bit for bit (or both miss),
// and intersectP() == intersect().has_value(). Returns the number of hits so the
// caller can check that the rays exercised something.
inline size_t expectSameHits(const Accel& accel, const Scene& scene, const std::vector<Ray>& rays) {
  const BruteForce brute(scene);
  size_t hits = 0, mismatches = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto want = brute.intersect(rays[i]);
    const auto got = accel.intersect(rays[i]);
    const bool any = accel.intersectP(rays[i]);
    hits += want.has_value();
    if (sameHit(want, got) && any == want.has_value()) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << accel.name() << " ray " << i << ": " << describe(rays[i])
                    << "\n  brute force: " << describe(want) << "\n  " << accel.name() << ": "
                    << describe(got) << "\n  intersectP: " << any;
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << rays.size() << " rays";
  return hits;
}

inline Aabb grow(const Aabb& b, float fraction) {
  const glm::vec3 g = fraction * b.diagonal();
  return Aabb{b.lo - g, b.hi + g};
}

class RayMaker {
 public:
  explicit RayMaker(uint32_t seed) : rng_(seed) {}
  float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
  size_t index(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }
  glm::vec3 inBox(const Aabb& b) {
    return {uniform(b.lo.x, b.hi.x), uniform(b.lo.y, b.hi.y), uniform(b.lo.z, b.hi.z)};
  }
  glm::vec3 direction() {
    std::normal_distribution<float> n;
    for (;;) {
      const glm::vec3 d(n(rng_), n(rng_), n(rng_));
      if (glm::length(d) > 1e-3f) return glm::normalize(d);
    }
  }
  glm::vec3 pointOn(const Triangle& t) {
    const float s = std::sqrt(uniform(0.0f, 1.0f)), r = uniform(0.0f, 1.0f);
    return (1.0f - s) * t.v0 + s * (1.0f - r) * t.v1 + s * r * t.v2;
  }

  // Origins uniform in the scene box grown by half its size each side (so inside
  // and outside); half the rays aimed at a random point of a random triangle (t
  // near 1), half in uniform random directions; every eighth has a finite tMax.
  std::vector<Ray> random(const Scene& scene, size_t n) {
    const Aabb box = grow(scene.bounds, 0.5f);
    const float diag = glm::length(scene.bounds.diagonal());
    std::vector<Ray> rays(n);
    for (size_t i = 0; i < n; ++i) {
      Ray& r = rays[i];
      r.origin = inBox(box);
      const bool aimed = i % 2 == 0;
      r.dir = aimed ? pointOn(scene.triangles[index(scene.size())]) - r.origin : direction();
      if (i % 8 == 3) r.tMax = uniform(0.0f, aimed ? 1.5f : 2.0f * diag);
    }
    return rays;
  }

 private:
  std::mt19937 rng_;
};

inline Scene translated(Scene scene, const glm::vec3& offset) {
  for (Triangle& t : scene.triangles) {
    t.v0 += offset;
    t.v1 += offset;
    t.v2 += offset;
  }
  scene.computeBounds();
  return scene;
}

inline Scene fromTriangles(std::vector<Triangle> triangles) {
  Scene scene;
  scene.name = "test";
  scene.triangles = std::move(triangles);
  scene.materialOf.assign(scene.triangles.size(), 0);
  scene.materials.push_back(Material{"default"});
  scene.computeBounds();
  return scene;
}

// Rays aimed exactly at every vertex and at every edge midpoint of (a sample of)
// the scene's triangles, from random origins around the scene.
inline std::vector<Ray> verticesAndMidpoints(const Scene& scene, size_t maxTriangles, uint32_t seed) {
  RayMaker maker(seed);
  const Aabb box = grow(scene.bounds, 0.5f);
  std::vector<Ray> rays;
  const size_t step = std::max<size_t>(1, scene.size() / maxTriangles);
  for (size_t i = 0; i < scene.size(); i += step) {
    const Triangle& t = scene.triangles[i];
    for (const glm::vec3& target :
         {t.v0, t.v1, t.v2, 0.5f * (t.v0 + t.v1), 0.5f * (t.v1 + t.v2), 0.5f * (t.v2 + t.v0)}) {
      Ray r;
      r.origin = maker.inBox(box);
      r.dir = target - r.origin;
      rays.push_back(r);
    }
  }
  return rays;
}

// Axis-parallel rays along `axis` (both signs) with the other two components +0
// or -0 in all four combinations, from `origin`.
inline void addAxisParallel(std::vector<Ray>& rays, const glm::vec3& origin, int axis) {
  for (float sign : {1.0f, -1.0f}) {
    for (int zeros = 0; zeros < 4; ++zeros) {
      Ray r;
      r.origin = origin;
      r.dir = glm::vec3(0.0f);
      r.dir[axis] = sign;
      r.dir[(axis + 1) % 3] = (zeros & 1) ? -0.0f : 0.0f;
      r.dir[(axis + 2) % 3] = (zeros & 2) ? -0.0f : 0.0f;
      rays.push_back(r);
    }
  }
}

inline const Scene& cornell() {
  static const Scene scene = loadScene(kDefaultSceneName);
  return scene;
}
inline const Scene& bunny() {
  static const Scene scene = loadScene(test::kBunny);
  return scene;
}
inline const Scene& wuson() {
  static const Scene scene = loadScene(test::kWuson);
  return scene;
}

// Two specks pinning the box [0,100]^3, so a structure's planes can be computed
// before the rest of the scene is made.
inline std::vector<Triangle> pins() {
  return {{{0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}},
          {{100, 100, 100}, {99.5f, 100, 100}, {100, 99.5f, 100}}};
}

// Axis-aligned right triangles lying in the given (interior) planes of each
// axis and one ulp either side of them, with their corners on the lattice the
// planes make: their boxes lie exactly on, or within an ulp of, cell boundaries.
inline Scene latticeScene(const std::array<std::vector<float>, 3>& planes) {
  std::vector<Triangle> tris = pins();
  for (int a = 0; a < 3; ++a) {
    const int p = (a + 1) % 3, q = (a + 2) % 3;
    for (size_t k = 0; k < planes[a].size(); k += 2) {
      for (float plane : {std::nextafter(planes[a][k], -kInfinity), planes[a][k],
                          std::nextafter(planes[a][k], kInfinity)}) {
        for (size_t i = 0; i + 1 < planes[p].size(); i += 2) {
          for (size_t j = 0; j + 1 < planes[q].size(); j += 3) {
            glm::vec3 v0, v1, v2;
            v0[a] = v1[a] = v2[a] = plane;
            v0[p] = v2[p] = planes[p][i];
            v1[p] = planes[p][i + 1];
            v0[q] = v1[q] = planes[q][j];
            v2[q] = planes[q][j + 1];
            tris.push_back({v0, v1, v2});
          }
        }
      }
    }
  }
  return fromTriangles(tris);
}

// Random rays at the lattice triangles, at their vertices and edge midpoints;
// each ray that hits also once more with tMax exactly at its brute-force hit.
inline std::vector<Ray> latticeRays(const Scene& scene, uint32_t seed) {
  RayMaker maker(seed);
  const BruteForce brute(scene);
  std::vector<Ray> rays = verticesAndMidpoints(scene, scene.size(), seed);
  for (size_t i = 0; i < 3000; ++i) {
    Ray r;
    r.origin = maker.inBox(grow(scene.bounds, 0.3f));
    r.dir = maker.pointOn(scene.triangles[maker.index(scene.size())]) - r.origin;
    rays.push_back(r);
  }
  for (size_t i = 0, n = rays.size(); i < n; ++i) {
    if (const auto hit = brute.intersect(rays[i])) {
      rays.push_back(rays[i]);
      rays.back().tMax = hit->t;
    }
  }
  return rays;
}

// Expects `build()` to throw InputError with every one of `parts` in its message.
template <class Build>
void expectInputErrorMentioning(Build build, std::initializer_list<std::string_view> parts) {
  try {
    build();
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    for (std::string_view part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
}

// The scene of the "closer triangle in the next cell wins" tests: two specks pin
// the box [0, side]^3; triangle 0 is a long slanted sliver whose box starts at
// x = 1 but which a ray along +x at y = z = 0.5 hits at x = side / 2 + 0.5;
// triangle 1 is a small wall at x = 2.5.
inline Scene closerTriangleScene(float side) {
  return fromTriangles({
      {{1.0f, 0.0f, 0.0f}, {side, 1.0f, 0.0f}, {side / 2 + 0.5f, 0.5f, side / 2}},
      {{2.5f, 0.3f, 0.3f}, {2.5f, 0.7f, 0.4f}, {2.5f, 0.4f, 0.7f}},
      {{0.0f, side - 1.0f, side - 1.0f}, {0.0f, side - 1.0f, side - 0.9f}, {0.0f, side - 0.9f, side - 1.0f}},
      {{side, side, side}, {side, side - 0.1f, side}, {side, side, side - 0.1f}},
  });
}

// The end of the "closer triangle in the next cell wins" tests: along +x from
// (0.5, 0.5, 0.5), `scene` (the structure's own: triangle 0 a slanted sliver
// listed in the first cell but hit far along, triangle 1 a small wall at x = 2.5)
// must give triangle 1 at t = 2 after at most `maxVisits` nodes, and triangle 0
// to the same ray raised to z = 2, above the wall.
template <class StructureT>
void expectCloserTriangleInALaterCellWins(const StructureT& accel, const Scene& scene, uint64_t maxVisits) {
  const Ray ray{{0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}};
  TraversalStats stats;
  const auto hit = accel.intersect(ray, &stats);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->prim, 1u);
  EXPECT_EQ(hit->t, 2.0f);
  EXPECT_LE(stats.nodesVisited, maxVisits);
  Ray open = ray;
  open.origin.z = 2.0f;  // above the wall, still through the sliver
  const auto far = accel.intersect(open);
  ASSERT_TRUE(far.has_value());
  EXPECT_EQ(far->prim, 0u);
  expectSameHits(accel, scene, {ray, open});
}

// The end of the "triangles on cell boundaries" tests: `accel`, built over
// latticeScene() of planes taken from `lattice` (the same structure over the
// pins() alone), has the same box, and agrees with brute force on latticeRays().
template <class StructureT>
void expectLatticeSceneMatches(const StructureT& accel, const StructureT& lattice, const Scene& scene, uint32_t seed) {
  ASSERT_EQ(accel.bounds().lo, lattice.bounds().lo);
  ASSERT_EQ(accel.bounds().hi, lattice.bounds().hi);
  const auto rays = latticeRays(scene, seed);
  EXPECT_GT(expectSameHits(accel, scene, rays), rays.size() * 3 / 4);
}

}  // namespace lancer::test
