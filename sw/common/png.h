#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lancer {

// An 8-bit RGB image, row-major from the top-left pixel (the same order as ray ids).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes a pixel

  Image(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0) {}
  void set(size_t pixel, float r, float g, float b);
};

// Throws InputError naming the path if the file cannot be written.
void writePng(const Image& image, const std::string& path);

}  // namespace lancer
