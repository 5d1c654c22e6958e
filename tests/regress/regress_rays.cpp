// Writes one chunk of the long regression (scripts/regress, docs/regress.md):
// COUNT rays of one generator on a scene, seeded, as a rays file (hex floats,
// so the file is exact). The same arguments always give the same file.
//
// Generators (every one aims at the scene's own geometry or at the lattice the
// hardware quantizes it to, so the hard cases of docs/number-formats.md come up
// often rather than by chance):
//   camera   pinhole views from random eyes around the scene, looking at a random
//            point inside it (auto-framed field of view)
//   random   origins in the bounds grown by half their extent, directions uniform
//            on the sphere; half of them aimed at a random point inside the bounds
//   axis     axis-parallel rays (the other components +0 or -0.0 at random), half
//            of them lying in a lattice cell / octree node boundary plane
//   corner   rays through lattice points that are grid cell and octree node corners
//            (k * 2^(P-L) for levels L = 1..8, and k * kPosMax / n for n = 2..64),
//            from random outside points, axis-parallel or along a diagonal
//   vertex   rays aimed exactly at mesh vertices (shared by the closed meshes' triangles)
//   edge     rays aimed at points on triangle edges (midpoints, quarter points, random)
//   outside  rays from outside entering the scene's bounds through a face, an edge or
//            a corner of the box, every face it is on crossed inward (where a closed
//            object's faces lie on the bounds, each is seen from outside)
//
// Usage: regress_rays SCENE SUBDIVIDE GENERATOR COUNT SEED OUT.rays
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/quantize.h"
#include "golden/formats.h"
#include "scene/camera.h"
#include "scene/rays_file.h"
#include "scene/scene.h"

namespace {

using namespace lancer;

constexpr std::array<const char*, 7> kGenerators = {"camera", "random", "axis", "corner", "vertex", "edge", "outside"};

class Generator {
 public:
  Generator(const Scene& scene, uint64_t seed) : scene_(scene), quantizer_(scene.bounds), rng_(seed) {
    lo_ = scene.bounds.lo;
    hi_ = scene.bounds.hi;
    extent_ = std::max({hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z, 1e-30f});
    centre_ = 0.5f * (lo_ + hi_);
  }

  std::vector<Ray> make(const std::string& kind, size_t count) {
    std::vector<Ray> rays;
    rays.reserve(count);
    if (kind == "camera") {
      camera(count, rays);
      return rays;
    }
    while (rays.size() < count) {
      Ray r;
      if (kind == "random") {
        r = random();
      } else if (kind == "axis") {
        r = axis();
      } else if (kind == "corner") {
        r = corner();
      } else if (kind == "vertex") {
        r = toward(vertex());
      } else if (kind == "outside") {
        r = entering();
      } else {
        r = toward(edgePoint());
      }
      if (valid(r)) rays.push_back(r);
    }
    return rays;
  }

 private:
  float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool coin() { return pick(2) == 1; }

  glm::vec3 unitVector() {
    std::normal_distribution<float> n(0.0f, 1.0f);
    glm::vec3 v(n(rng_), n(rng_), n(rng_));
    const float len = glm::length(v);
    return len > 1e-6f ? v / len : glm::vec3(0, 0, 1);
  }
  glm::vec3 inside() { return {uniform(lo_.x, hi_.x), uniform(lo_.y, hi_.y), uniform(lo_.z, hi_.z)}; }
  glm::vec3 grown() {
    const glm::vec3 g(0.5f * extent_);
    return {uniform(lo_.x - g.x, hi_.x + g.x), uniform(lo_.y - g.y, hi_.y + g.y), uniform(lo_.z - g.z, hi_.z + g.z)};
  }
  // A point outside the bounds, on a sphere around them.
  glm::vec3 outside() { return centre_ + unitVector() * (extent_ * uniform(1.0f, 2.0f)); }

