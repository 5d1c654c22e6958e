#include "scene/ply.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/polygon.h"
#include "scene/surface.h"
#include "scene/text.h"

namespace lancer {

namespace {

// ---- The header ------------------------------------------------------------------------

enum class Scalar : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// Both spellings of every type: the 1998 names and the sized ones later writers use.
std::optional<Scalar> scalarNamed(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, Scalar>, 16> kNames{{
      {"char", Scalar::Int8},     {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},   {"uint8", Scalar::UInt8},
      {"short", Scalar::Int16},   {"int16", Scalar::Int16},     {"ushort", Scalar::UInt16}, {"uint16", Scalar::UInt16},
      {"int", Scalar::Int32},     {"int32", Scalar::Int32},     {"uint", Scalar::UInt32},   {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64}, {"float64", Scalar::Float64},
  }};
  for (const auto& [n, s] : kNames) {
    if (n == name) return s;
  }
  return std::nullopt;
}

size_t sizeOf(Scalar s) {
  switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8:
      return 1;
    case Scalar::Int16:
    case Scalar::UInt16:
      return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32:
      return 4;
    case Scalar::Float64:
      return 8;
  }
  return 0;
}

bool isInteger(Scalar s) { return s != Scalar::Float32 && s != Scalar::Float64; }

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;    // a list's items
  std::optional<Scalar> countType;  // a list: the type of its length
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  size_t line = 0;  // of its header line

  std::optional<size_t> find(std::string_view property) const {
    for (size_t p = 0; p < properties.size(); ++p) {
      if (properties[p].name == property) return p;
    }
    return std::nullopt;
  }
};

enum class Format : uint8_t { Ascii, LittleEndian, BigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t bodyStart = 0;  // the first byte after end_header's line
  size_t bodyLine = 0;   // its line, for an ASCII body
};

