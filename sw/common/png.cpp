#include "common/png.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

void Image::set(size_t pixel, float r, float g, float b) {
  // Linear to sRGB-ish display gamma.
  auto encode = [](float c) {
    const float v = std::pow(std::clamp(c, 0.0f, 1.0f), 1.0f / 2.2f);
    return uint8_t(std::lround(v * 255.0f));
  };
  rgb[pixel * 3 + 0] = encode(r);
  rgb[pixel * 3 + 1] = encode(g);
  rgb[pixel * 3 + 2] = encode(b);
}

void writePng(const Image& image, const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw InputError(fmt::format("{}: cannot write image", path));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw InputError(fmt::format("{}: cannot encode PNG", path));
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, image.rgb.data() + size_t(y) * size_t(image.width) * 3);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace lancer
