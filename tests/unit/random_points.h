#pragma once

// Random points for the tests that draw their rays with std::mt19937
// (bvh_test.cpp, embree_agreement_test.cpp).

#include <random>

#include <glm/glm.hpp>

#include "scene/aabb.h"

namespace lancer::test {

// A point uniform in the box.
inline glm::vec3 randomIn(const Aabb& b, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  return b.lo + glm::vec3(u(rng), u(rng), u(rng)) * b.diagonal();
}

}  // namespace lancer::test