  static bool valid(const Ray& r) {
    const glm::vec3 o = r.origin, d = r.dir;
    return std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) &&
           std::isfinite(d.y) && std::isfinite(d.z) && (d.x != 0.0f || d.y != 0.0f || d.z != 0.0f);
  }

  Ray random() {
    Ray r;
    r.origin = grown();
    r.dir = coin() ? unitVector() : inside() - r.origin;
    return r;
  }

  // Scene position of a lattice point (what the quantizer maps there).
  glm::vec3 lattice(const glm::dvec3& p) const {
    return glm::vec3(quantizer_.latticeOrigin() + p * quantizer_.unit());
  }
  // One coordinate of a cell or node boundary: k * 2^(P-L) or k * kPosMax / n.
  double boundary() {
    const double max = double(fx::kPosMax);
    if (coin()) {
      const int level = 1 + pick(8);
      const double step = std::ldexp(1.0, fx::kPosBits - level);
      return step * pick((1 << level) + 1);
    }
    const int n = 2 + pick(63);
    return std::round(max * pick(n + 1) / n);
  }

  Ray axis() {
    Ray r;
    const int a = pick(3);
    r.origin = grown();
    if (coin()) {
      // In a boundary plane of one or two of the other axes.
      const int b = (a + 1 + pick(2)) % 3;
      r.origin[b] = lattice(glm::dvec3(boundary()))[b];
      if (coin()) r.origin[3 - a - b] = lattice(glm::dvec3(boundary()))[3 - a - b];
    }
    for (int i = 0; i < 3; ++i) r.dir[i] = coin() ? -0.0f : 0.0f;
    r.dir[a] = coin() ? 1.0f : -1.0f;
    return r;
  }

  Ray corner() {
    const glm::vec3 c = lattice(glm::dvec3(boundary(), boundary(), boundary()));
    Ray r;
    switch (pick(3)) {
      case 0: {  // axis-parallel through the corner, from outside the bounds
        const int a = pick(3);
        const float s = coin() ? 1.0f : -1.0f;
        r.dir = glm::vec3(coin() ? -0.0f : 0.0f);
        r.dir[a] = s;
        r.origin = c;
        r.origin[a] = c[a] - s * extent_ * uniform(1.0f, 2.0f);
        break;
      }
      case 1: {  // along a diagonal (all components +-1: dominant-axis ties)
        r.dir = glm::vec3(coin() ? 1.0f : -1.0f, coin() ? 1.0f : -1.0f, coin() ? 1.0f : -1.0f);
        r.origin = c - r.dir * (extent_ * uniform(1.0f, 2.0f));
        break;
      }
      default:
        r = toward(c);
    }
    return r;
  }

  glm::vec3 vertex() {
    const Triangle& t = scene_.triangles[size_t(pick(int(scene_.size())))];
    const int k = pick(3);
    return k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
  }
  glm::vec3 edgePoint() {
    const Triangle& t = scene_.triangles[size_t(pick(int(scene_.size())))];
    const std::array<glm::vec3, 3> v = {t.v0, t.v1, t.v2};
    const int k = pick(3);
    static constexpr std::array<float, 3> kFixed = {0.5f, 0.25f, 0.75f};
    const float s = pick(4) == 3 ? uniform(0.0f, 1.0f) : kFixed[size_t(pick(3))];
    return v[size_t(k)] + s * (v[size_t((k + 1) % 3)] - v[size_t(k)]);
  }
  // Through a point of the bounds' surface (on 1, 2 or 3 of its faces: a face, an
  // edge, a corner), crossing each of those faces inward.
  Ray entering() {
    const int faces = 1 + pick(3), free = pick(3);
    glm::vec3 target = inside(), dir;
    for (int a = 0; a < 3; ++a) {
      const bool pinned = faces == 3 || (faces == 2 ? a != free : a == free);
      if (pinned) target[a] = coin() ? hi_[a] : lo_[a];
      const float inward = target[a] == hi_[a] ? -1.0f : 1.0f;
      dir[a] = pinned ? inward * uniform(0.2f, 1.0f) : uniform(-1.0f, 1.0f);
    }
    return {target - dir * (extent_ * uniform(0.1f, 2.0f)), dir, kInfinity};
  }

