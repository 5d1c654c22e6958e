#include "stress/cases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <random>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/quantize.h"
#include "golden/formats.h"
#include "scene/obj.h"
#include "driver/cracks.h"

namespace lancer::stress {

namespace {

// Random draws in a fixed order: every draw is its own statement, so the
// values do not depend on the compiler's order of evaluating arguments.
class Draw {
 public:
  explicit Draw(uint64_t seed) : rng_(seed) {}
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool coin() { return integer(0, 1) == 1; }
  template <class T>
  const T& pick(const std::vector<T>& items) {
    return items[size_t(integer(0, int(items.size()) - 1))];
  }
  glm::vec3 point(float lo, float hi) {
    const float x = uniform(lo, hi);
    const float y = uniform(lo, hi);
    const float z = uniform(lo, hi);
    return {x, y, z};
  }
  glm::vec3 unit() {
    for (;;) {
      const glm::vec3 p = point(-1.0f, 1.0f);
      const float len = glm::length(p);
      if (len > 0.1f && len <= 1.0f) return p / len;
    }
  }
  // Log-uniform in [lo, hi].
  double logUniform(double lo, double hi) {
    const double e = std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng_);
    return std::exp(e);
  }
  // Barycentric point of a triangle, inside it.
  glm::vec3 inside(const Triangle& t) {
    float u = uniform(0.0f, 1.0f);
    float v = uniform(0.0f, 1.0f);
    if (u + v > 1.0f) {
      u = 1.0f - u;
      v = 1.0f - v;
    }
    return t.v0 + u * (t.v1 - t.v0) + v * (t.v2 - t.v0);
  }
  // A point on one of the triangle's edges.
  glm::vec3 onEdge(const Triangle& t) {
    const glm::vec3 corners[3] = {t.v0, t.v1, t.v2};
    const int e = integer(0, 2);
    const float s = uniform(0.0f, 1.0f);
    return corners[e] + s * (corners[(e + 1) % 3] - corners[e]);
  }
  std::mt19937_64& engine() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

StressCase named(std::string name, std::string description) {
  StressCase c;
  c.name = std::move(name);
  c.description = std::move(description);
  return c;
}

Scene makeScene(std::string name, std::vector<Triangle> triangles) {
  Scene s;
  s.name = std::move(name);
  s.triangles = std::move(triangles);
  s.materials.push_back(Material{.name = "stress"});
  s.materialOf.assign(s.triangles.size(), 0);
  s.computeBounds();
  return s;
}

// Random triangles with vertices within `size` of random centres in [-1, 1]^3.
std::vector<Triangle> randomTriangles(Draw& draw, int count, float minSize, float maxSize) {
  std::vector<Triangle> out;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 c = draw.point(-0.8f, 0.8f);
    const float size = draw.uniform(minSize, maxSize);
    const glm::vec3 a = c + size * draw.unit();
    const glm::vec3 b = c + size * draw.unit();
    const glm::vec3 d = c + size * draw.unit();
    out.push_back({a, b, d});
  }
  return out;
}

// A ray from a random point around the scene through `target`.
Ray aimedAt(Draw& draw, const glm::vec3& target, float distance) {
  const glm::vec3 from = target + distance * draw.unit();
  return {from, target - from, kInfinity};
}

// The shape of the cases on randomTriangles(draw, count, minSize, maxSize).
struct RandomTriangles {
  int count;
  float minSize, maxSize;
};

// A case `name` on random triangles whose every ray is drawn at one of them,
// picked at random: rayAt(draw, triangle, scene) gives the ray, or none to
// pick again.
template <class RayAt>
StressCase raysAtTriangles(std::string name, std::string description, size_t rays, uint64_t seed,
                           RandomTriangles shape, RayAt rayAt) {
  StressCase c = named(name, std::move(description));
  Draw draw(seed);
  c.scene = makeScene("stress:" + name, randomTriangles(draw, shape.count, shape.minSize, shape.maxSize));
  while (c.rays.size() < rays) {
    const Triangle& t = draw.pick(c.scene.triangles);
    if (const std::optional<Ray> ray = rayAt(draw, t, c.scene)) c.rays.push_back(*ray);
  }
  return c;
}

// ---- closed-mesh --------------------------------------------------------------

StressCase closedMesh(size_t rays, uint64_t seed) {
  StressCase c = named("closed-mesh", "closed icosphere, rays at its shared vertices and edges (lattice-exact and float)");
  c.scene = makeScene("stress:closed-mesh", makeIcosphere(3).triangles);
  const Quantizer quantizer(c.scene.bounds);
  const CrackRays cracks = makeCrackRays(c.scene, quantizer, rays / 2, seed);
  c.rays = cracks.rays;
  c.latticeRejected = cracks.rejected;
  Draw draw(seed);
  while (c.rays.size() < rays) {
    const Triangle& t = draw.pick(c.scene.triangles);
    const glm::vec3 target = draw.coin() ? t.v0 : 0.5f * (t.v0 + t.v1);
    // From outside, within about 30 degrees of the inward normal: the ray crosses
    // the surface transversally and goes on through the interior.
    const glm::vec3 from = target * 3.0f + 0.8f * draw.unit();
    c.rays.push_back({from, target - from, kInfinity});
  }
  c.mustHit = c.rays.size();
  return c;
}

// ---- closed-box -----------------------------------------------------------------

// A point on the surface of the box [-1, 1]^3 where `onFaces` axes are pinned
// to a face (1: inside a face, 2: on an edge, 3: a corner), the others inside.
glm::vec3 onBoxSurface(Draw& draw, int onFaces) {
  glm::vec3 p = draw.point(-0.95f, 0.95f);
  const int skip = draw.integer(0, 2);  // for an edge: the one free axis; for a face: the pinned one
  for (int a = 0; a < 3; ++a) {
    const bool pinned = onFaces == 3 || (onFaces == 2 ? a != skip : a == skip);
    if (pinned) p[a] = draw.coin() ? 1.0f : -1.0f;
  }
  return p;
}

// A ray from outside through `target` on the box's surface, entering it: every
// pinned axis of the target inward by at least 0.3, so the target lies inside
// the box's silhouette and the ray crosses the closed surface transversally.
Ray enteringAt(Draw& draw, const glm::vec3& target) {
  glm::vec3 dir;
  for (int a = 0; a < 3; ++a) {
    const float magnitude = draw.uniform(0.3f, 1.0f);
    dir[a] = std::fabs(target[a]) == 1.0f ? -target[a] * magnitude : draw.uniform(-1.0f, 1.0f);
  }
  const float distance = draw.uniform(0.5f, 4.0f);
  return {target - distance * dir, dir, kInfinity};
}

StressCase closedBox(size_t rays, uint64_t seed) {
  StressCase c = named("closed-box", "a closed box whose faces are the scene's bounds, with two walls across it; "
                                     "rays from outside through every face, edge, corner and wall seam");
  Draw draw(seed);
  std::vector<Triangle> triangles = boxTriangles(glm::vec3(-1.0f), glm::vec3(1.0f));
  // Two walls dividing the box into rooms, their edges on its faces.
  const auto wall = [&](int axis, float at) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::array<glm::vec3, 4> q;
    for (int k = 0; k < 4; ++k) {
      q[size_t(k)][axis] = at;
      q[size_t(k)][u] = (k == 1 || k == 2) ? 1.0f : -1.0f;
      q[size_t(k)][v] = k >= 2 ? 1.0f : -1.0f;
    }
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  };
  wall(0, 0.25f);
  wall(2, -0.5f);
  c.scene = makeScene("stress:closed-box", std::move(triangles));
  while (c.rays.size() < rays) {
    const int kind = draw.integer(0, 3);  // 0 face, 1 edge, 2 corner, 3 where a wall meets a face
    glm::vec3 target = onBoxSurface(draw, kind == 3 ? 1 : kind + 1);
    if (kind == 3) {
      // On a face that a wall meets, along the seam.
      const bool xWall = draw.coin();
      const int wallAxis = xWall ? 0 : 2;
      if (std::fabs(target[wallAxis]) == 1.0f) continue;
      target[wallAxis] = xWall ? 0.25f : -0.5f;
    }
    c.rays.push_back(enteringAt(draw, target));
  }
  c.mustHit = c.rays.size();
  return c;
}

