#pragma once

// Random mixed scenes of issue #40 (docs/oracle.md, "Quadrics in the exact
// arbiter and the float reference"): spheres, cones (a third cylinders, a
// third pointed) and triangles near the origin; rays from around them aimed
// at points of the primitives and at random, a third of them hard (grazing a
// sphere's silhouette, at a cone's rim, from a point of a surface). The exact
// arbiter judges the float reference and Embree on them
// (tests/oracle/exact_quadric_test.cpp); the float structures are checked
// against brute force on them (tests/ref/mixed_structures_test.cpp).

#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "driver/quantize.h"
#include "golden/quadric.h"
#include "golden/records.h"
#include "ref/quadric.h"
#include "scene/scene.h"

namespace lancer::test {

// A scene of these triangles and quadrics, one material.
inline Scene mixedScene(std::vector<Triangle> triangles, std::vector<Quadric> quadrics) {
  Scene scene;
  scene.name = "test";
  scene.triangles = std::move(triangles);
  scene.quadrics = std::move(quadrics);
  scene.materialOf.assign(scene.primitiveCount(), 0);
  scene.materials.resize(1);
  scene.computeBounds();
  return scene;
}

struct RandomScenes {
  std::mt19937 rng{4040};
  std::uniform_real_distribution<float> u{-1.0f, 1.0f};

  glm::vec3 point(float scale) { return scale * glm::vec3(u(rng), u(rng), u(rng)); }

  Scene scene(int triangles, int quadrics) {
    std::vector<Triangle> tris;
    for (int i = 0; i < triangles; ++i) {
      const glm::vec3 c = point(4.0f);
      tris.push_back({c + point(1.5f), c + point(1.5f), c + point(1.5f)});
    }
    std::vector<Quadric> qs;
    for (int i = 0; i < quadrics; ++i) {
      const glm::vec3 c = point(4.0f);
      const float r = 0.2f + 1.2f * std::fabs(u(rng));
      switch (i % 4) {
        case 0: qs.push_back(Quadric::sphere(c, i % 8 ? r : -r)); break;
        case 1: qs.push_back(Quadric::cone(c, r, c + point(2.0f), r)); break;
        case 2: qs.push_back(Quadric::cone(c, r, c + point(2.0f), 0.0f)); break;
        default: qs.push_back(Quadric::cone(c, r, c + point(2.0f), 0.1f + std::fabs(u(rng)))); break;
      }
    }
    return mixedScene(std::move(tris), std::move(qs));
  }

  // A unit vector perpendicular to `axis`.
  glm::dvec3 perpendicular(const glm::dvec3& axis) {
    const glm::dvec3 a = glm::normalize(axis);
    const glm::dvec3 v = glm::dvec3(point(1.0f)) + glm::dvec3(1e-3, 0, 0);
    return glm::normalize(v - glm::dot(v, a) * a);
  }

  // A hard ray at a quadric: grazing a sphere's silhouette, aimed at a cone's
  // rim, or from a point of the surface (all rounded to floats: within ~1e-7
  // of the exact grazing or on-surface ray).
  Ray hardRay(const Quadric& q) {
    const glm::dvec3 o(point(9.0f));
    const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
    if (q.kind == Quadric::Kind::Sphere && kind == 0) {
      const glm::dvec3 c(q.base), oc = o - c;
      const double r = std::fabs(double(q.baseRadius)), l2 = glm::dot(oc, oc);
      if (l2 <= r * r) return Ray{glm::vec3(o), point(1.0f)};
      const glm::dvec3 tangent = c + (r * r / l2) * oc + r * std::sqrt(1.0 - r * r / l2) * perpendicular(oc);
      return Ray{glm::vec3(o), glm::vec3(tangent - o)};
    }
    const QuadricShape s = QuadricShape::of(q);
    glm::dvec3 onSurface;
    if (q.kind == Quadric::Kind::Sphere) {
      onSurface = s.base + s.baseRadius * glm::normalize(glm::dvec3(point(1.0f)) + glm::dvec3(0, 0, 1e-3));
    } else {
      const glm::dvec3 w = s.apex - s.base, e = perpendicular(w);
      const double f = kind == 0 ? 0.0 : (kind == 1 ? 1.0 : std::fabs(u(rng)));
      onSurface = s.base + f * w + (s.baseRadius + f * (s.apexRadius - s.baseRadius)) * e;
    }
    if (kind == 2) return Ray{glm::vec3(onSurface), point(1.0f)};  // from the surface
    return Ray{glm::vec3(o), glm::vec3(onSurface - o)};            // at it (a cone: its rims)
  }

  // A ray from outside the primitives' region towards a point near one of
  // them (or anywhere), some with a segment end; every third a hard ray at a
  // quadric.
  Ray ray(const Scene& scene) {
    if (!scene.quadrics.empty() && std::uniform_int_distribution<int>(0, 2)(rng) == 0) {
      const size_t i = std::uniform_int_distribution<size_t>(0, scene.quadrics.size() - 1)(rng);
      return hardRay(scene.quadrics[i]);
    }
    const glm::vec3 origin = point(9.0f);
    glm::vec3 target = point(5.0f);
    const uint32_t n = uint32_t(scene.primitiveCount());
    const uint32_t pick = std::uniform_int_distribution<uint32_t>(0, 2 * n)(rng);
    if (pick < n) {
      if (scene.isQuadric(pick)) {
        const Quadric& q = scene.quadricOf(pick);
        target = q.kind == Quadric::Kind::Sphere ? q.base + std::fabs(q.baseRadius) * glm::normalize(point(1.0f))
                                                 : q.base + std::fabs(u(rng)) * (q.apex - q.base) + point(0.5f);
      } else {
        const Triangle& t = scene.triangles[pick];
        const float a = std::fabs(u(rng)), b = (1.0f - a) * std::fabs(u(rng));
        target = t.v0 + a * (t.v1 - t.v0) + b * (t.v2 - t.v0);
      }
    }
    const float tMax = std::fabs(u(rng)) < 0.2f ? 2.0f * std::fabs(u(rng)) : kInfinity;
    return Ray{origin, target - origin, tMax};
  }
};

// A random mixed scene (RandomScenes, seeded) on the lattice: its triangles and
// quadrics quantized as the driver quantizes them, and `rays` of its rays
// that enter the lattice, ids 0, 1, ... (what the traversal units' tests give
// their images and devices).
struct QuantizedMixedScene {
  std::vector<fx::QTriangle> triangles;
  std::vector<fx::QQuadric> quadrics;
  std::vector<fx::QRay> rays;
};
inline QuantizedMixedScene quantizedMixedScene(int triangles, int quadrics, int rays, uint32_t seed) {
  RandomScenes random;
  random.rng.seed(seed);
  const Scene scene = random.scene(triangles, quadrics);
  const Quantizer quantizer(scene.bounds);
  QuantizedMixedScene q{quantizer.quantizeTriangles(scene), quantizer.quantizeQuadrics(scene), {}};
  while (int(q.rays.size()) < rays) {
    if (const auto ray = quantizer.quantize(random.ray(scene), uint32_t(q.rays.size()))) q.rays.push_back(ray->q);
  }
  return q;
}

}  // namespace lancer::test
