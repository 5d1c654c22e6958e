#include "support/traversal_cases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

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

std::vector<QTriangle> quantizeScene(const Scene& scene) { return Quantizer(scene.bounds).quantize(scene); }

const std::vector<QTriangle>& quantizedCornell() {
  static const std::vector<QTriangle> tris = quantizeScene(makeCornellBox());
  return tris;
}

LatticePoint randomLatticePoint(std::mt19937_64& rng) {
  std::uniform_int_distribution<int64_t> pos(0, kPosMax);
  return {pos(rng), pos(rng), pos(rng)};
}

QRay aimedRay(const LatticePoint& org, const LatticePoint& target) {
  LatticePoint d{};
  int64_t big = 0;
  for (int a = 0; a < 3; ++a) big = std::max(big, std::abs(target[a] - org[a]));
  if (big == 0) return QRay{0, org, {kDirMax, 0, 0}};
  for (int a = 0; a < 3; ++a) d[a] = std::llround(double(target[a] - org[a]) * double(kDirMax) / double(big));
  return normalizedDirection(QRay{0, org, d});
}

void addOctantRays(std::vector<QRay>& rays, const LatticePoint& org, const LatticePoint& dir) {
  for (int octant = 0; octant < 8; ++octant) {
    LatticePoint d = dir;
    for (int a = 0; a < 3; ++a) {
      if (octant & (4 >> a)) d[a] = -d[a];
    }
    rays.push_back(normalizedDirection(QRay{0, org, d}));
  }
}

void numberCaseRays(std::string_view unit, const std::string& name, std::vector<QRay>& rays) {
  for (uint32_t i = 0; i < rays.size(); ++i) {
    QRay& r = rays[i];
    r.id = i;
    for (int a = 0; a < 3; ++a) {
      if (r.org[a] < 0 || r.org[a] > kPosMax || std::abs(r.dir[a]) > kDirMax) {
        throw std::logic_error(fmt::format("{} case {}: ray {} is off the lattice", unit, name, i));
      }
    }
    if (r.dir == LatticePoint{0, 0, 0}) {
      throw std::logic_error(fmt::format("{} case {}: ray {} has no direction", unit, name, i));
    }
  }
}

QRay randomLatticeRay(std::mt19937_64& rng, uint32_t id) {
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  return normalizedDirection(QRay{id, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}});
}

LatticePoint centroid(const QTriangle& t) {
  LatticePoint c{};
  for (int a = 0; a < 3; ++a) c[a] = (t.v[0][a] + t.v[1][a] + t.v[2][a]) / 3;
  return c;
}

std::vector<QRay> randomLatticeRays(uint64_t seed, uint32_t count) {
  std::mt19937_64 rng(seed);
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < count; ++i) rays.push_back(randomLatticeRay(rng, i));
  return rays;
}

void addRandomRays(std::vector<QRay>& rays, std::mt19937_64& rng, int count) {
  for (int i = 0; i < count; ++i) rays.push_back(randomLatticeRay(rng, 0));
}

void addAimedRays(std::vector<QRay>& rays, const std::vector<QTriangle>& tris, std::mt19937_64& rng, int count) {
  if (tris.empty()) return;
  std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
  for (int i = 0; i < count; ++i) {
    const QTriangle& t = tris[pick(rng)];
    rays.push_back(aimedRay(randomLatticePoint(rng), centroid(t)));
  }
}

