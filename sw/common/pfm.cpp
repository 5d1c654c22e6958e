#include "common/pfm.h"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

void writePfm(std::span<const glm::vec3> pixels, int width, int height, const std::string& path) {
  if (pixels.size() != size_t(width) * size_t(height)) {
    throw std::logic_error(fmt::format("writePfm: {} pixels for {}x{}", pixels.size(), width, height));
  }
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw InputError(fmt::format("{}: cannot write image", path));
  fmt::print(file.get(), "PF\n{} {}\n-1.0\n", width, height);
  std::vector<float> row(size_t(width) * 3);
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3& p = pixels[size_t(y) * size_t(width) + size_t(x)];
      row[size_t(x) * 3 + 0] = p.r;
      row[size_t(x) * 3 + 1] = p.g;
      row[size_t(x) * 3 + 2] = p.b;
    }
    if (std::fwrite(row.data(), sizeof(float), row.size(), file.get()) != row.size()) {
      throw InputError(fmt::format("{}: cannot write image", path));
    }
  }
}

}  // namespace lancer
