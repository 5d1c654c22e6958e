// Writes a scene's camera rays as a rays file (hex floats, exact), the same rays
// `lancer run --width W --height H` traces (auto-framed camera, ray id = y * W + x).
// scripts/make-traces uses it for traces/*-camera-*.rays.
// Usage: write_camera_rays SCENE WIDTH HEIGHT OUT.rays
#include <cstdio>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "scene/camera.h"
#include "scene/rays_file.h"
#include "scene/scene.h"

int main(int argc, char** argv) {
  using namespace lancer;
  if (argc != 5) {
    std::fprintf(stderr, "usage: write_camera_rays SCENE WIDTH HEIGHT OUT.rays\n");
    return 2;
  }
  try {
    const Scene scene = loadScene(argv[1]);
    CameraOptions options;
    options.width = std::stoi(argv[2]);
    options.height = std::stoi(argv[3]);
    const PinholeCamera camera = frameScene(scene, options);
    // One comment line; scripts/make-traces and the regress test read the scene
    // name from "# scene: NAME".
    writeRaysFile(argv[4], camera.generateRays(),
                  fmt::format("scene: {} ({}x{} camera rays, the auto-framed view of `lancer run --width {} "
                              "--height {}`; ray id = y * {} + x)",
                              scene.name, options.width, options.height, options.width, options.height,
                              options.width));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_camera_rays: %s\n", e.what());
    return 1;
  }
  return 0;
}
