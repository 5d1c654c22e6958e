#include "isect/quadric_cases.h"

#include <algorithm>
#include <cstdlib>
#include <random>

#include "support/lattice_rays.h"

namespace lancer::rtltest {

namespace {

using fx::kDirMax;
using fx::kPosMax;
using Vec3 = std::array<int64_t, 3>;

fx::QRay rayFrom(const Vec3& org, const Vec3& dir, uint32_t id) {
  fx::QRay r;
  r.id = id;
  r.org = org;
  r.dir = dir;
  return r;
}

int64_t clampPos(int64_t v) { return std::clamp<int64_t>(v, 0, kPosMax); }

}  // namespace

std::vector<QuadricRequest> randomQuadricPairs(size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  std::vector<QuadricRequest> pairs;
  pairs.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    QuadricRequest req;
    const uint32_t id = uint32_t(i);
    Vec3 target{};
    if (i % 2 == 0) {
      const fx::QSphere s{id, {pos(rng), pos(rng), pos(rng)}, 1 + int64_t(rng() % uint64_t(kPosMax / (1 + rng() % 64)))};
      req.quadric = fx::sphereRecord(s);
      for (size_t k = 0; k < 3; ++k) target[k] = clampPos(s.center[k] + int64_t(rng() % uint64_t(2 * s.radius + 1)) - s.radius);
    } else {
      fx::LatticeCone cone;
      cone.base = {pos(rng), pos(rng), pos(rng)};
      const int64_t len = 1 + int64_t(rng() % uint64_t(std::max<int64_t>(1, kPosMax >> (rng() % 10))));
      for (size_t k = 0; k < 3; ++k) cone.apex[k] = clampPos(cone.base[k] + dir(rng) * len / kDirMax);
      if (cone.apex == cone.base) cone.apex[0] = cone.base[0] == 0 ? 1 : cone.base[0] - 1;
      const auto radius = [&] { return int64_t(rng() % uint64_t(1 + (kPosMax >> (2 + rng() % 12)))); };
      cone.baseRadius = radius();
      cone.apexRadius = i % 8 == 1 ? cone.baseRadius : i % 8 == 3 ? 0 : radius();
      if (cone.baseRadius == 0 && cone.apexRadius == 0) cone.baseRadius = 1;
      req.quadric = fx::coneRecord(id, cone);
      const double f = double(rng() % 1001) / 1000;
      const double r = double(cone.baseRadius) + f * double(cone.apexRadius - cone.baseRadius);
      for (size_t k = 0; k < 3; ++k)
        target[k] = cone.base[k] + int64_t(f * double(cone.apex[k] - cone.base[k]) + (double(rng() % 2001) / 1000 - 1) * r);
    }
    req.ray = rayFrom({pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}, id);
    req.ray.dir[size_t(rng() % 3)] = rng() % 2 ? kDirMax : -kDirMax;
    if (i % 4 < 2) req.ray.dir = test::latticeDirectionTo(req.ray.org, target);
    if (i % 5 == 0) req.ray.tMax = rng() % (fx::kSegEndNone / 2);
    pairs.push_back(req);
  }
  return pairs;
}

