#include "isect/isect_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "golden/isect.h"

namespace lancer::rtltest {

namespace {

using fx::kDirMax;
using fx::kPosMax;

// The most negative direction code: valid two's complement, never produced by
// quantization (the format's kDirMax is symmetric), but the RTL must still match.
constexpr int64_t kDirMin = -kDirMax - 1;

class Rng {
 public:
  explicit Rng(uint64_t seed) : gen_(seed) {}
  int64_t uniform(int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(gen_); }
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }
  bool coin(double p = 0.5) { return real(0.0, 1.0) < p; }
  uint32_t id() { return uint32_t(gen_()); }
  template <typename T>
  const T& pick(const std::vector<T>& v) { return v[size_t(uniform(0, int64_t(v.size()) - 1))]; }
  Vec3 pos() { return {uniform(0, kPosMax), uniform(0, kPosMax), uniform(0, kPosMax)}; }
  Vec3 dirCode() { return {uniform(-kDirMax, kDirMax), uniform(-kDirMax, kDirMax), uniform(-kDirMax, kDirMax)}; }

 private:
  std::mt19937_64 gen_;
};

int64_t clampPos(int64_t v) { return std::clamp<int64_t>(v, 0, kPosMax); }
int64_t clampDir(int64_t v) { return std::clamp<int64_t>(v, -kDirMax, kDirMax); }

// A direction as the quantizer makes it: dominant component +-kDirMax, the
// others rounded to nearest. Zero vectors become +z.
Vec3 quantizeDir(double x, double y, double z) {
  const double m = std::max({std::abs(x), std::abs(y), std::abs(z)});
  if (m == 0.0) return {0, 0, kDirMax};
  const double s = double(kDirMax) / m;
  return {clampDir(std::llround(x * s)), clampDir(std::llround(y * s)), clampDir(std::llround(z * s))};
}

Vec3 quantizeDir(const Vec3& from, const std::array<double, 3>& to) {
  return quantizeDir(to[0] - double(from[0]), to[1] - double(from[1]), to[2] - double(from[2]));
}

IsectRequest pair(uint32_t rayId, const Vec3& org, const Vec3& dir, uint32_t primId, const Vec3& a,
                  const Vec3& b, const Vec3& c) {
  return IsectRequest{fx::QRay{rayId, org, dir}, fx::QTriangle{primId, {a, b, c}}};
}

// A point of the triangle's plane by barycentrics (outside it when u, v stray).
std::array<double, 3> planePoint(const Vec3& a, const Vec3& b, const Vec3& c, double u, double v) {
  std::array<double, 3> p{};
  for (int k = 0; k < 3; ++k) p[k] = double(a[k]) + u * double(b[k] - a[k]) + v * double(c[k] - a[k]);
  return p;
}

// A ray through the lattice point p at t = 1: org = p - dir. The direction is
// a quantized one (dominant +-kDirMax) when the lattice leaves room for it,
// otherwise the largest dominant component that keeps org on the lattice.
// `spread` bounds the lateral components relative to the dominant one.
fx::QRay rayThrough(uint32_t id, const Vec3& p, Rng& rng, double spread) {
  const int axis = int(rng.uniform(0, 2));
  Vec3 d{};
  // Dominant component: the sign that keeps org = p - d on the lattice.
  const int64_t roomPos = p[axis];            // d > 0 moves org down by d
  const int64_t roomNeg = kPosMax - p[axis];  // d < 0 moves org up by |d|
  bool positive = rng.coin();
  if (positive && roomPos < kDirMax && roomNeg >= kDirMax) positive = false;
  if (!positive && roomNeg < kDirMax && roomPos >= kDirMax) positive = true;
  const int64_t room = positive ? roomPos : roomNeg;
  const int64_t m = std::max<int64_t>(1, std::min(kDirMax, room));
  d[axis] = positive ? m : -m;
  const int64_t lateral = std::max<int64_t>(0, int64_t(double(m) * spread));
  for (int k = 0; k < 3; ++k) {
    if (k == axis) continue;
    // org[k] = p[k] - d[k] must stay in [0, kPosMax].
    const int64_t lo = std::max(-lateral, p[k] - kPosMax), hi = std::min(lateral, p[k]);
    d[k] = lo <= hi ? rng.uniform(lo, hi) : 0;
  }
  return fx::QRay{id, {p[0] - d[0], p[1] - d[1], p[2] - d[2]}, d};
}

}  // namespace

