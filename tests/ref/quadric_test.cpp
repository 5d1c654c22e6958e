// The float reference's ray-quadric test (sw/ref/quadric.h) on rays whose
// answer is known by construction, Quadric::bounds, and the entry points that
// refuse a scene with quadrics until they take them (Scene::requireTrianglesOnly;
// the float structures take them: mixed_structures_test.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/error.h"
#include "driver/quantize.h"
#include "ref/brute_force.h"
#include "ref/bvh.h"
#include "ref/grid.h"
#include "ref/octree.h"
#include "ref/quadric.h"
#include "scene/scene.h"
#include "scene/write.h"

namespace lancer {
namespace {

Ray rayOf(glm::vec3 origin, glm::vec3 dir, float tMax = kInfinity) { return {origin, dir, tMax}; }

std::optional<QuadricHit> hitOf(const Ray& ray, const Quadric& q) { return intersectQuadric(ray, q, 7); }

// How far `p` is from the surface: |p - c| - r for a sphere, rho - R(h) for a
// cone (its height h above the base in `height`, when asked).
double surfaceError(const QuadricShape& s, const glm::dvec3& p, double* height = nullptr) {
  if (s.kind == Quadric::Kind::Sphere) return glm::length(p - s.base) - s.baseRadius;
  const glm::dvec3 w = s.apex - s.base, axis = glm::normalize(w);
  const double h = glm::dot(p - s.base, axis);
  if (height) *height = h;
  return glm::length(p - s.base - h * axis) - (s.baseRadius + (s.apexRadius - s.baseRadius) * h / glm::length(w));
}

void expectNormal(const QuadricHit& hit, glm::dvec3 expected) {
  expected = glm::normalize(expected);
  EXPECT_NEAR(hit.normal.x, expected.x, 1e-12);
  EXPECT_NEAR(hit.normal.y, expected.y, 1e-12);
  EXPECT_NEAR(hit.normal.z, expected.z, 1e-12);
}

TEST(QuadricReference, SphereEnteringLeavingBehindAndSegmentEnd) {
  const Quadric s = Quadric::sphere({0, 0, 0}, 2);
  auto hit = hitOf(rayOf({0, 0, -5}, {0, 0, 1}), s);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.prim, 7u);
  EXPECT_EQ(hit->hit.t, 3.0f);
  EXPECT_TRUE(hit->entering);
  EXPECT_EQ(hit->hit.u, 0.0f);
  expectNormal(*hit, {0, 0, -1});
  // From the center: the leaving root, the normal still outward.
  hit = hitOf(rayOf({0, 0, 0}, {0, 0, 0.5f}), s);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.t, 4.0f);
  EXPECT_FALSE(hit->entering);
  EXPECT_EQ(hit->hit.u, 1.0f);
  expectNormal(*hit, {0, 0, 1});
  EXPECT_FALSE(hitOf(rayOf({0, 0, 5}, {0, 0, 1}), s));  // behind
  EXPECT_TRUE(hitOf(rayOf({0, 0, -5}, {0, 0, 1}, 3.0f), s));
  EXPECT_FALSE(hitOf(rayOf({0, 0, -5}, {0, 0, 1}, std::nextafter(3.0f, 0.0f)), s));
  // A negative radius (NFF: inside visible) is the same surface.
  EXPECT_EQ(hitOf(rayOf({0, 0, -5}, {0, 0, 1}), Quadric::sphere({0, 0, 0}, -2))->hit.t, 3.0f);
}