// ---- axis-planes ----------------------------------------------------------------

StressCase axisPlanes(size_t rays, uint64_t seed) {
  StressCase c = named("axis-planes", "axis-parallel rays (+0/-0), rays in cell and node boundary planes, along their edges, "
                              "through their corners");
  Draw draw(seed);
  c.scene = makeScene("stress:axis-planes", randomTriangles(draw, 200, 0.05f, 0.35f));
  // 16 cells a side: cell boundaries at multiples of 2^(P-4), which are the
  // boundaries of the octree's nodes of depth 4 as well.
  constexpr int kCells = 16;
  c.accel.gridResolution = kCells;
  const Quantizer quantizer(c.scene.bounds);
  const int64_t cell = (int64_t(1) << fx::kPosBits) / kCells;

  // Axis-parallel float rays from anywhere in the bounds, the other components +0 or -0.
  const Aabb& b = c.scene.bounds;
  while (c.rays.size() < rays / 3) {
    const int axis = draw.integer(0, 2);
    glm::vec3 dir(draw.coin() ? 0.0f : -0.0f, draw.coin() ? 0.0f : -0.0f, draw.coin() ? 0.0f : -0.0f);
    dir[axis] = draw.coin() ? 1.0f : -1.0f;
    glm::vec3 from = b.lo + draw.point(0.0f, 1.0f) * b.diagonal();
    from[axis] = dir[axis] > 0 ? b.lo[axis] - 0.5f : b.hi[axis] + 0.5f;
    c.rays.push_back({from, dir, kInfinity});
  }
  // Lattice-exact rays: `snapped` coordinates of the origin on boundaries, the
  // direction 0 on the axes it must stay in (in a plane, along an edge) or +-1
  // on every axis from a corner (through the corners of every cell it crosses).
  while (c.rays.size() < rays) {
    const int kind = draw.integer(0, 2);  // 0: in a plane, 1: along an edge, 2: corner to corner
    std::array<int64_t, 3> org{};
    std::array<int, 3> d{};
    for (int a = 0; a < 3; ++a) org[size_t(a)] = draw.integer(0, int(fx::kPosMax));
    const int free = draw.integer(0, 2);
    for (int a = 0; a < 3; ++a) {
      const bool snap = kind == 2 || (kind == 0 ? a == free : a != free);
      if (snap) org[size_t(a)] = int64_t(draw.integer(0, kCells - 1)) * cell;
      const bool still = kind != 2 && snap;
      d[size_t(a)] = still ? 0 : (draw.coin() ? 1 : -1);
    }
    glm::dvec3 scenePoint = quantizer.latticeOrigin();
    for (int a = 0; a < 3; ++a) scenePoint[a] += double(org[size_t(a)]) * quantizer.unit();
    const Ray ray{glm::vec3(scenePoint), glm::vec3(float(d[0]), float(d[1]), float(d[2])), kInfinity};
    const std::optional<QuantizedRay> q = quantizer.quantize(ray, 0);
    bool exact = q && q->q.org == org;
    for (int a = 0; exact && a < 3; ++a) exact = q->q.dir[size_t(a)] == d[size_t(a)] * fx::kDirMax;
    if (!exact) {
      ++c.latticeRejected;
      if (c.latticeRejected > 100 * rays) throw InputError("stress case axis-planes: the lattice rejects every ray");
      continue;
    }
    c.rays.push_back(ray);
  }
  return c;
}

