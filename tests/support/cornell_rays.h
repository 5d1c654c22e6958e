#pragma once

// The Cornell box, its auto-framed camera rays at side x side, and its
// quantizer: the small scene of the job-level tests (driver, chip).

#include <vector>

#include "driver/quantize.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace lancer {

struct CornellRays {
  explicit CornellRays(int side) : rays(frameScene(scene, CameraOptions::sized(side, side)).generateRays()) {}
  Scene scene = makeCornellBox();
  std::vector<Ray> rays;
  Quantizer quantizer{scene.bounds};
};

}  // namespace lancer
