#include "ref/brute_force.h"

#include "ref/primitive.h"

namespace lancer {

std::optional<Hit> BruteForce::intersect(const Ray& ray, TraversalStats* stats) const {
  const WatertightRay wray(ray);
  std::optional<Hit> best;
  for (uint32_t i = 0; i < scene_.triangles.size(); ++i) {
    if (auto hit = intersectTriangle(wray, scene_.triangles[i], i)) keepCloser(best, *hit);
  }
  for (uint32_t i = uint32_t(scene_.triangles.size()); i < scene_.primitiveCount(); ++i) {
    if (auto hit = intersectPrimitive(scene_, wray, ray, i)) keepCloser(best, *hit);
  }
  if (stats) {
    stats->triangleTests += scene_.triangles.size();
    stats->quadricTests += scene_.quadrics.size();
  }
  return best;
}

bool BruteForce::intersectP(const Ray& ray) const {
  const WatertightRay wray(ray);
  for (uint32_t i = 0; i < scene_.primitiveCount(); ++i) {
    if (intersectPrimitive(scene_, wray, ray, i)) return true;
  }
  return false;
}

}  // namespace lancer