// ---- grazing ----------------------------------------------------------------------

StressCase grazing(size_t rays, uint64_t seed) {
  const auto rayAt = [](Draw& draw, const Triangle& t, const Scene&) -> std::optional<Ray> {
    const glm::vec3 n = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
    const glm::vec3 target = draw.coin() ? draw.inside(t) : draw.onEdge(t);
    // An in-plane direction, tilted out of the plane by a tiny angle.
    glm::vec3 along = glm::cross(n, draw.unit());
    if (glm::length(along) < 1e-3f) return std::nullopt;
    along = glm::normalize(along);
    const float angle = float(draw.logUniform(1e-7, 1e-2)) * (draw.coin() ? 1.0f : -1.0f);
    const glm::vec3 from = target - 1.5f * (along + angle * n);
    return Ray{from, target - from, kInfinity};
  };
  return raysAtTriangles("grazing", "rays 1e-2 to 1e-7 rad from a triangle's plane, at its inside and edges", rays,
                         seed, {60, 0.3f, 0.7f}, rayAt);
}

// ---- degenerate -------------------------------------------------------------------

StressCase degenerate(size_t rays, uint64_t seed) {
  StressCase c = named("degenerate", "zero-area, needle and sliver triangles among ordinary ones");
  Draw draw(seed);
  std::vector<Triangle> tris = randomTriangles(draw, 40, 0.1f, 0.4f);
  const size_t odd = tris.size();
  for (int i = 0; i < 30; ++i) {
    const glm::vec3 a = draw.point(-0.8f, 0.8f);
    const glm::vec3 dir = 0.5f * draw.unit();
    const glm::vec3 side = glm::normalize(glm::cross(dir, draw.unit()));
    const float tiny = float(draw.logUniform(1e-7, 1e-4));
    tris.push_back({a, a + dir, a + 0.375f * dir});              // collinear: zero area
    tris.push_back({a, a, a + dir});                             // a repeated vertex
    tris.push_back({a, a + tiny * side, a + dir});               // needle: one edge tiny
    tris.push_back({a, a + dir, a + 0.5f * dir + tiny * side});  // sliver: tiny height
  }
  c.scene = makeScene("stress:degenerate", std::move(tris));
  while (c.rays.size() < rays) {
    const size_t i = size_t(draw.integer(int(odd), int(c.scene.size()) - 1));
    const Triangle& t = c.scene.triangles[draw.integer(0, 3) == 0 ? size_t(draw.integer(0, int(odd) - 1)) : i];
    const glm::vec3 target = draw.coin() ? (t.v0 + t.v1 + t.v2) / 3.0f : (draw.coin() ? t.v1 : draw.onEdge(t));
    c.rays.push_back(aimedAt(draw, target, 2.0f));
  }
  return c;
}

