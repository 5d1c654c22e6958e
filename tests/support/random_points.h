#pragma once

// Random points for the tests that draw their rays with std::mt19937
// (bvh_test.cpp, embree_agreement_test.cpp).

#include <random>

#include <glm/glm.hpp>

#include "common/aabb.h"

namespace lancer::test {

// Three draws for x, y, z, made z first: the order GCC evaluates the arguments
// of glm::vec3(draw(), draw(), draw()), which the tests' sample sets (and the
// floors measured on them) come from. C++ leaves that order unspecified and
// clang goes x first, so spelling it out gives every compiler the same rays
// (the clang sanitizer build, docs/stability.md).
template <class Draw>
glm::vec3 drawVec3(Draw&& draw) {
  const float z = draw();
  const float y = draw();
  const float x = draw();
  return {x, y, z};
}

// A point uniform in the box.
inline glm::vec3 randomIn(const Aabb& b, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  return b.lo + drawVec3([&] { return u(rng); }) * b.diagonal();
}

}  // namespace lancer::test
