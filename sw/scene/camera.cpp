#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

PinholeCamera::PinholeCamera(const View& view, int width, int height)
    : view_(view), width_(width), height_(height) {
  const float aspect = float(width) / float(height);
  const float halfHeight = std::tan(glm::radians(view.fovYDegrees) * 0.5f);
  const float halfWidth = aspect * halfHeight;
  const glm::vec3 w = glm::normalize(view.eye - view.target);
  const glm::vec3 u = glm::normalize(glm::cross(view.up, w));
  const glm::vec3 v = glm::cross(w, u);
  origin_ = view.eye;
  lowerLeft_ = -halfWidth * u - halfHeight * v - w;
  horizontal_ = 2.0f * halfWidth * u;
  vertical_ = 2.0f * halfHeight * v;
}

Ray PinholeCamera::generateRay(int x, int y) const {
  const float s = (float(x) + 0.5f) / float(width_);
  const float t = 1.0f - (float(y) + 0.5f) / float(height_);
  return Ray{origin_, glm::normalize(lowerLeft_ + s * horizontal_ + t * vertical_)};
}

std::vector<Ray> PinholeCamera::generateRays() const {
  std::vector<Ray> rays;
  rays.reserve(size_t(width_) * size_t(height_));
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) rays.push_back(generateRay(x, y));
  return rays;
}

Ray PinholeCamera::generateCornerRay(int x, int y) const {
  const float s = float(x) / float(width_);
  const float t = 1.0f - float(y) / float(height_);
  return Ray{origin_, glm::normalize(lowerLeft_ + s * horizontal_ + t * vertical_)};
}

std::vector<Ray> PinholeCamera::generateRays(Sampling sampling) const {
  if (sampling == Sampling::Centers) return generateRays();
  std::vector<Ray> rays;
  rays.reserve(sampleCount(sampling));
  for (int y = 0; y <= height_; ++y)
    for (int x = 0; x <= width_; ++x) rays.push_back(generateCornerRay(x, y));
  return rays;
}

size_t PinholeCamera::sampleCount(Sampling sampling) const {
  return sampling == Sampling::Centers ? size_t(width_) * size_t(height_)
                                       : size_t(width_ + 1) * size_t(height_ + 1);
}

Sampling parseSampling(std::string_view name) {
  if (name == "centers") return Sampling::Centers;
  if (name == "corners") return Sampling::Corners;
  throw InputError(fmt::format("--sampling {}: expected centers or corners", name));
}

std::string_view toString(Sampling sampling) {
  return sampling == Sampling::Centers ? "centers" : "corners";
}

PinholeCamera frameScene(const Scene& scene, const CameraOptions& options) {
  View view;
  if (scene.view) {
    view = *scene.view;
  } else {
    // Look at the broad side: along the thinner of the two horizontal axes
    // (y is up), from slightly above, far enough that the box fits the frame.
    const glm::vec3 center = scene.bounds.center();
    const glm::vec3 half = 0.5f * scene.bounds.diagonal();
    const float fov = options.fovYDegrees.value_or(view.fovYDegrees);
    const float aspect = float(std::max(options.width, 1)) / float(std::max(options.height, 1));
    const bool alongZ = half.z <= half.x;
    const float across = alongZ ? half.x : half.z;  // half-width seen by the camera
    const float depth = alongZ ? half.z : half.x;
    const float tanY = std::tan(glm::radians(fov) * 0.5f);
    const float fit = std::max(half.y / tanY, across / (tanY * aspect));
    const float distance = 1.15f * fit + depth;
    const glm::vec3 axis = alongZ ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    view.target = center;
    view.eye = center + distance * glm::normalize(axis + glm::vec3(0.0f, 0.25f, 0.0f));
  }
  if (options.eye) view.eye = *options.eye;
  if (options.target) view.target = *options.target;
  if (options.up) view.up = *options.up;
  if (options.fovYDegrees) view.fovYDegrees = *options.fovYDegrees;

  if (options.width <= 0 || options.height <= 0) {
    throw InputError(fmt::format("camera resolution {}x{} must be positive", options.width, options.height));
  }
  if (!(view.fovYDegrees > 0.0f && view.fovYDegrees < 180.0f)) {
    throw InputError(fmt::format("camera field of view {} degrees must lie in (0, 180)", view.fovYDegrees));
  }
  const glm::vec3 forward = view.target - view.eye;
  if (!allFinite(view.eye) || !allFinite(view.target) || glm::length(forward) == 0.0f) {
    throw InputError("camera eye and target must be finite and distinct");
  }
  if (glm::length(glm::cross(view.up, forward)) <= 1e-6f * glm::length(view.up) * glm::length(forward)) {
    throw InputError("camera up vector must not be parallel to the view direction");
  }
  return PinholeCamera(view, options.width, options.height);
}

}  // namespace lancer
