#include "scene/rays_file.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "common/error.h"
#include "common/aabb.h"

namespace lancer {

void validateRay(const Ray& ray, size_t index, const std::string& where) {
  if (!allFinite(ray.origin) || !allFinite(ray.dir)) {
    throw InputError(fmt::format("{}: ray {}: NaN or infinite component", where, index));
  }
  if (ray.dir == glm::vec3(0.0f)) {
    throw InputError(fmt::format("{}: ray {}: zero direction", where, index));
  }
}

std::vector<Ray> readRaysFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open rays file", path));
  return readRays(in, path);
}

std::vector<Ray> readRays(std::istream& in, const std::string& path) {
  std::vector<Ray> rays;
  std::string line;
  for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    // The parser below stops at a NUL; what follows it would be dropped unread.
    if (line.find('\0') != std::string::npos) {
      throw InputError(fmt::format("{}:{}: NUL byte in a ray line (not a text file?)", path, lineNo));
    }
    const char* cursor = line.c_str();
    float values[6];
    int count = 0;
    for (;;) {
      while (*cursor == ' ' || *cursor == '\t' || *cursor == '\r') ++cursor;
      if (*cursor == '\0') break;
      if (count == 6) {
        throw InputError(fmt::format("{}:{}: more than 6 numbers (expected ox oy oz dx dy dz)", path, lineNo));
      }
      char* end = nullptr;
      errno = 0;
      // strtof reads decimal and C99 hex floats (%a) alike.
      const float value = std::strtof(cursor, &end);
      if (end == cursor || (*end != '\0' && *end != ' ' && *end != '\t' && *end != '\r')) {
        const std::string token(cursor, std::strcspn(cursor, " \t\r"));
        throw InputError(fmt::format("{}:{}: '{}' is not a number", path, lineNo, token));
      }
      values[count++] = value;
      cursor = end;
    }
    if (count == 0) continue;  // blank or comment line
    if (count != 6) {
      throw InputError(fmt::format("{}:{}: expected 6 numbers (ox oy oz dx dy dz), found {}", path, lineNo, count));
    }
    const Ray ray{{values[0], values[1], values[2]}, {values[3], values[4], values[5]}};
    validateRay(ray, rays.size(), fmt::format("{}:{}", path, lineNo));
    rays.push_back(ray);
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error", path));
  return rays;
}

void writeRaysFile(const std::string& path, const std::vector<Ray>& rays, const std::string& comment) {
  std::ofstream out(path);
  if (!out) throw InputError(fmt::format("{}: cannot write rays file", path));
  writeRays(out, rays, comment);
  if (!out) throw InputError(fmt::format("{}: write failed", path));
}

void writeRays(std::ostream& out, const std::vector<Ray>& rays, const std::string& comment) {
  out << "# lancer rays: ox oy oz dx dy dz (hex floats, exact)\n";
  // Every line of the comment is commented out, so it cannot add rays.
  for (size_t at = 0; at < comment.size();) {
    const size_t end = std::min(comment.find('\n', at), comment.size());
    out << "# " << comment.substr(at, end - at) << "\n";
    at = end + 1;
  }
  for (const Ray& r : rays) {
    out << fmt::format("{:a} {:a} {:a} {:a} {:a} {:a}\n", r.origin.x, r.origin.y, r.origin.z, r.dir.x,
                       r.dir.y, r.dir.z);
  }
}

}  // namespace lancer
