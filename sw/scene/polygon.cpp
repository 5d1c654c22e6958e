#include "scene/polygon.h"

namespace lancer {

std::string_view describe(PolygonFault fault) {
  switch (fault) {
    case PolygonFault::None:
      return "is fine";
    case PolygonFault::NoArea:
      return "has no area (its vertices on a line, or its halves cancel)";
    case PolygonFault::CrossesItself:
      return "cannot be triangulated (it crosses itself)";
  }
  return "";
}

// The outline is projected along its dominant normal axis (Newell's normal:
// robust for concave and nearly degenerate outlines). A vertex is an ear when
// its corner turns the polygon's way and no other remaining vertex lies in the
// corner's triangle (edges included). O(n^3) at worst, fine for the SPD's
// 144-vertex gears.
PolygonTriangles triangulatePolygon(std::span<const glm::vec3> points) {
  PolygonTriangles out;
  glm::dvec3 newell(0.0);
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 p(points[i]), q(points[(i + 1) % points.size()]);
    newell += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  if (!(glm::length(newell) > 0.0)) {
    out.fault = PolygonFault::NoArea;
    return out;
  }
  out.normal = glm::vec3(glm::normalize(newell));
  const glm::dvec3 a = glm::abs(newell);
  const int drop = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  const int ux = (drop + 1) % 3, uy = (drop + 2) % 3;
  // In the (ux, uy) plane the polygon turns positive iff newell[drop] > 0.
  const double orientation = newell[drop] > 0 ? 1.0 : -1.0;
  const auto at = [&](size_t i) { return glm::dvec2(points[i][ux], points[i][uy]); };
  const auto cross = [](glm::dvec2 o, glm::dvec2 p, glm::dvec2 q) {
    return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
  };

  std::vector<uint32_t> ring(points.size());
  for (size_t i = 0; i < ring.size(); ++i) ring[i] = uint32_t(i);
  size_t stall = 0, i = 0;
  while (ring.size() > 3) {
    const size_t n = ring.size();
    const uint32_t ip = ring[(i + n - 1) % n], ic = ring[i % n], in = ring[(i + 1) % n];
    const double turn = orientation * cross(at(ip), at(ic), at(in));
    bool ear = false;
    if (turn == 0.0) {
      // Collinear or repeated: the vertex adds no area.
      ring.erase(ring.begin() + long(i % n));
      stall = 0;
      continue;
    }
    if (turn > 0.0) {
      ear = true;
      for (size_t k = 0; k < n && ear; ++k) {
        const uint32_t j = ring[k];
        if (j == ip || j == ic || j == in || points[j] == points[ip] || points[j] == points[ic] ||
            points[j] == points[in]) {
          continue;
        }
        const glm::dvec2 p = at(j);
        ear = !(orientation * cross(at(ip), at(ic), p) >= 0 && orientation * cross(at(ic), at(in), p) >= 0 &&
                orientation * cross(at(in), at(ip), p) >= 0);
      }
    }
    if (ear) {
      out.triangles.push_back({ip, ic, in});
      ring.erase(ring.begin() + long(i % n));
      stall = 0;
      continue;
    }
    ++i;
    if (++stall > n) {
      out.fault = PolygonFault::CrossesItself;
      return out;
    }
  }
  if (ring.size() == 3 && cross(at(ring[0]), at(ring[1]), at(ring[2])) != 0.0) {
    out.triangles.push_back({ring[0], ring[1], ring[2]});
  }
  return out;
}

std::array<std::array<uint32_t, 3>, 2> splitQuad(std::span<const glm::vec3, 4> quad) {
  // A corner is concave when it turns against the quad's Newell normal: the
  // diagonal from it runs inside the quad, the other one outside.
  glm::dvec3 newell(0.0);
  for (uint32_t i = 0; i < 4; ++i) {
    const glm::dvec3 p(quad[i]), q(quad[(i + 1) % 4]);
    newell += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  uint32_t k = 0;
  for (uint32_t i = 0; i < 4; ++i) {
    const glm::dvec3 in = glm::dvec3(quad[i]) - glm::dvec3(quad[(i + 3) % 4]);
    const glm::dvec3 out = glm::dvec3(quad[(i + 1) % 4]) - glm::dvec3(quad[i]);
    if (glm::dot(glm::cross(in, out), newell) < 0.0) {
      k = i;
      break;
    }
  }
  return {{{k, (k + 1) % 4, (k + 2) % 4}, {k, (k + 2) % 4, (k + 3) % 4}}};
}

}  // namespace lancer
