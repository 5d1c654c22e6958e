#include "driver/cracks.h"

#include <algorithm>
#include <array>
#include <map>
#include <random>

#include "golden/formats.h"

namespace lancer {

namespace {

using Vec = std::array<int64_t, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// The normal's components are below 2^49 (coordinates below 2^24), d's are -1..1: no overflow.
int64_t dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The 26 directions with components in {-1, 0, 1}.
std::vector<Vec> kingDirections() {
  std::vector<Vec> out;
  for (int64_t x = -1; x <= 1; ++x)
    for (int64_t y = -1; y <= 1; ++y)
      for (int64_t z = -1; z <= 1; ++z)
        if (x || y || z) out.push_back({x, y, z});
  return out;
}

// Whether d crosses every one of the normals' planes from the same side.
bool crossesAll(const Vec& d, const std::vector<Vec>& normals) {
  int sign = 0;
  for (const Vec& n : normals) {
    const int64_t s = dot(n, d);
    if (s == 0) return false;
    const int sg = s > 0 ? 1 : -1;
    if (sign && sg != sign) return false;
    sign = sg;
  }
  return true;
}

class Builder {
 public:
  Builder(const Scene& scene, const Quantizer& quantizer) : quantizer_(quantizer) {
    const std::vector<fx::QTriangle> tris = quantizer.quantize(scene);
    for (const fx::QTriangle& t : tris) {
      const Vec n = cross(sub(t.v[1], t.v[0]), sub(t.v[2], t.v[0]));
      if (n == Vec{0, 0, 0}) continue;  // degenerate on this lattice: it answers no ray
      normals_.push_back(n);
      const size_t tri = normals_.size() - 1;
      std::array<uint32_t, 3> ids{};
      for (int k = 0; k < 3; ++k) ids[size_t(k)] = vertexId(t.v[size_t(k)]);
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = ids[size_t(k)], b = ids[size_t((k + 1) % 3)];
        edges_[{std::min(a, b), std::max(a, b)}].push_back(tri);
        fans_[a].push_back(tri);
      }
    }
  }

  CrackRays build(size_t count, uint64_t seed) {
    CrackRays out;
    std::vector<std::pair<std::pair<uint32_t, uint32_t>, std::vector<size_t>>> shared;
    std::map<uint32_t, bool> closed;  // vertex -> every incident edge shared by exactly two
    for (const auto& [edge, tris] : edges_) {
      const bool two = tris.size() == 2;
      if (two) shared.push_back({edge, tris});
      for (uint32_t v : {edge.first, edge.second}) {
        auto [it, inserted] = closed.try_emplace(v, two);
        if (!inserted) it->second = it->second && two;
      }
    }
    std::vector<uint32_t> vertices;
    for (const auto& [v, isClosed] : closed)
      if (isClosed) vertices.push_back(v);
    out.sharedEdges = shared.size();
    out.closedVertices = vertices.size();

    std::mt19937_64 rng(seed);
    std::shuffle(shared.begin(), shared.end(), rng);
    std::shuffle(vertices.begin(), vertices.end(), rng);
    const size_t edgeTarget = count - count / 2;
    for (const auto& [edge, tris] : shared) {
      if (out.edgeRays == edgeTarget) break;
      const Vec& a = vertices_[edge.first];
      const Vec& b = vertices_[edge.second];
      const Vec p2{a[0] + b[0], a[1] + b[1], a[2] + b[2]};  // twice the midpoint
      if (add(p2, {normals_[tris[0]], normals_[tris[1]]}, rng, out)) ++out.edgeRays;
    }
    const size_t vertexTarget = count - out.edgeRays;
    for (uint32_t v : vertices) {
      if (out.vertexRays == vertexTarget) break;
      const Vec& p = vertices_[v];
      std::vector<Vec> fan;
      for (size_t tri : fans_[v]) fan.push_back(normals_[tri]);
      if (add({2 * p[0], 2 * p[1], 2 * p[2]}, fan, rng, out)) ++out.vertexRays;
    }
    return out;
  }

 private:
  uint32_t vertexId(const Vec& v) {
    auto [it, inserted] = ids_.try_emplace(v, uint32_t(vertices_.size()));
    if (inserted) vertices_.push_back(v);
    fans_.resize(vertices_.size());
    return it->second;
  }

  // A ray through the point p2 / 2 crossing every plane of `normals`; false if
  // no direction fits or the quantizer does not reproduce it.
  bool add(const Vec& p2, const std::vector<Vec>& normals, std::mt19937_64& rng, CrackRays& out) {
    // Axes where p2 is odd need d = +-1 there and 0 elsewhere, and an odd m2 (= 2m).
    const bool half = (p2[0] | p2[1] | p2[2]) & 1;
    std::vector<Vec> candidates;
    for (const Vec& d : kingDirections()) {
      bool fits = true;
      for (int k = 0; k < 3 && half; ++k) fits = fits && ((p2[size_t(k)] & 1) == (d[size_t(k)] != 0));
      if (fits && crossesAll(d, normals)) candidates.push_back(d);
    }
    if (candidates.empty()) return false;
    const Vec d = candidates[std::uniform_int_distribution<size_t>(0, candidates.size() - 1)(rng)];
    // A far origin on the lattice: m2 about as large as every axis allows, of the right parity.
    int64_t m2 = INT64_MAX;
    for (int k = 0; k < 3; ++k) {
      if (d[size_t(k)] > 0) m2 = std::min(m2, p2[size_t(k)]);
      if (d[size_t(k)] < 0) m2 = std::min(m2, 2 * fx::kPosMax - p2[size_t(k)]);
    }
    if ((m2 & 1) != int64_t(half)) --m2;
    // A unit inside the lattice cube rather than on its faces, where the float
    // origin could round outside and be clipped.
    if (m2 > 2) m2 -= 2;
    if (m2 < 1) return false;
    Vec origin{};
    for (int k = 0; k < 3; ++k) origin[size_t(k)] = (p2[size_t(k)] - m2 * d[size_t(k)]) / 2;

    fx::QRay q;
    q.org = origin;
    const glm::dvec3 o = quantizer_.sceneOrigin(q);
    const Ray ray{glm::vec3(o), glm::vec3(float(d[0]), float(d[1]), float(d[2]))};
    const std::optional<QuantizedRay> back = quantizer_.quantize(ray, 0);
    const Vec dir{d[0] * fx::kDirMax, d[1] * fx::kDirMax, d[2] * fx::kDirMax};
    if (!back || back->q.org != origin || back->q.dir != dir || back->tEnter != 0.0) {
      ++out.rejected;
      return false;
    }
    out.rays.push_back(ray);
    return true;
  }

  const Quantizer& quantizer_;
  std::map<Vec, uint32_t> ids_;
  std::vector<Vec> vertices_;
  std::vector<Vec> normals_;                                 // per non-degenerate triangle
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges_;
  std::vector<std::vector<size_t>> fans_;                    // per vertex, its triangles
};

}  // namespace

CrackRays makeCrackRays(const Scene& scene, const Quantizer& quantizer, size_t count, uint64_t seed) {
  return Builder(scene, quantizer).build(count, seed);
}

}  // namespace lancer
