#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include <glm/glm.hpp>

namespace lancer {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A ray o + t d, valid for 0 < t <= tMax. The direction need not be normalized;
// t is measured in units of |d|.
struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 dir{0.0f, 0.0f, 1.0f};
  float tMax = kInfinity;
};

// A ray-triangle hit: the triangle id, the ray parameter and the barycentrics of
// v1 (u) and v2 (v); the point is (1-u-v) v0 + u v1 + v v2.
struct Hit {
  uint32_t prim = 0;
  float t = kInfinity;
  float u = 0.0f;
  float v = 0.0f;
};

// The one ordering of hits used everywhere (reference, golden model, hardware):
// smaller t first; exact ties go to the lower triangle id.
inline bool closerHit(const Hit& a, const Hit& b) {
  return a.t < b.t || (a.t == b.t && a.prim < b.prim);
}

inline void keepCloser(std::optional<Hit>& best, const Hit& candidate) {
  if (!best || closerHit(candidate, *best)) best = candidate;
}

}  // namespace lancer
