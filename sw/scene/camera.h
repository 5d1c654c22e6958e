#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "ref/ray.h"
#include "scene/scene.h"

namespace lancer {

// What the user may say about the camera; anything left empty is filled in by
// frameScene() from the scene's suggested view or its bounds.
struct CameraOptions {
  std::optional<glm::vec3> eye;
  std::optional<glm::vec3> target;
  std::optional<glm::vec3> up;
  std::optional<float> fovYDegrees;
  int width = 512;
  int height = 512;
};

// A pinhole camera. Ray ids run row-major from the top-left pixel:
// id = y * width + x, and that id follows the ray through every model.
class PinholeCamera {
 public:
  PinholeCamera(const View& view, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  const View& view() const { return view_; }
  // The ray through the centre of pixel (x, y); direction normalized.
  Ray generateRay(int x, int y) const;
  std::vector<Ray> generateRays() const;

 private:
  View view_;
  int width_, height_;
  glm::vec3 origin_, lowerLeft_, horizontal_, vertical_;
};

// Auto-framing: the scene's own view if it has one; otherwise the camera looks
// at the centre of the bounds along the thinner horizontal axis (y is up), from
// slightly above, far enough that the box's broad side fits the frame with a
// 15% margin.
// Explicit options override either. Throws InputError on a degenerate camera
// (eye equal to target, up parallel to the view direction, fov outside (0,180),
// a non-positive resolution).
PinholeCamera frameScene(const Scene& scene, const CameraOptions& options);

}  // namespace lancer