TEST(QuadricReference, SphereTangentAndFarAway) {
  const Quadric s = Quadric::sphere({0, 0, 0}, 1);
  const auto tangent = hitOf(rayOf({1, 0, -4}, {0, 0, 1}), s);
  ASSERT_TRUE(tangent);
  EXPECT_EQ(tangent->hit.t, 4.0f);
  EXPECT_TRUE(tangent->entering);
  EXPECT_FALSE(hitOf(rayOf({std::nextafter(1.0f, 2.0f), 0, -4}, {0, 0, 1}), s));
  // 10^6 radii away the quadratic's terms cancel by 12 digits unless the line
  // restarts near the center: t must still be exact here (999 999 and 1e6 + 1).
  const Quadric far = Quadric::sphere({1e6f, 0, 0}, 1);
  EXPECT_EQ(hitOf(rayOf({0, 0, 0}, {1, 0, 0}), far)->hit.t, 999999.0f);
  EXPECT_NEAR(hitOf(rayOf({0, 0.5f, 0}, {1, 0, 0}), far)->t, 1e6 - std::sqrt(0.75), 3e-10);
  EXPECT_EQ(hitOf(rayOf({1e6f, 0, 0}, {1, 0, 0}), far)->hit.t, 1.0f);
}

TEST(QuadricReference, RaysAlongACylindersAxisMiss) {
  const Quadric cylinder = Quadric::cone({0, 0, 0}, 1, {0, 0, 4}, 1);
  for (const float x : {0.0f, 0.5f, 1.0f, 2.0f}) {
    EXPECT_FALSE(hitOf(rayOf({x, 0, -1}, {0, 0, 1}), cylinder)) << x;
    EXPECT_FALSE(hitOf(rayOf({x, 0, 2}, {0, 0, -3}), cylinder)) << x;
  }
  // An oblique axis: d along w exactly.
  const Quadric oblique = Quadric::cone({0, 0, 0}, 1, {3, 3, 0}, 1);
  EXPECT_FALSE(hitOf(rayOf({-1, -1, 0.5f}, {1, 1, 0}), oblique));
  EXPECT_FALSE(hitOf(rayOf({-1, -1, 0}, {1, 1, 0}), oblique));
  // Across the axis it is hit, at the radius.
  const auto across = hitOf(rayOf({-3, 0, 2}, {1, 0, 0}), cylinder);
  ASSERT_TRUE(across);
  EXPECT_EQ(across->hit.t, 2.0f);
  expectNormal(*across, {-1, 0, 0});
}

TEST(QuadricReference, OpenEndsAndRims) {
  const Quadric cylinder = Quadric::cone({0, 0, 0}, 1, {0, 0, 4}, 1);
  // In through the open base, out through the wall: the inside wall, leaving.
  auto hit = hitOf(rayOf({0, 0, -1}, {0.5f, 0, 1}), cylinder);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.t, 2.0f);
  EXPECT_FALSE(hit->entering);
  expectNormal(*hit, {1, 0, 0});
  // In through the base and out through the apex end: nothing.
  EXPECT_FALSE(hitOf(rayOf({0, 0, -1}, {0.1f, 0, 1}), cylinder));
  // A cone of radius 2 at z = 0 and 1 at z = 2: rays in both end planes hit the rims.
  const Quadric cone = Quadric::cone({0, 0, 0}, 2, {0, 0, 2}, 1);
  EXPECT_EQ(hitOf(rayOf({-5, 0, 0}, {1, 0, 0}), cone)->hit.t, 3.0f);
  EXPECT_EQ(hitOf(rayOf({-5, 0, 2}, {1, 0, 0}), cone)->hit.t, 4.0f);
  EXPECT_FALSE(hitOf(rayOf({-5, 0, std::nextafter(0.0f, -1.0f)}, {1, 0, 0}), cone));
  EXPECT_FALSE(hitOf(rayOf({-5, 0, std::nextafter(2.0f, 3.0f)}, {1, 0, 0}), cone));
  // Slanted through the base rim: the near root at the rim exactly (t = 2).
  hit = hitOf(rayOf({-4, 0, -1}, {1, 0, 0.5f}), cone);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.t, 2.0f);
  EXPECT_TRUE(hit->entering);
}

