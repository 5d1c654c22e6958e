#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/assimp_scene.h"
#include "scene/gltf.h"
#include "scene/nff.h"
#include "scene/obj.h"
#include "scene/ply.h"
#include "scene/spd.h"
#include "scene/stl.h"
#include "scene/text.h"

namespace lancer {

void Scene::computeBounds() {
  bounds = Aabb{};
  for (const Triangle& t : triangles) bounds.extend(t.bounds());
  for (const Quadric& q : quadrics) bounds.extend(q.bounds());
}

void Scene::requireTrianglesOnly(std::string_view who) const {
  if (quadrics.empty()) return;
  throw InputError(fmt::format("{}: {} has {} quadrics (native spheres and cones): quadrics not supported yet here "
                               "(issue #40; read the scene with its spheres and cones tessellated)",
                               who, name, quadrics.size()));
}

namespace {

// A double rounded to the float at or below (lo) or at or above (hi) it.
float floatDown(double x) {
  const float f = static_cast<float>(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float floatUp(double x) {
  const float f = static_cast<float>(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

Aabb Quadric::bounds() const {
  // In double (every float and its products exact enough), each extent grown
  // by a relative 2^-40 for the square root's and the sums' rounding, then
  // rounded outwards to floats.
  glm::dvec3 lo, hi;
  if (kind == Kind::Sphere) {
    const double r = std::fabs(double(baseRadius));
    lo = glm::dvec3(base) - r;
    hi = glm::dvec3(base) + r;
  } else {
    const glm::dvec3 b(base), a(apex), w = a - b;
    const double ww = glm::dot(w, w);
    lo = glm::min(b, a);
    hi = glm::max(b, a);
    for (int axis = 0; axis < 3; ++axis) {
      const double spread = ww > 0.0 ? std::sqrt(std::max(0.0, 1.0 - w[axis] * w[axis] / ww)) * (1.0 + 0x1p-40) : 1.0;
      const double rb = std::fabs(double(baseRadius)) * spread, ra = std::fabs(double(apexRadius)) * spread;
      lo[axis] = std::min(b[axis] - rb, a[axis] - ra);
      hi[axis] = std::max(b[axis] + rb, a[axis] + ra);
    }
  }
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
    const double slack = 0x1p-40 * std::max(std::fabs(lo[axis]), std::fabs(hi[axis]));
    box.lo[axis] = floatDown(lo[axis] - slack);
    box.hi[axis] = floatUp(hi[axis] + slack);
  }
  return box;
}

const char* toString(SceneNumbers numbers) {
  switch (numbers) {
    case SceneNumbers::Exact: return "exact";
    case SceneNumbers::CorrectlyRounded: return "correctly_rounded";
    case SceneNumbers::AssimpText: return "assimp_text";
  }
  return "unknown";
}

std::vector<uint32_t> Scene::emissiveTriangles() const {
  std::vector<uint32_t> out;
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    if (glm::any(glm::greaterThan(materials[materialOf[t]].emission, glm::vec3(0.0f)))) out.push_back(t);
  }
  return out;
}

Scene::PrimitiveCounts Scene::primitivesByKind() const {
  PrimitiveCounts counts;
  counts.triangles = triangles.size();
  for (const Quadric& q : quadrics) ++(q.kind == Quadric::Kind::Sphere ? counts.spheres : counts.cones);
  return counts;
}

std::string Scene::primitivesText() const {
  const PrimitiveCounts c = primitivesByKind();
  std::string text = fmt::format("{} triangles", c.triangles);
  if (c.spheres) text += fmt::format(", {} sphere{}", c.spheres, c.spheres == 1 ? "" : "s");
  if (c.cones) text += fmt::format(", {} cone{}", c.cones, c.cones == 1 ? "" : "s");
  return text;
}

const char* toString(QuadricForm form) { return form == QuadricForm::Native ? "native" : "tessellate"; }

Scene loadScene(const std::string& nameOrPath, QuadricForm quadrics) {
  if (nameOrPath == kDefaultSceneName || nameOrPath == "cornell") return makeCornellBox();
  if (nameOrPath == "builtin:cube") return makeCube();
  if (nameOrPath.starts_with("builtin:spd-")) return loadSpdScene(nameOrPath.substr(12), quadrics);
  if (nameOrPath.starts_with("builtin:")) {
    throw InputError(fmt::format("unknown built-in scene '{}' (available: {}, builtin:cube, builtin:spd-tetra[@N], builtin:spd-gears[@N])", nameOrPath,
                                 kDefaultSceneName));
  }
  // The formats Lancer reads itself, whose numbers are correctly rounded
  // (docs/scenes.md, "Numbers"); glTF 2.0's binary buffers through assimp.
  const std::string extension = lowercase(std::filesystem::path(nameOrPath).extension().string());
  if (extension == ".obj") return loadObj(nameOrPath);
  if (extension == ".ply") return loadPly(nameOrPath);
  if (extension == ".stl") return loadStl(nameOrPath);
  if (extension == ".nff") {
    NffOptions options;
    options.quadrics = quadrics;
    return loadNff(nameOrPath, options);
  }
  if ((extension == ".gltf" || extension == ".glb") && gltfMajorVersion(nameOrPath) == 2) return loadGltf(nameOrPath);
  // Every other format assimp imports (glTF 1.0 among them), through assimp.
  if (const std::optional<SceneNumbers> numbers = assimpSceneNumbers(nameOrPath)) {
    if (!std::filesystem::exists(nameOrPath)) throw InputError(fmt::format("{}: cannot open file", nameOrPath));
    return loadAssimpScene(nameOrPath, *numbers);
  }
  throw InputError(fmt::format("{}: {} is not a scene format Lancer reads: {} (convert the scene to one of them)",
                               nameOrPath, extension.empty() ? "a file without an extension" : "'" + extension + "'",
                               kSceneFormats));
}

Scene makeIcosphere(int levels) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  std::vector<std::array<uint32_t, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    // Each edge's midpoint is made once, so both faces sharing it use the same bits.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = midpoints.try_emplace(key, uint32_t(v.size()));
      if (fresh) v.push_back(glm::normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& f : faces) {
      const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.insert(next.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    faces = std::move(next);
  }
  Scene scene;
  scene.name = "icosphere";
  for (const auto& f : faces) scene.triangles.push_back({v[f[0]], v[f[1]], v[f[2]]});
  scene.materials.push_back(Material{});
  scene.materialOf.assign(scene.size(), 0);
  scene.computeBounds();
  return scene;
}

Scene subdivide(const Scene& scene, int times) {
  Scene out = scene;
  for (int i = 0; i < times; ++i) {
    Scene next;
    next.name = out.name;
    next.materials = out.materials;
    next.triangles.reserve(out.triangles.size() * 4);
    for (size_t t = 0; t < out.triangles.size(); ++t) {
      const Triangle& tri = out.triangles[t];
      // 0.5f * (a + b) is symmetric in a and b, so both triangles sharing an edge
      // compute a bit-identical midpoint.
      const glm::vec3 m01 = 0.5f * (tri.v0 + tri.v1);
      const glm::vec3 m12 = 0.5f * (tri.v1 + tri.v2);
      const glm::vec3 m20 = 0.5f * (tri.v2 + tri.v0);
      for (const Triangle& child : {Triangle{tri.v0, m01, m20}, Triangle{m01, tri.v1, m12},
                                    Triangle{m20, m12, tri.v2}, Triangle{m01, m12, m20}}) {
        next.triangles.push_back(child);
        next.materialOf.push_back(out.materialOf[t]);
      }
    }
    // Quadrics are kept as they are, after the triangles in the id space.
    next.quadrics = out.quadrics;
    for (size_t i = 0; i < out.quadrics.size(); ++i) next.materialOf.push_back(out.materialOf[out.triangles.size() + i]);
    out = std::move(next);
  }
  out.computeBounds();
  return out;
}

}  // namespace lancer
