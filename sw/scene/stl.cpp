#include "scene/stl.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/surface.h"
#include "scene/text.h"

namespace lancer {

namespace {

constexpr size_t kHeaderBytes = 84;    // 80 bytes of anything, then the count
constexpr size_t kTriangleBytes = 50;  // normal, three vertices (floats), a 16-bit attribute

uint32_t littleU32(std::string_view bytes, size_t at) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | uint8_t(bytes[at + size_t(i)]);
  return value;
}

glm::vec3 littleVec3(std::string_view bytes, size_t at) {
  return {std::bit_cast<float>(littleU32(bytes, at)), std::bit_cast<float>(littleU32(bytes, at + 4)),
          std::bit_cast<float>(littleU32(bytes, at + 8))};
}

void addTriangle(Scene& scene, const Triangle& tri, const glm::vec3& facetNormal) {
  scene.triangles.push_back(tri);
  scene.materialOf.push_back(0);
  scene.normals.push_back(shadingNormals(tri, {&facetNormal, &facetNormal, &facetNormal}));
}

void readBinary(std::string_view bytes, size_t count, Scene& scene) {
  scene.triangles.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const size_t at = kHeaderBytes + i * kTriangleBytes;
    const Triangle tri{littleVec3(bytes, at + 12), littleVec3(bytes, at + 24), littleVec3(bytes, at + 36)};
    if (!allFinite(tri.v0) || !allFinite(tri.v1) || !allFinite(tri.v2)) {
      throw InputError(fmt::format("{}: triangle {}: a vertex is not finite", scene.name, i));
    }
    addTriangle(scene, tri, littleVec3(bytes, at));
  }
}

void readAscii(std::string_view text, Scene& scene) {
  enum class At { Outside, Solid, Facet, Loop, LoopEnd } at = At::Outside;
  TextLines lines(text, /*continuation=*/false);
  std::vector<std::string_view> words;
  glm::vec3 normal(0.0f);
  std::array<glm::vec3, 3> v{};
  size_t vertices = 0;
  const auto numbers = [&](size_t from) {
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      const std::string_view word = words[from + size_t(i)];
      const std::optional<float> value = parseFloat(word);
      if (!value) throw InputError(fmt::format("{}:{}: '{}' is not a number", scene.name, lines.number(), word));
      out[i] = *value;
    }
    return out;
  };
  while (const auto line = lines.next()) {
    splitWords(*line, words);
    if (words.empty()) continue;
    const auto fail = [&](const std::string& what) {
      throw InputError(fmt::format("{}:{}: {}", scene.name, lines.number(), what));
    };
    const std::string key = lowercase(words[0]);
    if (at == At::Outside && key == "solid") {
      at = At::Solid;
    } else if (at == At::Solid && key == "facet") {
      if (words.size() != 5 || lowercase(words[1]) != "normal") fail("expected 'facet normal nx ny nz'");
      normal = numbers(2);
      at = At::Facet;
    } else if (at == At::Solid && key == "endsolid") {
      at = At::Outside;
    } else if (at == At::Facet && key == "outer") {
      if (words.size() != 2 || lowercase(words[1]) != "loop") fail("expected 'outer loop'");
      vertices = 0;
      at = At::Loop;
    } else if (at == At::Loop && key == "vertex") {
      if (words.size() != 4) fail("expected 'vertex x y z'");
      if (vertices == 3) fail("a facet of more than 3 vertices (STL facets are triangles)");
      v[vertices] = numbers(1);
      if (!allFinite(v[vertices])) {
        fail(fmt::format("vertex {} is not a finite float", fmt::join(words.begin() + 1, words.end(), " ")));
      }
      ++vertices;
    } else if (at == At::Loop && key == "endloop") {
      if (vertices != 3) fail(fmt::format("a facet of {} vertices (STL facets are triangles)", vertices));
      at = At::LoopEnd;
    } else if (at == At::LoopEnd && key == "endfacet") {
      addTriangle(scene, {v[0], v[1], v[2]}, normal);
      at = At::Solid;
    } else {
      static constexpr std::array<const char*, 5> kExpected{"'solid'", "'facet' or 'endsolid'", "'outer loop'",
                                                            "'vertex' or 'endloop'", "'endfacet'"};
      fail(fmt::format("expected {}, found '{}'", kExpected[size_t(at)], words[0]));
    }
  }
  // A missing endsolid loses nothing; a file cut inside a facet does.
  if (at != At::Outside && at != At::Solid) {
    throw InputError(fmt::format("{}: the file ends inside a facet", scene.name));
  }
}

}  // namespace

Scene readStl(std::string_view bytes, const std::string& name) {
  Scene scene;
  scene.name = name;
  scene.materials.push_back(Material{"default"});
  const uint64_t count = bytes.size() >= kHeaderBytes ? littleU32(bytes, 80) : 0;
  const std::string_view start = trimmed(bytes.substr(0, std::min<size_t>(bytes.size(), 100)));
  if (bytes.size() >= kHeaderBytes && kHeaderBytes + kTriangleBytes * count == bytes.size()) {
    // Binary, even when its header starts with "solid" (many do).
    readBinary(bytes, count, scene);
    scene.numbers = SceneNumbers::Exact;
  } else if (lowercase(start.substr(0, 5)) == "solid") {
    if (const size_t line = lineOfNulByte(bytes)) {
      throw InputError(fmt::format("{}:{}: a NUL byte in an ASCII STL (a binary STL of {} triangles would be {} bytes, "
                                   "this file has {})",
                                   name, line, count, kHeaderBytes + kTriangleBytes * count, bytes.size()));
    }
    readAscii(bytes, scene);
  } else {
    throw InputError(fmt::format("{}: not an STL file: it does not start with 'solid' (ASCII), and a binary STL of "
                                 "{} triangles would be {} bytes, not {}",
                                 name, count, kHeaderBytes + kTriangleBytes * count, bytes.size()));
  }
  if (scene.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", name));
  scene.computeBounds();
  return scene;
}

Scene loadStl(const std::string& path) { return readStl(readFileBytes(path), path); }

}  // namespace lancer