std::vector<IsectRequest> randomPairs(size_t count, uint64_t seed) {
  Rng rng(seed);
  std::vector<IsectRequest> out;
  out.reserve(count);
  const int64_t small = std::max<int64_t>(2, kPosMax >> 6);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t rayId = uint32_t(i);
    const uint32_t primId = rng.id();
    const int kind = int(rng.uniform(0, 7));
    Vec3 a, b, c;
    if (kind <= 3) {  // large triangles
      a = rng.pos(), b = rng.pos(), c = rng.pos();
    } else {  // small triangles anywhere in the cube
      const Vec3 centre = rng.pos();
      auto near = [&] {
        return Vec3{clampPos(centre[0] + rng.uniform(-small, small)),
                    clampPos(centre[1] + rng.uniform(-small, small)),
                    clampPos(centre[2] + rng.uniform(-small, small))};
      };
      a = near(), b = near(), c = near();
    }
    const Vec3 org = rng.pos();
    Vec3 dir;
    if (kind == 6) {
      dir = rng.dirCode();  // unaimed, arbitrary codes: mostly misses
    } else {
      // Aimed at a point of the plane, inside the triangle or just outside it.
      double u = rng.real(-0.05, 1.05), v = rng.real(-0.05, 1.05);
      if (u + v > 1.1) u = 1.0 - u, v = 1.0 - v;
      dir = quantizeDir(org, planePoint(a, b, c, u, v));
      if (kind == 7) {  // the same direction, scaled down: not normalized
        const int64_t shift = rng.uniform(1, 8);
        for (auto& d : dir) d /= (int64_t(1) << shift);
        if (dir == Vec3{0, 0, 0}) dir = {0, 0, 1};
      }
    }
    out.push_back(pair(rayId, org, dir, primId, a, b, c));
  }
  return out;
}

std::vector<fx::QTriangle> octahedron() {
  const int64_t c = kPosMax / 2, r = kPosMax / 4;
  std::vector<fx::QTriangle> faces;
  uint32_t id = 100;
  for (int sx : {1, -1}) {
    for (int sy : {1, -1}) {
      for (int sz : {1, -1}) {
        const Vec3 x{c + sx * r, c, c}, y{c, c + sy * r, c}, z{c, c, c + sz * r};
        // Counter-clockwise seen from outside: flip when an odd number of signs is negative.
        if (sx * sy * sz > 0) {
          faces.push_back(fx::QTriangle{id++, {x, y, z}});
        } else {
          faces.push_back(fx::QTriangle{id++, {x, z, y}});
        }
      }
    }
  }
  return faces;
}

std::vector<IsectRequest> watertightRays(size_t rays, uint64_t seed) {
  Rng rng(seed);
  const auto mesh = octahedron();
  const int64_t c = kPosMax / 2, r = kPosMax / 4;
  // The 6 vertices, and the 12 edges as pairs of (axis, sign).
  std::vector<Vec3> vertices;
  for (int axis = 0; axis < 3; ++axis) {
    for (int s : {1, -1}) {
      Vec3 v{c, c, c};
      v[axis] += s * r;
      vertices.push_back(v);
    }
  }
  auto edgePoint = [&] {
    const int a = int(rng.uniform(0, 2));
    const int b = (a + 1 + int(rng.uniform(0, 1))) % 3;
    const int64_t sa = rng.coin() ? 1 : -1, sb = rng.coin() ? 1 : -1;
    // Lattice points of the edge from c + sa*r*e_a to c + sb*r*e_b, ends included.
    const int64_t s = rng.coin(0.1) ? (rng.coin() ? 0 : r) : rng.uniform(0, r);
    Vec3 p{c, c, c};
    p[a] += sa * (r - s);
    p[b] += sb * s;
    return p;
  };
  auto interiorPoint = [&] {  // strictly inside: |x-c| + |y-c| + |z-c| < r
    for (;;) {
      const Vec3 o{c + rng.uniform(-r, r), c + rng.uniform(-r, r), c + rng.uniform(-r, r)};
      if (std::llabs(o[0] - c) + std::llabs(o[1] - c) + std::llabs(o[2] - c) < r) return o;
    }
  };
  // Directions from the centre that point exactly at vertices, edge midpoints
  // and face centres, then random ones.
  std::vector<Vec3> centreDirs;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) centreDirs.push_back({x * kDirMax, y * kDirMax, z * kDirMax});

  std::vector<IsectRequest> out;
  out.reserve(rays * mesh.size());
  for (size_t i = 0; i < rays; ++i) {
    const uint32_t id = uint32_t(i);
    fx::QRay ray;
    const int kind = int(rng.uniform(0, 5));
    if (kind == 0 || kind == 1) {  // from outside (or inside) through a vertex / edge point
      const Vec3 p = kind == 0 ? rng.pick(vertices) : edgePoint();
      ray = rayThrough(id, p, rng, rng.coin() ? 0.125 : 1.0);
    } else if (kind == 2) {  // from an interior point exactly through a vertex or edge point
      const Vec3 p = rng.coin() ? rng.pick(vertices) : edgePoint();
      for (;;) {
        const Vec3 o = interiorPoint();
        const Vec3 d{p[0] - o[0], p[1] - o[1], p[2] - o[2]};
        if (std::max({std::llabs(d[0]), std::llabs(d[1]), std::llabs(d[2])}) <= kDirMax &&
            d != Vec3{0, 0, 0}) {
          ray = fx::QRay{id, o, d};
          break;
        }
      }
    } else if (kind == 3) {  // from the centre, special and random directions
      const Vec3 d = i < centreDirs.size() ? centreDirs[i] : quantizeDir(rng.real(-1, 1), rng.real(-1, 1), rng.real(-1, 1));
      ray = fx::QRay{id, {c, c, c}, d};
    } else {  // from a random interior point in a random quantized direction
      ray = fx::QRay{id, interiorPoint(), quantizeDir(rng.real(-1, 1), rng.real(-1, 1), rng.real(-1, 1))};
    }
    for (const auto& face : mesh) out.push_back(IsectRequest{ray, face});
  }
  return out;
}