TEST(QuadricReference, PointedConeAndARayParallelToItsSide) {
  // Radius 2 at z = 0 to a point at z = 2; at z = 1 the radius is 1.
  const Quadric cone = Quadric::cone({0, 0, 0}, 2, {0, 0, 2}, 0);
  auto hit = hitOf(rayOf({-5, 0, 1}, {1, 0, 0}), cone);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.t, 4.0f);
  EXPECT_TRUE(hit->entering);
  expectNormal(*hit, {-1, 0, 1});  // the gradient of rho^2 - R^2, R = 2 - z: the 45-degree side
  // Parallel to a side of the 45-degree cone radius 1 -> 0 over height 1:
  // A = 0, one root (t = 0.75, leaving: the origin is inside the infinite cone).
  const Quadric steep = Quadric::cone({0, 0, 0}, 1, {0, 0, 1}, 0);
  hit = hitOf(rayOf({0, 0, -0.5f}, {-1, 0, 1}), steep);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->hit.t, 0.75f);
  EXPECT_FALSE(hit->entering);
  // Above the apex the other nappe of the quadric is no part of the cone.
  EXPECT_FALSE(hitOf(rayOf({-5, 0, 3}, {1, 0, 0}), cone));
}

TEST(QuadricReference, HitPointsLieOnTheSurface) {
  std::mt19937 rng(40);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), radius(0.1f, 2.0f);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    const glm::vec3 base(u(rng), u(rng), u(rng)), apex = base + 3.0f * glm::vec3(u(rng), u(rng), u(rng));
    const Quadric q = i % 2 ? Quadric::sphere(base, radius(rng)) : Quadric::cone(base, radius(rng), apex, i % 4 ? radius(rng) : 0.0f);
    const glm::vec3 origin = 6.0f * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec3 target = base + glm::vec3(u(rng), u(rng), u(rng));
    const auto hit = intersectQuadric(rayOf(origin, target - origin), q, 0);
    if (!hit) continue;
    ++hits;
    const QuadricShape s = QuadricShape::of(q);
    const glm::dvec3 p = glm::dvec3(origin) + hit->t * glm::dvec3(target - origin);
    double h = 0.0;
    EXPECT_LT(std::fabs(surfaceError(s, p, &h)), 1e-9) << i;
    if (q.kind == Quadric::Kind::Cone) {
      EXPECT_GE(h, -1e-9);
      EXPECT_LE(h, glm::length(s.apex - s.base) + 1e-9);
    }
    EXPECT_GT(hit->t, 0.0);
  }
  EXPECT_GT(hits, 1000);
}

TEST(QuadricReference, PointsNearTheSurfaceProjectOntoIt) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 base(float(u(rng)), float(u(rng)), float(u(rng)));
    const glm::vec3 apex = base + 3.0f * glm::vec3(float(u(rng)), float(u(rng)), float(u(rng)));
    const float r0 = 0.2f + float(std::fabs(u(rng))), r1 = i % 3 ? 0.2f + float(std::fabs(u(rng))) : 0.0f;
    const QuadricShape s = QuadricShape::of(i % 2 ? Quadric::sphere(base, r0) : Quadric::cone(base, r0, apex, r1));
    // A point of the surface, then moved off it by up to 1e-3 in any direction.
    glm::dvec3 onSurface;
    if (s.kind == Quadric::Kind::Sphere) {
      onSurface = s.base + s.baseRadius * glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)) + glm::dvec3(0, 0, 1e-3));
    } else {
      const glm::dvec3 w = s.apex - s.base, axis = glm::normalize(w);
      const glm::dvec3 helper = std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
      const glm::dvec3 e1 = glm::normalize(glm::cross(helper, axis)), e2 = glm::cross(axis, e1);
      const double f = 0.1 + 0.8 * std::fabs(u(rng)), angle = 3.2 * u(rng);
      onSurface = s.base + f * w + (s.baseRadius + f * (s.apexRadius - s.baseRadius)) *
                                       (std::cos(angle) * e1 + std::sin(angle) * e2);
    }
    const glm::dvec3 p = projectOntoQuadric(s, onSurface + 1e-3 * glm::dvec3(u(rng), u(rng), u(rng)));
    // On the surface, near the point it came from.
    EXPECT_LT(std::fabs(surfaceError(s, p)), 1e-12) << i;
    EXPECT_LT(glm::length(p - onSurface), 2e-3) << i;
  }
  // On the center or the axis: left where it is.
  const QuadricShape sphere = QuadricShape::of(Quadric::sphere({1, 2, 3}, 1));
  EXPECT_EQ(projectOntoQuadric(sphere, glm::dvec3(1, 2, 3)), glm::dvec3(1, 2, 3));
}

