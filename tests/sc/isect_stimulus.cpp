#include "isect_stimulus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include <fmt/format.h>

#include "golden/records.h"

namespace lancer::sctest {

namespace {

using fx::kDirMax;
using fx::kPosMax;
using Vec = std::array<int64_t, 3>;

int64_t uniform(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return std::uniform_int_distribution<int64_t>(lo, hi)(rng);
}

int64_t clampPos(int64_t v) { return std::clamp<int64_t>(v, 0, kPosMax); }

// A quantized direction: component `axis` is +-kDirMax, the others anything.
Vec randomDir(std::mt19937_64& rng) {
  Vec d{uniform(rng, -kDirMax, kDirMax), uniform(rng, -kDirMax, kDirMax),
        uniform(rng, -kDirMax, kDirMax)};
  d[size_t(uniform(rng, 0, 2))] = uniform(rng, 0, 1) ? kDirMax : -kDirMax;
  return d;
}

// A ray that passes exactly through `target` at t = 1: origin = target - dir,
// with the dominant axis `axis` and the other components drawn so the origin
// stays on the lattice. nonzero: no zero component (never parallel to an axis plane).
fx::QRay aimAt(uint32_t id, const Vec& target, int axis, std::mt19937_64& rng, bool nonzero) {
  Vec d{};
  for (int i = 0; i < 3; ++i) {
    const size_t k = size_t(i);
    if (i == axis) {
      d[k] = target[k] >= kDirMax ? kDirMax : -kDirMax;  // needs kPosMax >= 2 kDirMax
      continue;
    }
    const int64_t lo = std::max(-kDirMax, target[k] - kPosMax), hi = std::min(kDirMax, target[k]);
    do {
      d[k] = uniform(rng, lo, hi);
    } while (nonzero && d[k] == 0 && hi > lo);
  }
  return fx::QRay{id, {target[0] - d[0], target[1] - d[1], target[2] - d[2]}, d};
}

std::string hexWire(const fx::Wire& wire) {
  std::string out = "0x";
  for (size_t i = wire.size(); i-- > 0;) out += fmt::format("{}{:08x}", i + 1 < wire.size() ? "_" : "", wire[i]);
  return out;
}

}  // namespace

std::vector<IsectRequest> randomPairs(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<IsectRequest> pairs;
  pairs.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    IsectRequest r;
    r.ray.id = uint32_t(i);
    r.ray.org = {uniform(rng, 0, kPosMax), uniform(rng, 0, kPosMax), uniform(rng, 0, kPosMax)};
    r.ray.dir = randomDir(rng);
    r.tri.id = uint32_t(rng());
    if (uniform(rng, 0, 1) == 0) {
      // A point p of the ray inside the lattice cube, and a triangle whose
      // centroid is p (so it contains p in every projection): mostly hits,
      // some grazing ones when the ray passes p off the lattice point.
      double tMax = 1e300;
      for (size_t k = 0; k < 3; ++k) {
        const double d = double(r.ray.dir[k]);
        if (d > 0) tMax = std::min(tMax, double(kPosMax - r.ray.org[k]) / d);
        if (d < 0) tMax = std::min(tMax, double(r.ray.org[k]) / -d);
      }
      const double t = tMax * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      Vec p{}, a{}, b{};
      const int64_t extent = std::array<int64_t, 3>{2, 64, kPosMax / 8}[size_t(uniform(rng, 0, 2))];
      for (size_t k = 0; k < 3; ++k) {
        p[k] = clampPos(std::llround(double(r.ray.org[k]) + double(r.ray.dir[k]) * t));
        a[k] = uniform(rng, -extent, extent);
        b[k] = uniform(rng, -extent, extent);
      }
      for (size_t k = 0; k < 3; ++k) {
        r.tri.v[0][k] = clampPos(p[k] + a[k]);
        r.tri.v[1][k] = clampPos(p[k] + b[k]);
        r.tri.v[2][k] = clampPos(p[k] - a[k] - b[k]);
      }
    } else {
      for (auto& v : r.tri.v)
        for (auto& c : v) c = uniform(rng, 0, kPosMax);
    }
    pairs.push_back(r);
  }
  return pairs;
}