std::vector<QuadricCaseGroup> quadricHardCases() {
  const int64_t n = kPosMax + 1, mid = n / 2;
  const int64_t len = n / 8, x0 = n / 4, x1 = x0 + len, r = n / 32;
  const fx::QQuadric cylinder = fx::coneRecord(1, {{x0, mid, mid}, {x1, mid, mid}, r, r});
  const fx::QQuadric cone = fx::coneRecord(2, {{mid, mid - len / 2, mid}, {mid, mid + len / 2, mid}, 3 * r / 2, r / 2});
  const fx::QQuadric pointed = fx::coneRecord(3, {{mid, mid, mid - len / 2}, {mid, mid, mid + len / 2}, r, 0});
  std::vector<QuadricCaseGroup> groups;
  const auto group = [&](std::string name) -> std::vector<QuadricRequest>& {
    return groups.emplace_back(QuadricCaseGroup{std::move(name), {}}).pairs;
  };
  uint32_t id = 0;
  const auto add = [&](std::vector<QuadricRequest>& g, const fx::QQuadric& q, const Vec3& org, const Vec3& d,
                       uint64_t tMax = fx::kSegEndNone) {
    QuadricRequest req{rayFrom({clampPos(org[0]), clampPos(org[1]), clampPos(org[2])}, d, id++), q};
    req.ray.tMax = tMax;
    g.push_back(req);
  };

  auto& tangent = group("tangent rays and one unit further");
  for (const int64_t radius : {int64_t(1), int64_t(7), kPosMax / 4}) {
    const fx::QQuadric s = fx::sphereRecord({10, {mid, mid, mid}, radius});
    for (const int64_t off : {radius - 1, radius, radius + 1}) {
      add(tangent, s, {mid - radius - 100, mid + off, mid}, {kDirMax, 0, 0});
      add(tangent, s, {mid, mid - off, mid - radius - 100}, {0, 0, kDirMax});
    }
  }
  for (const int64_t off : {r - 1, r, r + 1}) add(tangent, cylinder, {x0 + len / 2, mid + off, mid - 3 * r}, {0, 0, kDirMax});

  auto& inside = group("from inside, behind, and the segment's end");
  const fx::QQuadric big = fx::sphereRecord({11, {mid, mid, mid}, std::max<int64_t>(2, n / 64)});
  const int64_t br = std::max<int64_t>(2, n / 64);
  add(inside, big, {mid, mid, mid}, {0, -kDirMax, 0});
  add(inside, big, {mid, mid, mid}, {kDirMax, kDirMax / 3, -kDirMax / 5});
  add(inside, big, {mid + 2 * br, mid, mid}, {kDirMax, 0, 0});
  for (const int64_t end : {br - 1, br, br + 1})
    add(inside, big, {mid - 2 * br, mid, mid}, {kDirMax, 0, 0}, uint64_t(end) << fx::kSegFracBits);

  auto& secondary = group("secondary rays one unit off the surface");
  for (const int64_t radius : {int64_t(2), int64_t(50) % n, kPosMax / 3}) {
    const fx::QQuadric s = fx::sphereRecord({12, {mid, mid, mid}, std::max<int64_t>(1, radius)});
    add(secondary, s, {mid + radius + 1, mid, mid}, {kDirMax, kDirMax / 3, 0});
    add(secondary, s, {mid, mid - radius - 1, mid}, {kDirMax / 5, -kDirMax, kDirMax / 7});
    add(secondary, s, {mid + radius - 1, mid, mid}, {-kDirMax, 0, 0});
  }
  add(secondary, cylinder, {x0 + len / 2, mid + r + 1, mid}, {0, kDirMax / 3, kDirMax});
  add(secondary, cylinder, {x0 + len / 2, mid + r - 1, mid}, {0, -kDirMax, kDirMax / 4});

  auto& axis = group("rays along a cylinder's axis");
  for (const int64_t dx : {kDirMax, -kDirMax}) {
    for (const int64_t x : {x0 - 10, x0 + len / 2, x1 + 10}) {
      for (const int64_t off : {int64_t(0), r / 2, r, 2 * r}) add(axis, cylinder, {x, mid + off, mid}, {dx, 0, 0});
    }
  }

  auto& rims = group("rims, open ends and the apex");
  for (const int64_t x : {x0, x1}) add(rims, cylinder, {x, mid - 3 * r, mid}, {0, kDirMax, 0});
  for (const int64_t x : {x0 - 1, x1 + 1}) add(rims, cylinder, {x, mid - 3 * r, mid}, {0, kDirMax, 0});
  add(rims, cylinder, {x0 - r, mid, mid}, {kDirMax, std::max<int64_t>(1, kDirMax / 64), 0});
  add(rims, cylinder, {x0 - 1, mid, mid}, {kDirMax, std::max<int64_t>(1, kDirMax / 64), 0});
  add(rims, cone, {mid - 3 * r, mid, mid}, {kDirMax, 0, 0});
  add(rims, cone, {mid, mid - len, mid}, {0, kDirMax, 0});
  add(rims, pointed, {mid - 3 * r, mid, mid + len / 2}, {kDirMax, 0, 0});
  add(rims, pointed, {mid - 3 * r, mid, mid}, {kDirMax, 0, 0});
  add(rims, pointed, {mid, mid, mid + len}, {0, 0, -kDirMax});

  auto& extremes = group("tiny and huge, the scene box, extreme codes");
  const fx::QQuadric tiny = fx::sphereRecord({13, {0, 0, 0}, 1});
  add(extremes, tiny, {0, 0, 40 % n}, {0, 0, -kDirMax});
  add(extremes, tiny, {kPosMax, kPosMax, kPosMax}, {-kDirMax, -kDirMax, -kDirMax});
  const int64_t half = kPosMax / 2;
  const fx::QQuadric huge = fx::sphereRecord({14, {half, half, half}, std::max<int64_t>(1, half)});
  add(extremes, huge, {0, half, half}, {kDirMax, 0, 0});
  add(extremes, huge, {0, 0, 0}, {kDirMax, kDirMax, kDirMax});
  add(extremes, huge, {kPosMax, kPosMax, kPosMax}, {-kDirMax, -kDirMax + 1, -kDirMax});
  const fx::QQuadric wide = fx::coneRecord(15, {{0, half, half}, {kPosMax, half, half}, std::max<int64_t>(1, half), 1});
  add(extremes, wide, {half, 0, half}, {0, kDirMax, 0});
  add(extremes, wide, {0, 0, 0}, {kDirMax, kDirMax, kDirMax / 2});
  for (const int64_t d0 : {-kDirMax, -kDirMax + 1, int64_t(-1), int64_t(0), int64_t(1), kDirMax - 1})
    add(extremes, huge, {half, half, 0}, {d0, -d0 / 2, kDirMax});
  return groups;
}

}  // namespace lancer::rtltest