TEST(QuadricReference, BoundsHoldTheSurface) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f), radius(0.0f, 3.0f);
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 base(u(rng), u(rng), u(rng)), apex(u(rng), u(rng), u(rng));
    const Quadric q = Quadric::cone(base, radius(rng), apex, -radius(rng) - 0.01f);
    const Aabb box = q.bounds();
    const QuadricShape s = QuadricShape::of(q);
    const glm::dvec3 w = s.apex - s.base, axis = glm::normalize(w);
    const glm::dvec3 helper = std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(helper, axis)), e2 = glm::cross(axis, e1);
    for (int k = 0; k < 64; ++k) {
      const double angle = 2 * std::numbers::pi * k / 64;
      for (const double f : {0.0, 0.5, 1.0}) {
        const double r = s.baseRadius + f * (s.apexRadius - s.baseRadius);
        const glm::dvec3 p = s.base + f * w + r * (std::cos(angle) * e1 + std::sin(angle) * e2);
        for (int a = 0; a < 3; ++a) {
          EXPECT_LE(double(box.lo[a]), p[a]);
          EXPECT_GE(double(box.hi[a]), p[a]);
        }
      }
    }
  }
  const Aabb sphere = Quadric::sphere({1, 2, 3}, -0.5f).bounds();
  EXPECT_LE(sphere.lo.x, 0.5f);
  EXPECT_GE(sphere.hi.z, 3.5f);
  EXPECT_GT(sphere.lo.x, 0.49f);
}

TEST(QuadricReference, EntryPointsThatWouldDropQuadricsRefuseThem) {
  Scene scene;
  scene.name = "mixed";
  scene.triangles = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  scene.quadrics = {Quadric::sphere({0, 0, 2}, 1)};
  scene.materialOf = {0, 0};
  scene.materials.resize(1);
  scene.computeBounds();
  EXPECT_EQ(scene.primitiveCount(), 2u);
  EXPECT_TRUE(scene.isQuadric(1));
  EXPECT_FALSE(scene.isQuadric(0));
  EXPECT_GE(scene.bounds.hi.z, 3.0f);
  EXPECT_LT(scene.bounds.hi.z, 3.001f);
  const auto refuses = [](auto&& build) {
    try {
      build();
    } catch (const InputError& e) {
      return std::string(e.what()).find("quadrics not supported yet") != std::string::npos;
    }
    return false;
  };
  EXPECT_NO_THROW(Bvh(scene, {}));
  EXPECT_NO_THROW(UniformGrid(scene, {}));
  EXPECT_NO_THROW(Octree(scene, {}));
  EXPECT_NO_THROW(BruteForce{scene});
  EXPECT_TRUE(refuses([&] { Quantizer(scene.bounds).quantize(scene); }));
  EXPECT_TRUE(refuses([&] { writeScene(scene, std::filesystem::temp_directory_path() / "lancer_quadric_refused.obj"); }));
  // Without quadrics nothing changes.
  scene.quadrics.clear();
  scene.materialOf.resize(1);
  EXPECT_NO_THROW(Bvh(scene, {}));
}

}  // namespace
}  // namespace lancer
