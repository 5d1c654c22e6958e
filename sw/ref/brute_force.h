#pragma once

#include <optional>

#include "ref/accel.h"

namespace lancer {

// Tests every primitive, the triangles then the quadrics: the slow, obviously
// correct answer the structures are checked against in the tests.
class BruteForce final : public Accel {
 public:
  explicit BruteForce(const Scene& scene) : scene_(scene) {}
  explicit BruteForce(Scene&&) = delete;  // keeps a reference: a temporary would dangle
  std::string_view name() const override { return "brute-force"; }
  std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const override;
  bool intersectP(const Ray& ray) const override;

 private:
  const Scene& scene_;
};

}  // namespace lancer