std::vector<IsectRequest> watertightTetraRays(size_t rays, uint64_t seed) {
  Rng rng(seed);
  std::vector<IsectRequest> out;
  out.reserve(rays * kTetraFaces);
  const int64_t grid = kPosMax / 4;  // vertices at 4 * (0 .. grid)
  std::array<Vec3, 4> v{};
  Vec3 centroid{};
  uint32_t primId = 0;
  for (size_t i = 0; i < rays; ++i) {
    if (i % 16 == 0) {  // a new tetrahedron every 16 rays, of non-zero volume
      for (int64_t volume = 0; volume == 0;) {
        for (auto& p : v) p = {4 * rng.uniform(0, grid), 4 * rng.uniform(0, grid), 4 * rng.uniform(0, grid)};
        Vec3 e[3];
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) e[k][j] = v[k + 1][j] - v[0][j];
        volume = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                 e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                 e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      }
      for (int j = 0; j < 3; ++j) centroid[j] = (v[0][j] + v[1][j] + v[2][j] + v[3][j]) / 4;
    }
    // A vertex or a lattice point of an edge (at k/4 of its length).
    const int a = int(rng.uniform(0, 3)), b = (a + 1 + int(rng.uniform(0, 2))) % 4;
    const int64_t k = rng.coin(0.3) ? 0 : rng.uniform(1, 3);
    Vec3 p{};
    for (int j = 0; j < 3; ++j) p[j] = v[a][j] + k * (v[b][j] - v[a][j]) / 4;
    fx::QRay ray;
    const Vec3 d{p[0] - centroid[0], p[1] - centroid[1], p[2] - centroid[2]};
    const int kind = int(rng.uniform(0, 2));
    if (kind == 0 && d != Vec3{0, 0, 0} &&
        std::max({std::llabs(d[0]), std::llabs(d[1]), std::llabs(d[2])}) <= kDirMax) {
      ray = fx::QRay{uint32_t(i), centroid, d};  // from inside, exactly through p
    } else if (kind == 1) {  // from inside in a random direction
      ray = fx::QRay{uint32_t(i), centroid, quantizeDir(rng.real(-1, 1), rng.real(-1, 1), rng.real(-1, 1))};
    } else {  // through p at t = 1, from wherever the direction puts the origin
      ray = rayThrough(uint32_t(i), p, rng, rng.coin() ? 0.25 : 1.0);
    }
    const uint32_t id = primId;
    primId += 4;
    // Faces of a closed tetrahedron, consistently oriented or not: the test is two-sided.
    out.push_back(IsectRequest{ray, fx::QTriangle{id, {v[0], v[1], v[2]}}});
    out.push_back(IsectRequest{ray, fx::QTriangle{id + 1, {v[0], v[3], v[1]}}});
    out.push_back(IsectRequest{ray, fx::QTriangle{id + 2, {v[0], v[2], v[3]}}});
    out.push_back(IsectRequest{ray, fx::QTriangle{id + 3, {v[1], v[3], v[2]}}});
  }
  return out;
}