Header readHeader(std::string_view bytes, const std::string& name) {
  Header header;
  std::optional<Format> format;
  std::vector<std::string_view> words;
  size_t at = 0, line = 0;
  for (;;) {
    ++line;
    const auto fail = [&](const std::string& what) { throw InputError(fmt::format("{}:{}: {}", name, line, what)); };
    if (at >= bytes.size()) fail("the header has no end_header line");
    const size_t end = std::min(bytes.find('\n', at), bytes.size());
    std::string_view text = bytes.substr(at, end - at);
    if (text.ends_with('\r')) text.remove_suffix(1);
    at = std::min(end + 1, bytes.size());
    splitWords(text, words);
    if (line == 1) {
      if (words.size() != 1 || words[0] != "ply") fail("not a PLY file (it does not start with the line 'ply')");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") break;
    if (words[0] == "format") {
      if (words.size() != 3) fail("'format' takes a format and a version");
      if (words[1] == "ascii") {
        format = Format::Ascii;
      } else if (words[1] == "binary_little_endian") {
        format = Format::LittleEndian;
      } else if (words[1] == "binary_big_endian") {
        format = Format::BigEndian;
      } else {
        fail(fmt::format("unknown format '{}' (ascii, binary_little_endian, binary_big_endian)", words[1]));
      }
    } else if (words[0] == "element") {
      const std::optional<int64_t> count = words.size() == 3 ? parseInteger(words[2]) : std::nullopt;
      if (!count || *count < 0) fail("'element' takes a name and a count");
      header.elements.push_back(
          {.name = std::string(words[1]), .count = uint64_t(*count), .properties = {}, .line = line});
    } else if (words[0] == "property") {
      if (header.elements.empty()) fail("a property before the first element");
      Property p;
      if (words.size() == 5 && words[1] == "list") {
        p.countType = scalarNamed(words[2]);
        const std::optional<Scalar> item = scalarNamed(words[3]);
        if (!p.countType || !item) fail(fmt::format("unknown type in '{}'", fmt::join(words, " ")));
        if (!isInteger(*p.countType)) fail("a list's length must be of an integer type");
        p.type = *item;
      } else if (words.size() == 3) {
        const std::optional<Scalar> type = scalarNamed(words[1]);
        if (!type) fail(fmt::format("unknown type '{}'", words[1]));
        p.type = *type;
      } else {
        fail("'property' takes a type and a name, or 'list', two types and a name");
      }
      p.name = std::string(words.back());
      header.elements.back().properties.push_back(p);
    }
    // Any other line is taken for a comment: Blender 2.4's exporter wrote its
    // "Created by Blender" without the keyword.
  }
  if (!format) throw InputError(fmt::format("{}: the header has no 'format' line", name));
  header.format = *format;
  header.bodyStart = at;
  header.bodyLine = line + 1;
  return header;
}

// ---- The data --------------------------------------------------------------------------

// The values after the header, one at a time, in either encoding.
class Body {
 public:
  Body(std::string_view bytes, const Header& header, std::string name)
      : bytes_(bytes), at_(header.bodyStart), line_(header.bodyLine), format_(header.format), name_(std::move(name)) {}

  // Where the next value is: its line in an ASCII file, its byte in a binary one.
  size_t mark() {
    if (format_ == Format::Ascii) skipSpace();
    return format_ == Format::Ascii ? line_ : at_;
  }
  // A mark for messages: "<file>:<line>" or "<file>: byte <n>".
  std::string place(size_t mark) const {
    return format_ == Format::Ascii ? fmt::format("{}:{}", name_, mark) : fmt::format("{}: byte {}", name_, mark);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", place(format_ == Format::Ascii ? line_ : at_), what));
  }

  // The next ASCII word read by parse (parseFloat, parseInteger), or a failure
  // saying it is not `what`.
  template <class T>
  T asciiNumber(std::optional<T> (*parse)(std::string_view), const char* what) {
    const std::string_view word = token();
    const std::optional<T> value = parse(word);
    if (!value) fail(fmt::format("'{}' is not {}", word, what));
    return *value;
  }

  // A coordinate: ASCII text correctly rounded to float, a binary float as it
  // is, a double or an integer rounded once.
  float real(Scalar type) {
    if (format_ == Format::Ascii) return asciiNumber(parseFloat, "a number");
    switch (type) {
      case Scalar::Float32:
        return std::bit_cast<float>(uint32_t(binary(4)));
      case Scalar::Float64:
        return float(std::bit_cast<double>(binary(8)));
      default:
        return float(whole(type));
    }
  }

  // A list length or an index.
  int64_t whole(Scalar type) {
    if (format_ == Format::Ascii) return asciiNumber(parseInteger, "a whole number");
    const uint64_t raw = binary(sizeOf(type));
    switch (type) {
      case Scalar::Int8:
        return int8_t(raw);
      case Scalar::Int16:
        return int16_t(raw);
      case Scalar::Int32:
        return int32_t(raw);
      default:
        return int64_t(raw);  // unsigned; floats are refused by the header checks
    }
  }

  void skip(Scalar type) {
    if (format_ == Format::Ascii) {
      token();
    } else {
      binary(sizeOf(type));
    }
  }

  // Whether `count` more values of `type` can still be in the file: checked
  // before a loop over a count the file declares, so an absurd count fails at
  // once instead of running for hours.
  void expect(uint64_t count, Scalar type, std::string_view what) const {
    const uint64_t each = format_ == Format::Ascii ? 2 : sizeOf(type);  // ASCII: a digit and a blank at least
    const uint64_t left = bytes_.size() - at_ + (format_ == Format::Ascii ? 1 : 0);
    if (count > left / each) fail(fmt::format("{} of {} values: more than the rest of the file holds", what, count));
  }

 private:
  void skipSpace() {
    while (at_ < bytes_.size() && (isBlank(bytes_[at_]) || bytes_[at_] == '\n' || bytes_[at_] == '\r')) {
      if (bytes_[at_] == '\n') ++line_;
      ++at_;
    }
  }

  std::string_view token() {
    skipSpace();
    if (at_ >= bytes_.size()) fail("the data ends before the header's counts are read");
    const size_t start = at_;
    while (at_ < bytes_.size() && !isBlank(bytes_[at_]) && bytes_[at_] != '\n' && bytes_[at_] != '\r') ++at_;
    return bytes_.substr(start, at_ - start);
  }

  uint64_t binary(size_t size) {
    if (bytes_.size() - at_ < size) fail("the data ends before the header's counts are read");
    uint64_t raw = 0;
    for (size_t i = 0; i < size; ++i) {
      const uint64_t byte = uint8_t(bytes_[at_ + i]);
      raw |= format_ == Format::LittleEndian ? byte << (8 * i) : byte << (8 * (size - 1 - i));
    }
    at_ += size;
    return raw;
  }

  std::string_view bytes_;
  size_t at_, line_;
  Format format_;
  std::string name_;
};

// The header's element counts against the data's size, before anything is
// allocated for them: each instance takes at least a byte a value.
void checkCounts(const Header& header, size_t bodyBytes, const std::string& name) {
  for (const Element& e : header.elements) {
    uint64_t least = 0;
    for (const Property& p : e.properties) {
      least += header.format == Format::Ascii ? 1 : sizeOf(p.countType.value_or(p.type));
    }
    if (least > 0 && e.count > bodyBytes / least) {
      throw InputError(fmt::format("{}:{}: element '{}' declares {} instances, more than the file's {} bytes of "
                                   "data hold",
                                   name, e.line, e.name, e.count, bodyBytes));
    }
  }
}

}  // namespace

