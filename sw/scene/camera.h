#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "common/ray.h"
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
  // Auto-framed at width x height.
  static CameraOptions sized(int width, int height) {
    CameraOptions o;
    o.width = width;
    o.height = height;
    return o;
  }
};

// Where the camera shoots its rays. Centers: one ray through the centre of each
// pixel, W x H rays, id = y * W + x. Corners: one ray through each pixel
// corner, (W + 1) x (H + 1) rays, id = y * (W + 1) + x for corner (x, y) with
// 0 <= x <= W, 0 <= y <= H, (0, 0) the top-left corner of the image; a pixel's
// colour is the mean of its four corners (the SPD's testing procedure, rule 6).
// Both span the same field of view: the outermost corners lie on the image's
// edges, the outermost centres half a pixel inside them.
enum class Sampling : uint8_t { Centers, Corners };

// Throws InputError naming --sampling unless `name` is "centers" or "corners".
Sampling parseSampling(std::string_view name);
std::string_view toString(Sampling sampling);

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
  // The ray through pixel corner (x, y), 0 <= x <= width, 0 <= y <= height.
  Ray generateCornerRay(int x, int y) const;
  // Every sample of `sampling` in id order (see Sampling).
  std::vector<Ray> generateRays(Sampling sampling) const;
  size_t sampleCount(Sampling sampling) const;

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
