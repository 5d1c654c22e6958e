#include "support/traversal_cases.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "driver/quantize.h"
#include "golden/isect.h"
#include "scene/camera.h"

namespace lancer::test {

using fx::kDirMax;
using fx::kPosMax;
using fx::QRay;
using fx::QTriangle;

QuantizedScene quantizedCamera(const Scene& scene, int width, int height) {
  const Quantizer quantizer(scene.bounds);
  QuantizedScene q;
  q.triangles = quantizer.quantize(scene);
  CameraOptions camera;
  camera.width = width;
  camera.height = height;
  const std::vector<Ray> rays = frameScene(scene, camera).generateRays();
  for (uint32_t i = 0; i < rays.size(); ++i) {
    if (auto r = quantizer.quantize(rays[i], i)) q.rays.push_back(r->q);
  }
  return q;
}

QRay normalizedDirection(QRay r) {
  const int k = fx::dominantAxis(r.dir);
  r.dir[k] = r.dir[k] < 0 ? -kDirMax : kDirMax;
  return r;
}

QRay randomLatticeRay(std::mt19937_64& rng, uint32_t id) {
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  return normalizedDirection(QRay{id, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}});
}

std::vector<QTriangle> randomLatticeTriangles(std::mt19937_64& rng, int count, int64_t lo, int64_t hi,
                                              int64_t spread) {
  std::uniform_int_distribution<int64_t> centre(lo, hi), off(-spread, spread);
  std::vector<QTriangle> tris;
  for (int i = 0; i < count; ++i) {
    QTriangle t;
    t.id = uint32_t(i);
    const std::array<int64_t, 3> c{centre(rng), centre(rng), centre(rng)};
    for (auto& v : t.v)
      for (int a = 0; a < 3; ++a) v[a] = std::clamp<int64_t>(c[a] + off(rng), 0, kPosMax);
    tris.push_back(t);
  }
  return tris;
}

TraversalRunOptions roughTraversalOptions(uint64_t seed, int raysInFlight) {
  TraversalRunOptions o;
  o.memLatency = 7;
  o.memLatencyJitter = 13;
  o.raysInFlight = raysInFlight;
  o.stream.outputStallProbability = 0.3;
  o.stream.inputIdleProbability = 0.2;
  o.stream.seed = seed;
  return o;
}

std::string describeLatticeRay(const QRay& r) {
  return fmt::format("ray {} org ({:#x}, {:#x}, {:#x}) dir ({}, {}, {})", r.id, r.org[0], r.org[1], r.org[2], r.dir[0],
                     r.dir[1], r.dir[2]);
}

std::string describeTraversalTrace(const fx::TraversalTrace& t, const char* element, size_t shown) {
  std::string s = fmt::format("{} {} [", t.visits.size(), element);
  for (size_t i = 0; i < std::min<size_t>(t.visits.size(), shown); ++i) s += fmt::format("{} ", t.visits[i]);
  if (t.visits.size() > shown) s += "...";
  s += fmt::format("] tests {} ", t.tests);
  if (t.hit) {
    s += fmt::format("hit prim {} t_num {:#x} det {:#x}", t.hit->primId, uint64_t(t.hit->tNum), uint64_t(t.hit->det));
  } else {
    s += "miss";
  }
  return s;
}

}  // namespace lancer::test
