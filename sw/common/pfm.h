#pragma once

#include <span>
#include <string>

#include <glm/glm.hpp>

namespace lancer {

// A linear RGB image as PFM (Portable Float Map: "PF", the size, -1 for
// little-endian, then 32-bit floats bottom row first), for the integrators'
// images without tone mapping. `pixels` are row-major from the top-left.
// Throws InputError naming the path if the file cannot be written.
void writePfm(std::span<const glm::vec3> pixels, int width, int height, const std::string& path);

}  // namespace lancer