Scene readPly(std::string_view bytes, const std::string& name) {
  const Header header = readHeader(bytes, name);
  checkCounts(header, bytes.size() - header.bodyStart, name);
  Body body(bytes, header, name);

  std::vector<glm::vec3> positions, normals;
  // The faces as one list of indices, each face's start, and its mark.
  std::vector<int64_t> indices;
  std::vector<size_t> faceStart, faceMark;
  bool withNormals = false;
  for (const Element& e : header.elements) {
    const auto fail = [&](const std::string& what) { throw InputError(fmt::format("{}:{}: {}", name, e.line, what)); };
    // Which properties are kept: x y z (nx ny nz) of a vertex, a face's index list.
    std::vector<int> role(e.properties.size(), -1);
    std::optional<size_t> list;
    if (e.name == "vertex") {
      for (int axis = 0; axis < 3; ++axis) {
        const std::optional<size_t> p = e.find(std::array{"x", "y", "z"}[size_t(axis)]);
        if (!p || e.properties[*p].countType) fail("the vertex element needs scalar properties x, y and z");
        role[*p] = axis;
      }
      const std::array<std::optional<size_t>, 3> n{e.find("nx"), e.find("ny"), e.find("nz")};
      withNormals = n[0] && n[1] && n[2] && !e.properties[*n[0]].countType && !e.properties[*n[1]].countType &&
                    !e.properties[*n[2]].countType;
      for (int axis = 0; axis < 3 && withNormals; ++axis) role[*n[size_t(axis)]] = 3 + axis;
      positions.reserve(e.count);
      if (withNormals) normals.reserve(e.count);
    } else if (e.name == "face") {
      list = e.find("vertex_indices");
      if (!list) list = e.find("vertex_index");
      if (list && (!e.properties[*list].countType || !isInteger(e.properties[*list].type))) {
        fail(fmt::format("the face element's {} must be a list of integers", e.properties[*list].name));
      }
    }
    if (e.properties.empty()) continue;  // nothing to read, however many
    for (uint64_t i = 0; i < e.count; ++i) {
      std::array<float, 6> values{};
      const size_t mark = body.mark();
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const Property& property = e.properties[p];
        if (property.countType) {
          const int64_t n = body.whole(*property.countType);
          if (n < 0) body.fail(fmt::format("a list of {} items", n));
          body.expect(uint64_t(n), property.type, property.name);
          if (list == p) {
            faceStart.push_back(indices.size());
            faceMark.push_back(mark);
            for (int64_t k = 0; k < n; ++k) indices.push_back(body.whole(property.type));
          } else {
            for (int64_t k = 0; k < n; ++k) body.skip(property.type);
          }
        } else if (role[p] >= 0) {
          values[size_t(role[p])] = body.real(property.type);
        } else {
          body.skip(property.type);
        }
      }
      if (e.name == "vertex") {
        const glm::vec3 v(values[0], values[1], values[2]);
        if (!allFinite(v)) {
          throw InputError(fmt::format("{}: vertex {} ({}, {}, {}) is not finite", body.place(mark), i, v.x, v.y, v.z));
        }
        positions.push_back(v);
        if (withNormals) normals.emplace_back(values[3], values[4], values[5]);
      }
    }
  }

  Scene scene;
  scene.name = name;
  // Binary numbers are the file's (a double or a large integer rounded once).
  scene.numbers = header.format == Format::Ascii ? SceneNumbers::CorrectlyRounded : SceneNumbers::Exact;
  scene.materials.push_back(Material{"default"});
  std::vector<glm::vec3> outline;
  const auto emit = [&](size_t at, uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t v[3] = {uint32_t(indices[at + a]), uint32_t(indices[at + b]), uint32_t(indices[at + c])};
    const Triangle tri{positions[v[0]], positions[v[1]], positions[v[2]]};
    scene.triangles.push_back(tri);
    scene.materialOf.push_back(0);
    if (withNormals) scene.normals.push_back(shadingNormals(tri, {&normals[v[0]], &normals[v[1]], &normals[v[2]]}));
  };
  for (size_t f = 0; f < faceStart.size(); ++f) {
    const size_t at = faceStart[f], n = (f + 1 < faceStart.size() ? faceStart[f + 1] : indices.size()) - at;
    const auto fail = [&](const std::string& what) {
      throw InputError(fmt::format("{}: face {}: {}", body.place(faceMark[f]), f, what));
    };
    if (n < 3) fail(fmt::format("{} vertices (at least 3)", n));
    for (size_t k = 0; k < n; ++k) {
      if (indices[at + k] < 0 || uint64_t(indices[at + k]) >= positions.size()) {
        fail(fmt::format("vertex index {} is out of range ({} vertices)", indices[at + k], positions.size()));
      }
    }
    if (n == 3) {
      emit(at, 0, 1, 2);  // as written, even with no area, as OBJ's triangles and quads
      continue;
    }
    outline.clear();
    for (size_t k = 0; k < n; ++k) outline.push_back(positions[size_t(indices[at + k])]);
    if (n == 4) {
      for (const auto& [a, b, c] : splitQuad(std::span<const glm::vec3, 4>(outline.data(), 4))) emit(at, a, b, c);
      continue;
    }
    const PolygonTriangles cut = triangulatePolygon(outline);
    if (cut.fault == PolygonFault::NoArea) continue;  // nothing a ray could hit
    if (cut.fault != PolygonFault::None) fail(fmt::format("a polygon of {} vertices that {}", n, describe(cut.fault)));
    for (const auto& [a, b, c] : cut.triangles) emit(at, a, b, c);
  }
  if (scene.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", name));
  scene.computeBounds();
  return scene;
}

Scene loadPly(const std::string& path) { return readPly(readFileBytes(path), path); }

}  // namespace lancer