  // From a random outside point (or, one time in four, axis-parallel) at `p`.
  Ray toward(const glm::vec3& p) {
    Ray r;
    if (pick(4) == 0) {
      const int a = pick(3);
      const float s = coin() ? 1.0f : -1.0f;
      r.dir = glm::vec3(0.0f);
      r.dir[a] = s;
      r.origin = p;
      r.origin[a] = p[a] - s * extent_ * uniform(1.0f, 2.0f);
      return r;
    }
    r.origin = outside();
    r.dir = p - r.origin;
    return r;
  }

  void camera(size_t count, std::vector<Ray>& rays) {
    while (rays.size() < count) {
      const size_t left = count - rays.size();
      const int side = int(std::min<size_t>(256, std::max<size_t>(1, size_t(std::sqrt(double(left))))));
      CameraOptions options;
      options.width = side;
      options.height = int(std::min<size_t>(size_t(side), (left + size_t(side) - 1) / size_t(side)));
      options.eye = centre_ + unitVector() * (extent_ * uniform(1.2f, 3.0f));
      options.target = centre_ + (inside() - centre_) * 0.3f;
      options.fovYDegrees = uniform(20.0f, 60.0f);
      const glm::vec3 view = glm::normalize(*options.target - *options.eye);
      options.up = std::fabs(view.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      for (const Ray& r : frameScene(scene_, options).generateRays()) {
        if (rays.size() < count && valid(r)) rays.push_back(r);
      }
    }
  }

  const Scene& scene_;
  Quantizer quantizer_;
  std::mt19937_64 rng_;
  glm::vec3 lo_, hi_, centre_;
  float extent_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: regress_rays SCENE SUBDIVIDE GENERATOR COUNT SEED OUT.rays\n"
                         "  GENERATOR: camera, random, axis, corner, vertex, edge, outside\n");
    return 2;
  }
  try {
    const std::string sceneName = argv[1], kind = argv[3];
    const auto number = [](const char* what, const char* text) {
      char* end = nullptr;
      const unsigned long long v = std::strtoull(text, &end, 10);
      if (!*text || *end || text[0] == '-') throw InputError(fmt::format("{} '{}' is not a whole number", what, text));
      return uint64_t(v);
    };
    const uint64_t subdivideTimes = number("SUBDIVIDE", argv[2]);
    const uint64_t count = number("COUNT", argv[4]);
    const uint64_t seed = number("SEED", argv[5]);
    if (std::find(kGenerators.begin(), kGenerators.end(), kind) == kGenerators.end()) {
      throw InputError(fmt::format("GENERATOR '{}' is not one of {}", kind, fmt::join(kGenerators, ", ")));
    }
    if (subdivideTimes > 6) throw InputError(fmt::format("SUBDIVIDE {} is out of range 0..6", subdivideTimes));
    if (count == 0 || count > 100000000) throw InputError(fmt::format("COUNT {} is out of range 1..1e8", count));
    Scene scene = loadScene(sceneName);
    if (subdivideTimes) scene = subdivide(scene, int(subdivideTimes));
    if (scene.size() == 0) throw InputError(fmt::format("{}: the scene has no triangles", sceneName));
    Generator gen(scene, seed);
    const std::vector<Ray> rays = gen.make(kind, size_t(count));
    writeRaysFile(argv[6], rays,
                  fmt::format("scene: {} (regress_rays {} {} {} {} {}: {} rays)", scene.name, sceneName,
                              subdivideTimes, kind, count, seed, rays.size()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "regress_rays: %s\n", e.what());
    return 1;
  }
  return 0;
}
