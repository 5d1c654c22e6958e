#pragma once

// The integrators' random numbers and the directions drawn from them
// (docs/incoherent.md, "The sampler"). Every number is Philox4x32-10 of a
// counter that names what it is for: the camera sample (pixel or pixel
// corner), the pass (--spp), the bounce and the dimension, under a key from
// the run's seed. A ray of a run therefore depends only on its place in the
// image and its path, never on the model, the unit count, the dispatch order,
// the threads or the shard: golden, SystemC and RTL, one unit or 64, spawn
// the same rays bit for bit.

#include <array>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "common/philox.h"

namespace lancer {

class Sampler {
 public:
  explicit Sampler(uint64_t seed) : key_{uint32_t(seed), uint32_t(seed >> 32)} {}

  // Four uniform numbers in [0, 1): dimensions 4 * group .. 4 * group + 3.
  std::array<float, 4> uniform4(uint32_t sample, uint32_t pass, uint32_t bounce, uint32_t group) const {
    const PhiloxCounter r = philox4x32_10({sample, pass, bounce, group}, key_);
    return {unitFloat(r[0]), unitFloat(r[1]), unitFloat(r[2]), unitFloat(r[3])};
  }
  // Two: dimensions 2 * pair and 2 * pair + 1.
  glm::vec2 uniform2(uint32_t sample, uint32_t pass, uint32_t bounce, uint32_t pair) const {
    const std::array<float, 4> u = uniform4(sample, pass, bounce, pair / 2);
    return pair % 2 == 0 ? glm::vec2(u[0], u[1]) : glm::vec2(u[2], u[3]);
  }

 private:
  PhiloxKey key_;
};

// A unit vector about +z with density cos(theta) / pi (Malley's method: a
// uniform point of the unit disc, lifted to the hemisphere).
inline glm::vec3 cosineHemisphere(glm::vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = 6.28318530717958647692f * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

// `local` (about +z) turned about the unit normal n: Duff et al.'s branchless
// orthonormal basis (JCGT 2017).
inline glm::vec3 aboutNormal(const glm::vec3& n, const glm::vec3& local) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 s(b, sign + n.y * n.y * a, -n.y);
  return local.x * t + local.y * s + local.z * n;
}

}  // namespace lancer