HardCases hardCases() {
  HardCases hard;
  std::mt19937_64 rng(2024);
  uint32_t rayId = 0x10000;
  auto add = [&](const fx::QRay& ray, const fx::QTriangle& tri) { hard.pairs.push_back({ray, tri}); };

  // ---- A closed lattice mesh: the box [lo, hi]^3, each face an n x n grid of
  // quads split into two triangles (diagonals alternating). Even spacing, so
  // every edge midpoint is a lattice point.
  const int n = 3;
  const int64_t lo = kPosMax / 4;
  const int64_t spacing = std::max<int64_t>(2, (kPosMax / 2) / n / 2 * 2);
  std::vector<fx::QTriangle> mesh;
  std::set<Vec> targets;
  for (int axis = 0; axis < 3; ++axis) {
    for (const int64_t side : {lo, lo + n * spacing}) {
      auto point = [&](int i, int j) {
        Vec p{};
        p[size_t(axis)] = side;
        p[size_t((axis + 1) % 3)] = lo + i * spacing;
        p[size_t((axis + 2) % 3)] = lo + j * spacing;
        return p;
      };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const Vec a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
          const uint32_t id = uint32_t(mesh.size());
          if ((i + j) % 2 == 0) {
            mesh.push_back({id, {a, b, c}});
            mesh.push_back({id + 1, {a, c, d}});
          } else {
            mesh.push_back({id, {a, b, d}});
            mesh.push_back({id + 1, {b, c, d}});
          }
        }
      }
    }
  }
  for (const fx::QTriangle& tri : mesh) {
    for (int e = 0; e < 3; ++e) {
      const Vec& p = tri.v[size_t(e)];
      const Vec& q = tri.v[size_t((e + 1) % 3)];
      targets.insert(p);
      targets.insert(Vec{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
    }
  }
  for (const Vec& target : targets) {
    const fx::QRay ray = aimAt(rayId++, target, int(uniform(rng, 0, 2)), rng, true);
    hard.meshRays.push_back(ray.id);
    for (const fx::QTriangle& tri : mesh) add(ray, tri);
  }

  // ---- Degenerate and needle triangles, with rays through their points.
  const int64_t c = (kPosMax + 1) / 2;
  const Vec center{c, c, c};
  const int64_t w = kPosMax / 8;
  const std::vector<fx::QTriangle> degenerate = {
      {1, {center, center, center}},                                            // a point
      {2, {Vec{c - w, c - w, c}, center, Vec{c + w, c + w, c}}},                // a segment
      {3, {center, center, Vec{c + w, c - w, c + 1}}},                          // two equal vertices
      {4, {Vec{c - w, c, c}, Vec{c + w, c, c}, Vec{c - w, c + 1, c}}},          // needle, 1 unit wide
      {5, {Vec{c - w, c - w, c - w}, Vec{c + w, c + w, c + w}, Vec{c + w, c + w, c + w - 1}}},  // needle
      {6, {Vec{0, 0, 0}, Vec{kPosMax, kPosMax, kPosMax}, Vec{kPosMax, kPosMax, kPosMax - 1}}},  // long needle
  };
  for (const fx::QTriangle& tri : degenerate) {
    std::vector<Vec> aims(tri.v.begin(), tri.v.end());
    for (int e = 0; e < 3; ++e) {
      const Vec& p = tri.v[size_t(e)];
      const Vec& q = tri.v[size_t((e + 1) % 3)];
      aims.push_back(Vec{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
    }
    for (const Vec& target : aims) {
      for (int axis = 0; axis < 3; ++axis) add(aimAt(rayId++, target, axis, rng, false), tri);
    }
  }

  // ---- Rays in the plane of their triangle: z = c, and the tilted plane x + y = 2c.
  const fx::QTriangle flat{7, {Vec{c - w, c - w, c}, Vec{c + w, c - w, c}, Vec{c, c + w, c}}};
  const fx::QTriangle tilted{8, {Vec{c - w, c + w, c - w}, Vec{c + w, c - w, c - w}, Vec{c, c, c + w}}};
  for (const Vec& d : {Vec{kDirMax, 0, 0}, Vec{0, -kDirMax, 0}, Vec{kDirMax, 3, 0}, Vec{-kDirMax, kDirMax, 0}}) {
    add(fx::QRay{rayId++, {c - d[0], c - d[1], c}, d}, flat);
  }
  for (const Vec& d : {Vec{kDirMax, -kDirMax, 0}, Vec{kDirMax, -kDirMax, 5}, Vec{-kDirMax, kDirMax, -kDirMax},
                       Vec{1, -1, kDirMax}, Vec{0, 0, kDirMax}}) {
    add(fx::QRay{rayId++, {c - d[0], c - d[1], c - d[2]}, d}, tilted);
  }

  // ---- Directions with 0 and +-1 components and dominant-axis ties, through
  // the center of triangles in the three axis planes and a slanted one.
  std::vector<fx::QTriangle> around;
  for (int axis = 0; axis < 3; ++axis) {
    fx::QTriangle tri{uint32_t(10 + axis), {center, center, center}};
    tri.v[0][size_t((axis + 1) % 3)] -= w;
    tri.v[1][size_t((axis + 1) % 3)] += w;
    tri.v[1][size_t((axis + 2) % 3)] -= w;
    tri.v[2][size_t((axis + 2) % 3)] += w;
    around.push_back(tri);
  }
  around.push_back({13, {Vec{c - w, c, c - w}, Vec{c + w, c - w, c}, Vec{c, c + w, c + w}}});
  const std::vector<Vec> specialDirs = {
      {kDirMax, 0, 0},   {-kDirMax, 0, 0}, {0, kDirMax, 0},   {0, -kDirMax, 0},  {0, 0, kDirMax},
      {0, 0, -kDirMax},  {kDirMax, 1, -1}, {-1, kDirMax, 1},  {1, -1, -kDirMax}, {kDirMax, kDirMax, 0},
      {kDirMax, -kDirMax, kDirMax},        {-kDirMax, -kDirMax, -kDirMax},      {kDirMax, kDirMax - 1, 1},
      {-1, -1, kDirMax}, {1, 1, -kDirMax}, {0, 1, kDirMax},   {-kDirMax, 0, 1},
  };
  for (const Vec& d : specialDirs) {
    for (const Vec& offset : {Vec{0, 0, 0}, Vec{1, 0, 0}, Vec{0, -1, 1}, Vec{w, w, w}}) {
      const Vec target{c + offset[0], c + offset[1], c + offset[2]};
      const fx::QRay ray{rayId++, {clampPos(target[0] - d[0]), clampPos(target[1] - d[1]),
                                   clampPos(target[2] - d[2])}, d};
      for (const fx::QTriangle& tri : around) add(ray, tri);
    }
  }

  // ---- Extreme coordinates: origins at the corners and face centers of the
  // lattice cube, every direction in {-kDirMax, 0, kDirMax}^3, triangles with
  // vertices at 0 and kPosMax.
  std::vector<Vec> origins;
  for (int corner = 0; corner < 8; ++corner) {
    origins.push_back({corner & 1 ? kPosMax : 0, corner & 2 ? kPosMax : 0, corner & 4 ? kPosMax : 0});
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (const int64_t side : {int64_t(0), kPosMax}) {
      Vec o{c, c, c};
      o[size_t(axis)] = side;
      origins.push_back(o);
    }
  }
  const int64_t m = kPosMax;
  const std::vector<fx::QTriangle> extreme = {
      {20, {Vec{0, 0, 0}, Vec{m, 0, 0}, Vec{0, m, 0}}},
      {21, {Vec{m, m, m}, Vec{0, m, m}, Vec{m, 0, m}}},
      {22, {Vec{m, 0, 0}, Vec{0, m, 0}, Vec{0, 0, m}}},
      {23, {Vec{0, m, m}, Vec{m, 0, m}, Vec{m, m, 0}}},
      {24, {Vec{0, 0, m}, Vec{m, m, m}, Vec{m, 0, 0}}},
      {25, {Vec{m, m, 0}, Vec{0, 0, 0}, Vec{0, m, m}}},
  };
  for (const Vec& o : origins) {
    for (int code = 0; code < 27; ++code) {
      const Vec d{(code % 3 - 1) * kDirMax, (code / 3 % 3 - 1) * kDirMax, (code / 9 - 1) * kDirMax};
      if (d == Vec{0, 0, 0}) continue;
      const fx::QRay ray{rayId++, o, d};
      for (const fx::QTriangle& tri : extreme) add(ray, tri);
    }
  }
  return hard;
}

std::string describe(const IsectRequest& request) {
  const fx::QRay& r = request.ray;
  const fx::QTriangle& t = request.tri;
  return fmt::format("ray {} org ({}, {}, {}) dir ({}, {}, {}) tri {} v0 ({}, {}, {}) v1 ({}, {}, {}) "
                     "v2 ({}, {}, {}); wires ray {} tri {}",
                     r.id, r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1], r.dir[2], t.id, t.v[0][0],
                     t.v[0][1], t.v[0][2], t.v[1][0], t.v[1][1], t.v[1][2], t.v[2][0], t.v[2][1],
                     t.v[2][2], hexWire(fx::packWire(r)), hexWire(fx::packWire(t)));
}

std::string describe(const fx::IsectResult& result) { return hexWire(fx::packWire(result)); }

void expectSameStats(const StreamStats& got, const StreamStats& want, std::string_view who) {
  EXPECT_EQ(got.cycles, want.cycles) << who;
  EXPECT_EQ(got.requests, want.requests) << who;
  EXPECT_EQ(got.results, want.results) << who;
  EXPECT_EQ(got.inputStalls, want.inputStalls) << who;
}

}  // namespace lancer::sctest