// ---- coincident -------------------------------------------------------------------

StressCase coincident(size_t rays, uint64_t seed) {
  StressCase c = named("coincident", "duplicated triangles (same, rotated, reversed order) and overlapping coplanar ones");
  Draw draw(seed);
  const std::vector<Triangle> base = randomTriangles(draw, 30, 0.2f, 0.5f);
  std::vector<Triangle> tris;
  for (const Triangle& t : base) {
    tris.push_back(t);
    tris.push_back({t.v1, t.v2, t.v0});  // the same triangle, rotated
    tris.push_back({t.v0, t.v2, t.v1});  // reversed
    tris.push_back(t);                   // an exact copy, later id
    // Coplanar and overlapping (up to rounding): a corner at an edge's midpoint.
    tris.push_back({0.5f * (t.v0 + t.v1), t.v1, t.v2 + 0.5f * (t.v1 - t.v0)});
  }
  c.scene = makeScene("stress:coincident", std::move(tris));
  while (c.rays.size() < rays) {
    const Triangle& t = draw.pick(base);
    c.rays.push_back(aimedAt(draw, draw.integer(0, 3) ? draw.inside(t) : draw.onEdge(t), 2.0f));
  }
  return c;
}

// ---- origin-on-surface ----------------------------------------------------------

StressCase originOnSurface(size_t rays, uint64_t seed) {
  const auto rayAt = [](Draw& draw, const Triangle& t, const Scene&) -> std::optional<Ray> {
    const glm::vec3 from = draw.integer(0, 2) == 0 ? t.v2 : draw.inside(t);
    const glm::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
    glm::vec3 dir = draw.unit();
    if (draw.integer(0, 3) == 0) dir = glm::cross(n, dir);  // in the plane
    if (glm::length(dir) == 0.0f) return std::nullopt;
    return Ray{from, dir, kInfinity};
  };
  return raysAtTriangles("origin-on-surface", "rays from a vertex or a point of a triangle: away, into it, along it",
                         rays, seed, {80, 0.2f, 0.5f}, rayAt);
}

// ---- tiny-components ------------------------------------------------------------

StressCase tinyComponents(size_t rays, uint64_t seed) {
  const auto rayAt = [](Draw& draw, const Triangle& t, const Scene& scene) -> std::optional<Ray> {
    constexpr std::array<float, 7> kTiny = {0.0f, -0.0f, 1e-7f, 1e-20f, 1e-30f, 1e-38f, 1.4e-45f};
    const Aabb& b = scene.bounds;
    const int axis = draw.integer(0, 2);
    glm::vec3 dir;
    for (int a = 0; a < 3; ++a) {
      const float tiny = kTiny[size_t(draw.integer(0, int(kTiny.size()) - 1))];
      dir[a] = draw.coin() ? tiny : -tiny;
    }
    dir[axis] = draw.coin() ? 1.0f : -1.0f;
    // Through a point of the triangle along the near-axis direction.
    glm::vec3 from = draw.inside(t);
    from[axis] = dir[axis] > 0 ? b.lo[axis] - 0.25f : b.hi[axis] + 0.25f;
    return Ray{from, dir, kInfinity};
  };
  return raysAtTriangles("tiny-components", "direction components 1e-7 .. 1e-45 (subnormal), +0, -0 beside 1", rays,
                         seed, {120, 0.1f, 0.4f}, rayAt);
}