std::vector<CaseGroup> hardCases(uint64_t seed) {
  Rng rng(seed);
  std::vector<CaseGroup> groups;
  uint32_t rayId = 0;
  const int64_t mid = kPosMax / 2, q = kPosMax / 4;

  {  // Zero-area triangles: collinear, two and three coincident vertices.
    CaseGroup g{"degenerate", {}};
    for (int i = 0; i < 400; ++i) {
      const Vec3 a = rng.pos();
      Vec3 bb = rng.pos(), c;
      switch (i % 4) {
        case 0: {  // b and c on a lattice line through a: a + m*s, a + k*s
          const int64_t span = std::max<int64_t>(1, kPosMax / 8);
          for (bool inside = false; !inside;) {
            const Vec3 step{rng.uniform(-span, span), rng.uniform(-span, span), rng.uniform(-span, span)};
            const int64_t m = rng.uniform(-3, 3), k = rng.uniform(-3, 3);
            inside = true;
            for (int j = 0; j < 3; ++j) {
              bb[j] = a[j] + m * step[j];
              c[j] = a[j] + k * step[j];
              inside = inside && bb[j] == clampPos(bb[j]) && c[j] == clampPos(c[j]);
            }
          }
          break;
        }
        case 1: c = a; break;
        case 2: c = bb; break;
        default: bb = a, c = a; break;  // all three equal
      }
      const Vec3 org = rng.pos();
      const auto target = planePoint(a, bb, c, rng.real(0, 1), rng.real(0, 1));
      g.pairs.push_back(pair(rayId++, org, quantizeDir(org, target), rng.id(), a, bb, c));
      // And a ray exactly through the first vertex.
      g.pairs.push_back(IsectRequest{rayThrough(rayId++, a, rng, 0.5), fx::QTriangle{rng.id(), {a, bb, c}}});
    }
    // Collinear at the lattice's extremes.
    g.pairs.push_back(pair(rayId++, {mid, mid, 0}, {0, 0, kDirMax}, 1, {0, 0, kPosMax},
                           {kPosMax, kPosMax, kPosMax}, {mid, mid, kPosMax}));
    groups.push_back(std::move(g));
  }

  {  // Needles: two far vertices, the third one lattice step off their midpoint.
    CaseGroup g{"needle", {}};
    for (int i = 0; i < 400; ++i) {
      const Vec3 a = rng.pos(), b = rng.pos();
      Vec3 c{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
      const size_t k = size_t(rng.uniform(0, 2));
      c[k] += c[k] < kPosMax ? 1 : -1;
      c = {clampPos(c[0]), clampPos(c[1]), clampPos(c[2])};
      const Vec3 org = rng.pos();
      const auto target = planePoint(a, b, c, rng.real(0, 1), rng.real(0, 0.02));
      g.pairs.push_back(pair(rayId++, org, quantizeDir(org, target), rng.id(), a, b, c));
      // Rays exactly through the tip and through the needle's far vertex.
      g.pairs.push_back(IsectRequest{rayThrough(rayId++, c, rng, 0.3), fx::QTriangle{rng.id(), {a, b, c}}});
      g.pairs.push_back(IsectRequest{rayThrough(rayId++, b, rng, 1.0), fx::QTriangle{rng.id(), {a, b, c}}});
    }
    // The thinnest needle across the whole lattice.
    g.pairs.push_back(pair(rayId++, {mid, 1, mid}, {0, 0, kDirMax}, 2, {0, 0, kPosMax},
                           {kPosMax, 0, kPosMax}, {mid, 1, kPosMax}));
    groups.push_back(std::move(g));
  }

  {  // Rays parallel to the triangle's plane: in it and one lattice step off it.
    CaseGroup g{"parallel", {}};
    for (int i = 0; i < 300; ++i) {
      const int axis = int(rng.uniform(0, 2));  // the plane is axis = level
      const int64_t level = rng.uniform(0, kPosMax);
      auto inPlane = [&] {
        Vec3 v = rng.pos();
        v[axis] = level;
        return v;
      };
      const Vec3 a = inPlane(), b = inPlane(), c = inPlane();
      Vec3 org = inPlane();
      const int64_t off = i % 3 == 0 ? 0 : (i % 3 == 1 ? 1 : -1);
      org[axis] = clampPos(level + off);
      auto target = planePoint(a, b, c, rng.real(0, 1), rng.real(0, 0.5));
      target[axis] = double(org[axis]);
      Vec3 dir = quantizeDir(org, target);
      dir[axis] = 0;
      if (dir == Vec3{0, 0, 0}) dir[(axis + 1) % 3] = kDirMax;
      g.pairs.push_back(pair(rayId++, org, dir, rng.id(), a, b, c));
    }
    // A tilted plane (normal (1,1,0)) and a ray along it.
    g.pairs.push_back(pair(rayId++, {0, q, 0}, {kDirMax, -kDirMax, 0}, 3, {q, 0, 0}, {0, q, kPosMax},
                           {q, 0, kPosMax}));
    groups.push_back(std::move(g));
  }

  {  // Direction components 0 and +-1 (and a direction of magnitude 1).
    CaseGroup g{"tiny_dirs", {}};
    const std::vector<int64_t> tiny{0, 1, -1};
    for (int i = 0; i < 400; ++i) {
      const int axis = int(rng.uniform(0, 2));
      Vec3 dir{rng.pick(tiny), rng.pick(tiny), rng.pick(tiny)};
      dir[axis] = rng.coin(0.9) ? (rng.coin() ? kDirMax : -kDirMax) : (rng.coin() ? 1 : -1);
      // A triangle around the ray's path, the ray passing near an edge or vertex.
      const Vec3 org = rng.pos();
      const int64_t depth = rng.uniform(1, kPosMax / 4);
      Vec3 p{};
      for (int k = 0; k < 3; ++k) {
        const int64_t step = dir[axis] > 0 ? depth : -depth;
        p[k] = clampPos(org[k] + (k == axis ? step : dir[k] * depth / kDirMax));
      }
      const int64_t s = rng.uniform(1, std::max<int64_t>(1, kPosMax / 32));
      Vec3 a = p, b = p, c = p;
      a[(axis + 1) % 3] = clampPos(a[(axis + 1) % 3] - rng.uniform(0, s));
      b[(axis + 1) % 3] = clampPos(b[(axis + 1) % 3] + rng.uniform(0, s));
      c[(axis + 2) % 3] = clampPos(c[(axis + 2) % 3] + rng.uniform(-s, s));
      g.pairs.push_back(pair(rayId++, org, dir, rng.id(), a, b, c));
    }
    groups.push_back(std::move(g));
  }

  {  // Ties of the dominant axis: |dx| = |dy|, |dy| = |dz|, |dx| = |dz|, all three.
    CaseGroup g{"axis_ties", {}};
    for (int i = 0; i < 400; ++i) {
      const int64_t m = rng.coin(0.8) ? kDirMax : rng.uniform(1, kDirMax);
      Vec3 dir{};
      const int tie = i % 4;
      for (int k = 0; k < 3; ++k) dir[k] = rng.coin() ? m : -m;
      if (tie < 3) dir[size_t(tie)] = rng.uniform(-(m - 1), m - 1);  // the other two tie
      const Vec3 org = rng.pos();
      // A triangle straddling the ray's path.
      const int64_t t = rng.uniform(1, std::max<int64_t>(1, kPosMax / (2 * std::max<int64_t>(1, m))));
      Vec3 p{};
      for (int k = 0; k < 3; ++k) p[k] = clampPos(org[k] + dir[k] * t);
      const int64_t s = std::max<int64_t>(1, kPosMax / 16);
      const Vec3 a{clampPos(p[0] - s), clampPos(p[1] + s), clampPos(p[2])};
      const Vec3 b{clampPos(p[0] + s), clampPos(p[1]), clampPos(p[2] - s)};
      const Vec3 c{clampPos(p[0]), clampPos(p[1] - s), clampPos(p[2] + s)};
      g.pairs.push_back(pair(rayId++, org, dir, rng.id(), a, b, c));
    }
    groups.push_back(std::move(g));
  }

  {  // Ties between triangles: a shared edge crossed at one t, coincident copies.
    CaseGroup g{"triangle_ties", {}};
    for (int i = 0; i < 200; ++i) {
      const Vec3 a = rng.pos(), b = rng.pos(), c = rng.pos(), d = rng.pos();
      // Through a lattice point of the shared edge a-b when there is one: its midpoint.
      const Vec3 onEdge{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
      const fx::QRay ray = rayThrough(rayId++, onEdge, rng, 1.0);
      const uint32_t id = rng.id();
      g.pairs.push_back(IsectRequest{ray, fx::QTriangle{id, {a, b, c}}});
      g.pairs.push_back(IsectRequest{ray, fx::QTriangle{id + 1, {b, a, d}}});
      // Coincident copies with other ids and other vertex orders.
      g.pairs.push_back(IsectRequest{ray, fx::QTriangle{id + 2, {b, c, a}}});
      g.pairs.push_back(IsectRequest{ray, fx::QTriangle{id + 3, {a, c, b}}});
    }
    groups.push_back(std::move(g));
  }

  {  // The largest and smallest coordinates and directions.
    CaseGroup g{"extremes", {}};
    const std::vector<int64_t> coords{0, 1, kPosMax - 1, kPosMax};
    const std::vector<int64_t> dirs{kDirMin, -kDirMax, -1, 0, 1, kDirMax};
    const std::vector<int64_t> bigDirs{kDirMin, -kDirMax, kDirMax};
    auto corner = [&](const std::vector<int64_t>& set) { return Vec3{rng.pick(set), rng.pick(set), rng.pick(set)}; };
    for (int i = 0; i < 3000; ++i) {
      Vec3 dir = corner(i % 2 ? dirs : bigDirs);
      if (dir == Vec3{0, 0, 0}) dir = {kDirMax, 0, 0};
      g.pairs.push_back(pair(rayId++, corner(coords), dir, rng.id(), corner(coords), corner(coords), corner(coords)));
    }
    // Every triangle with corners of the cube, from every corner origin, along
    // the diagonal directions with one component in the lead: these reach the
    // largest shear, edge, det and T magnitudes the formats allow.
    const int64_t lead = kDirMax, side = kDirMax - 1;
    for (int v = 0; v < 512; ++v) {
      Vec3 t[3];
      for (int k = 0; k < 9; ++k) t[k / 3][size_t(k % 3)] = (v >> k) & 1 ? kPosMax : 0;
      const Vec3 org{(v & 1) ? 0 : kPosMax, (v & 2) ? kPosMax : 0, (v & 4) ? 0 : kPosMax};
      for (int axis = 0; axis < 3; ++axis) {
        Vec3 dir{};
        for (int k = 0; k < 3; ++k) dir[k] = ((v + axis) >> k) & 1 ? side : -side;
        dir[axis] = (v >> 3) & 1 ? lead : -lead;
        g.pairs.push_back(pair(rayId++, org, dir, uint32_t(v), t[0], t[1], t[2]));
      }
    }
    groups.push_back(std::move(g));
  }

  {  // Segment ends (t_max) and the any-hit flag. Each hit of random pairs again
     // with its segment ending at the hit's code, floor(2^F t_num / det) (the hit
     // counts iff that is exact), one code past it (it counts), one short of it
     // (it does not), at 0 and at the largest bounded end; each miss with a
     // random end. any_hit on every other pair: the pipeline tests it the same.
    CaseGroup g{"segment_ends", {}};
    bool anyHit = false;
    const auto add = [&](IsectRequest r, uint64_t tMax) {
      r.ray.id = rayId++;
      r.ray.tMax = std::min(tMax, fx::kSegEndNone);
      r.ray.anyHit = anyHit = !anyHit;
      g.pairs.push_back(r);
    };
    for (const IsectRequest& r : randomPairs(600, seed + 3)) {
      const fx::IsectResult hit = fx::intersect(r.ray, r.tri);
      if (!hit.hit) {
        add(r, uint64_t(rng.uniform(0, int64_t(fx::kSegEndNone) - 1)));
        continue;
      }
      const fx::u128 whole = hit.tNum / hit.det, rest = hit.tNum % hit.det;
      const uint64_t code = whole > (fx::kSegEndNone >> fx::kSegFracBits)
                                ? fx::kSegEndNone
                                : uint64_t((whole << fx::kSegFracBits) + (rest << fx::kSegFracBits) / hit.det);
      add(r, code);
      add(r, code + 1);
      if (code > 0) add(r, code - 1);
      add(r, 0);
      add(r, fx::kSegEndNone - 1);
    }
    groups.push_back(std::move(g));
  }
  return groups;
}

std::vector<IsectRequest> allHardCases(uint64_t seed) {
  std::vector<IsectRequest> all;
  for (auto& group : hardCases(seed)) all.insert(all.end(), group.pairs.begin(), group.pairs.end());
  const auto mesh = watertightRays(600, seed + 1);
  all.insert(all.end(), mesh.begin(), mesh.end());
  const auto tetra = watertightTetraRays(600, seed + 2);
  all.insert(all.end(), tetra.begin(), tetra.end());
  return all;
}

}  // namespace lancer::rtltest