std::vector<QRay> randomAndAimedRays(std::mt19937_64& rng, const std::vector<QTriangle>& tris, int random,
                                     int aimed) {
  std::vector<QRay> rays;
  addRandomRays(rays, rng, random);
  addAimedRays(rays, tris, rng, aimed);
  return rays;
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

SegmentCode segmentCodeOf(const fx::IsectResult& hit) {
  // 2^F t_num / det without forming 2^F t_num (which may not fit 128 bits).
  const fx::u128 whole = hit.tNum / hit.det, rest = hit.tNum % hit.det;
  const fx::u128 scaledRest = rest << fx::kSegFracBits;
  return {uint64_t((whole << fx::kSegFracBits) + scaledRest / hit.det), scaledRest % hit.det == 0};
}

std::optional<fx::IsectResult> bruteForceHit(std::span<const QTriangle> triangles, const QRay& ray) {
  std::optional<fx::IsectResult> best;
  for (const QTriangle& t : triangles) {
    const fx::IsectResult r = fx::intersect(ray, t);
    if (r.hit && (!best || fx::closerResult(r, *best))) best = r;
  }
  return best;
}

std::vector<QRay> segmentVariants(std::span<const QTriangle> triangles, std::span<const QRay> rays, size_t maxRays) {
  std::vector<QRay> out;
  const auto add = [&](QRay r, uint64_t tMax, bool anyHit) {
    r.id = uint32_t(out.size());
    r.tMax = std::min(tMax, fx::kSegEndNone);
    r.anyHit = anyHit;
    out.push_back(r);
  };
  for (size_t i = 0; i < std::min(maxRays, rays.size()); ++i) {
    const QRay& ray = rays[i];
    const int k = fx::dominantAxis(ray.dir);
    const int64_t toEdge = ray.dir[k] > 0 ? kPosMax - ray.org[k] : ray.org[k];
    add(ray, uint64_t(toEdge / 4) << fx::kSegFracBits, false);  // a light inside the lattice
    add(ray, fx::kSegEndNone, true);                            // a light outside it
    if (const auto hit = bruteForceHit(triangles, ray)) {
      const SegmentCode code = segmentCodeOf(*hit);
      add(ray, code.floor, false);
      add(ray, code.floor + 1, false);
      if (code.floor > 0) add(ray, code.floor - 1, false);
      add(ray, code.floor + 1, true);
    }
  }
  return out;
}

QuantizedScene segmentScene(int64_t zWall, int64_t zOrigin) {
  QuantizedScene s;
  const int64_t lo = kPosMax / 8, hi = kPosMax - kPosMax / 8, mid = (lo + hi) / 2;
  const int64_t zOccluder = (zWall + zOrigin) / 2, half = kPosMax / 16;
  s.triangles.push_back({0, {{{lo, lo, zWall}, {hi, lo, zWall}, {hi, hi, zWall}}}});
  s.triangles.push_back({1, {{{lo, lo, zWall}, {hi, hi, zWall}, {lo, hi, zWall}}}});
  s.triangles.push_back({2, {{{mid - half, mid - half, zOccluder}, {mid + half, mid - half, zOccluder},
                              {mid, mid + half, zOccluder}}}});
  const int64_t sign = zWall > zOrigin ? 1 : -1;
  const uint64_t toWall = uint64_t(std::llabs(zWall - zOrigin)) << fx::kSegFracBits;
  const uint64_t toOccluder = uint64_t(std::llabs(zOccluder - zOrigin)) << fx::kSegFracBits;
  const auto add = [&](int64_t x, int64_t y, int64_t dx, int64_t dy, uint64_t tMax, bool anyHit) {
    QRay r{uint32_t(s.rays.size()), {x, y, zOrigin}, {dx, dy, sign * kDirMax}};
    r.tMax = tMax;
    r.anyHit = anyHit;
    s.rays.push_back(r);
  };
  // Through the occluder's centre and beside it, straight and oblique (|dx|, |dy| < DIR_MAX keeps z dominant).
  const std::array<std::array<int64_t, 4>, 6> starts{{{mid, mid, 0, 0},
                                                      {lo + half, lo + half, 0, 0},
                                                      {mid - 3 * half, mid, kDirMax / 3, 0},
                                                      {mid, mid - 3 * half, 0, kDirMax / 5},
                                                      {mid + half, mid + half, -kDirMax / 7, -kDirMax / 9},
                                                      {hi - half, lo + half, -kDirMax / 11, kDirMax / 13}}};
  for (const auto& [x, y, dx, dy] : starts) {
    for (const bool anyHit : {false, true}) {
      add(x, y, dx, dy, toWall, anyHit);                             // ends exactly at the wall: the hit counts
      add(x, y, dx, dy, toWall - 1, anyHit);                         // one code short: it does not
      add(x, y, dx, dy, (toOccluder + toWall) / 2, anyHit);          // a light between occluder and wall
      add(x, y, dx, dy, toOccluder / 2, anyHit);                     // a light before the occluder
      add(x, y, dx, dy, toOccluder, anyHit);                         // ends exactly at the occluder's plane
      add(x, y, dx, dy, fx::kSegEndNone, anyHit);                    // no end
    }
  }
  return s;
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

TraversalRunOptions treeletStressOptions(int units, int queueKib) {
  TraversalRunOptions o;
  o.units = units;
  o.memory.kind = mem::MemoryKind::Hierarchy;
  o.stream.outputStallProbability = 0.3;
  o.stream.inputIdleProbability = 0.2;
  o.treelets = true;
  o.queues.kib = queueKib;
  o.dispatchBatch = 4;
  return o;
}

}  // namespace lancer::test