// ---- obj-text -------------------------------------------------------------------

// The OBJ text of a mesh whose vertices are `vertices` times 2^exponent, each
// written with 17 significant digits: the double, not a float.
std::string objText(const std::vector<glm::dvec3>& vertices, const std::vector<std::array<uint32_t, 3>>& faces,
                    int exponent) {
  std::string text = "# lancer stress case obj-text\n";
  for (const glm::dvec3& v : vertices) {
    text += fmt::format("v {:.17g} {:.17g} {:.17g}\n", std::ldexp(v.x, exponent), std::ldexp(v.y, exponent),
                        std::ldexp(v.z, exponent));
  }
  for (const auto& f : faces) text += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  return text;
}

StressCase objTextCase(size_t rays, uint64_t seed) {
  StressCase c = named("obj-text", "a closed mesh read from OBJ text of full-precision decimals, scaled as text; "
                                   "rays from 1000x its size away, directions of any length");
  Draw draw(seed);
  // An icosphere with its vertices moved off the floats, in double: each
  // coordinate a decimal that no float is.
  const Scene sphere = makeIcosphere(2);
  std::vector<glm::dvec3> vertices;
  std::map<std::tuple<float, float, float>, uint32_t> index;
  std::vector<std::array<uint32_t, 3>> faces;
  for (const Triangle& t : sphere.triangles) {
    std::array<uint32_t, 3> f{};
    int k = 0;
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      const auto [it, fresh] = index.try_emplace({v.x, v.y, v.z}, uint32_t(vertices.size()));
      if (fresh) {
        const double jitter = 1.0 + 1e-3 * double(draw.uniform(-1.0f, 1.0f));
        vertices.push_back(glm::dvec3(v) * (3.1377567211166024 * jitter));
      }
      f[size_t(k++)] = it->second;
    }
    faces.push_back(f);
  }
  c.readScaled = [vertices, faces](int exponent) {
    Scene s = readObj(objText(vertices, faces, exponent), fmt::format("stress:obj-text 2^{}", exponent), ".");
    s.name = "stress:obj-text";
    return s;
  };
  c.scene = c.readScaled(0);
  // From 1000 times the mesh's size away, aimed within about 30 degrees of the
  // inward normal at a vertex or inside a face: every ray crosses the closed mesh.
  const float size = glm::length(c.scene.bounds.diagonal());
  while (c.rays.size() < rays) {
    const Triangle& t = draw.pick(c.scene.triangles);
    const glm::vec3 target = draw.coin() ? t.v0 : draw.inside(t);
    const glm::vec3 outward = glm::normalize(target) + 0.5f * draw.unit();
    const glm::vec3 from = target + 1000.0f * size * glm::normalize(outward);
    const float length = float(draw.logUniform(1e-3, 1e3));
    c.rays.push_back({from, length * glm::normalize(target - from), kInfinity});
  }
  c.mustHit = c.rays.size();
  return c;
}

using Maker = std::function<StressCase(size_t, uint64_t)>;
const std::vector<std::pair<std::string, Maker>>& makers() {
  static const std::vector<std::pair<std::string, Maker>> all = {
      {"closed-mesh", closedMesh},   {"closed-box", closedBox},   {"axis-planes", axisPlanes}, {"grazing", grazing},
      {"degenerate", degenerate},    {"coincident", coincident},  {"origin-on-surface", originOnSurface},
      {"obj-text", objTextCase},     {"tiny-components", tinyComponents}};
  return all;
}

}  // namespace

const std::vector<std::string>& caseNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& [name, make] : makers()) out.push_back(name);
    return out;
  }();
  return names;
}

StressCase makeCase(const std::string& name, size_t rays, uint64_t seed) {
  for (const auto& [known, make] : makers()) {
    if (known == name) return make(std::max<size_t>(rays, 8), seed);
  }
  throw InputError(fmt::format("unknown stress case '{}' (available: {})", name, fmt::join(caseNames(), ", ")));
}

}  // namespace lancer::stress
