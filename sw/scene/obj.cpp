#include "scene/obj.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/polygon.h"
#include "scene/surface.h"
#include "scene/text.h"

namespace lancer {

namespace {

// What follows the statement's keyword, blanks trimmed: a name, which may hold
// blanks and '#' ("Material #25" is a 3ds Max name).
std::string_view restOf(std::string_view line, std::string_view keyword) {
  line = trimmed(line);
  return trimmed(line.substr(keyword.size()));
}

// Data statements end at a word that starts a comment.
void dropComment(std::vector<std::string_view>& words) {
  const auto hash = std::find_if(words.begin(), words.end(), [](std::string_view w) { return w.starts_with('#'); });
  words.erase(hash, words.end());
}

[[noreturn]] void failAt(const std::string& file, size_t line, const std::string& what) {
  throw InputError(fmt::format("{}:{}: {}", file, line, what));
}

// The NUL byte check every text file gets first: the parser would take the
// bytes of a binary or UTF-16 file for statements.
void refuseNulBytes(std::string_view text, const std::string& name) {
  if (const size_t line = lineOfNulByte(text)) failAt(name, line, "a NUL byte (not a text file; UTF-16 is not read)");
}

// ---- MTL ------------------------------------------------------------------------------

// An MTL material as its statements left it; Whitted terms are made of it once
// every MTL file is read (a later statement may change an earlier one's meaning:
// illum decides whether Ks reflects).
struct MtlMaterial {
  std::string name;
  std::string where;  // "<file>:<line>" of its first newmtl, for messages
  glm::vec3 kd = Material{}.diffuse, ks{0.0f}, ke{0.0f};  // no Kd: Lancer's default grey
  float ns = 0.0f, ni = 1.0f;
  float opacity = 1.0f;  // d, or 1 - Tr: the last one written
  int64_t illum = 1;

  // MTL's illum decides what is traced: illum >= 3 reflects, with Ks's
  // largest component as the weight (illum 2's highlight-only Ks has no
  // mirror); a dissolve d < 1 transmits T = 1 - d; Ni is the index of
  // refraction and Ns the highlight's exponent (negative: 0). Ni <= 0 on a
  // transmitting material is an error; on an opaque one it is unused
  // (exporters write Ni 0 there) and becomes 1.
  Material whitted() const {
    Material m;
    m.name = name;
    m.diffuse = kd;
    m.emission = ke;
    if (illum >= 3) m.ks = std::max({ks.r, ks.g, ks.b});
    m.shine = std::max(ns, 0.0f);
    m.transmittance = std::clamp(1.0f - opacity, 0.0f, 1.0f);
    m.ior = ni;
    if (m.ior <= 0.0f || !std::isfinite(m.ior)) {
      if (m.transmittance > 0.0f) {
        throw InputError(fmt::format("{}: material '{}': index of refraction {} must be > 0 on a transmitting material",
                                     where, name, m.ior));
      }
      m.ior = 1.0f;
    }
    checkMaterialTerms(m, where);
    return m;
  }
};

// The materials of every MTL file an OBJ names, by name. A newmtl of a name
// already defined, in the same file or an earlier one, goes on with that
// material, as assimp did.
class MtlLibrary {
 public:
  void read(std::string_view text, const std::string& file);
  std::vector<Material> materials() const {
    std::vector<Material> out;
    for (const MtlMaterial& m : list_) out.push_back(m.whitted());
    return out;
  }
  std::optional<uint32_t> find(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? std::nullopt : std::optional<uint32_t>(it->second);
  }

 private:
  std::vector<MtlMaterial> list_;
  std::unordered_map<std::string, uint32_t> index_;
};

void MtlLibrary::read(std::string_view text, const std::string& file) {
  refuseNulBytes(text, file);
  TextLines lines(text);
  std::vector<std::string_view> words;
  std::optional<uint32_t> current;
  while (const auto line = lines.next()) {
    splitWords(*line, words);
    if (words.empty() || words[0].starts_with('#')) continue;
    const auto fail = [&](const std::string& what) { failAt(file, lines.number(), what); };
    // In any case: exporters differ ("Kd", "kd"), and assimp, which Lancer used
    // before, ignored it.
    const std::string key = lowercase(words[0]);
    if (key == "newmtl") {
      const std::string name(restOf(*line, words[0]));
      const std::string where = fmt::format("{}:{}", file, lines.number());
      // A material without a name (assimp's test files have one) is read, and
      // no usemtl can name it.
      const auto [it, fresh] =
          name.empty() ? std::pair{index_.end(), true} : index_.try_emplace(name, uint32_t(list_.size()));
      if (fresh) list_.push_back({.name = name, .where = where});
      current = fresh ? uint32_t(list_.size() - 1) : it->second;
      continue;
    }
    // assimp 5.2 crashed on these (a null current material; tests/fuzz/corpus/mtl),
    // and no reader has a material to apply them to.
    if (!current) fail("a statement before the first newmtl (no material to apply it to)");
    dropComment(words);
    MtlMaterial& m = list_[*current];
    // The numbers after the keyword: one, or (a colour) one or three.
    const auto numbers = [&](std::initializer_list<size_t> counts) {
      const size_t have = words.size() - 1;
      if (std::find(counts.begin(), counts.end(), have) == counts.end()) {
        fail(counts.size() == 1
                 ? fmt::format("{} takes one number, this line has {}", words[0], have)
                 : fmt::format("{} takes {} numbers, this line has {}", words[0], fmt::join(counts, " or "), have));
      }
      std::vector<float> out;
      for (size_t i = 1; i < words.size(); ++i) {
        const std::optional<float> value = parseFloat(words[i]);
        if (!value) fail(fmt::format("'{}' is not a number", words[i]));
        out.push_back(*value);
      }
      return out;
    };
    // MTL's "Kd r" means grey r (assimp read it as (r, 0, 0)); "Kd spectral
    // file" and "Kd xyz x y z" name colours Lancer does not convert.
    const auto colour = [&]() -> std::optional<glm::vec3> {
      const std::string first = words.size() > 1 ? lowercase(words[1]) : "";
      if (first == "spectral" || first == "xyz") return std::nullopt;
      const std::vector<float> c = numbers({1, 3});
      return c.size() == 1 ? glm::vec3(c[0]) : glm::vec3(c[0], c[1], c[2]);
    };
    if (key == "kd" || key == "ks" || key == "ke") {
      if (const auto c = colour()) (key == "kd" ? m.kd : key == "ks" ? m.ks : m.ke) = *c;
    } else if (key == "ns") {
      m.ns = numbers({1})[0];
    } else if (key == "ni") {
      m.ni = numbers({1})[0];
    } else if (key == "d") {
      if (words.size() > 1 && words[1] == "-halo") words.erase(words.begin() + 1);  // a halo is still a dissolve
      m.opacity = numbers({1})[0];
    } else if (key == "tr") {
      m.opacity = 1.0f - numbers({1})[0];
    } else if (key == "illum") {
      const std::optional<int64_t> illum = words.size() == 2 ? parseInteger(words[1]) : std::nullopt;
      if (!illum) {
        fail(fmt::format("illum takes one whole number, got '{}'", fmt::join(words.begin() + 1, words.end(), " ")));
      }
      m.illum = *illum;
    }
    // Ka, Tf, texture maps and PBR extensions change nothing Lancer traces.
  }
}

// ---- OBJ ------------------------------------------------------------------------------

class ObjReader {
 public:
  ObjReader(std::string name, std::filesystem::path folder) : name_(std::move(name)), folder_(std::move(folder)) {
    scene_.name = name_;
  }
  Scene read(std::string_view text);

 private:
  [[noreturn]] void fail(const std::string& what) const { failAt(name_, line_, what); }
  void vertex(const std::vector<std::string_view>& words);
  void normal(const std::vector<std::string_view>& words);
  void face(const std::vector<std::string_view>& words);
  void useMaterial(std::string_view name);
  void materialLibraries(std::string_view files);
  // An index of a face corner, from 1 or negative, as an index from 0 into the
  // `count` elements (vertices, ...) defined so far.
  uint32_t resolve(std::string_view index, std::string_view corner, size_t count, const char* what) const;
  void finishMaterials();

  std::string name_;
  std::filesystem::path folder_;
  size_t line_ = 0;
  Scene scene_;
  std::vector<glm::vec3> positions_, normals_;
  size_t texcoords_ = 0;
  // Per triangle, its corners' vn indices (-1: none); shading normals are made
  // at the end, and only if some face names a normal.
  std::vector<std::array<int64_t, 3>> normalIds_;
  bool anyNormals_ = false;
  // Materials by the name usemtl gives them, resolved once every MTL file is
  // read; slot 0 is the default, for faces before any usemtl.
  std::vector<std::string> slotNames_{""};
  std::vector<size_t> slotLines_{0};  // where each name was first used
  std::unordered_map<std::string, uint32_t> slotOf_{{"", 0}};
  uint32_t slot_ = 0;
  MtlLibrary library_;
  std::vector<std::string> libraryFiles_;  // read so far, each once
  std::vector<std::string_view> words_;
  // A face's corners, reused from face to face.
  std::vector<uint32_t> cornerPositions_;
  std::vector<int64_t> cornerNormals_;
  std::vector<glm::vec3> outline_;
};

Scene ObjReader::read(std::string_view text) {
  refuseNulBytes(text, name_);
  TextLines lines(text);
  while (const auto line = lines.next()) {
    line_ = lines.number();
    splitWords(*line, words_);
    if (words_.empty() || words_[0].starts_with('#')) continue;
    const std::string_view key = words_[0];
    if (key == "usemtl") {
      useMaterial(restOf(*line, key));
      continue;
    }
    if (key == "mtllib") {
      materialLibraries(restOf(*line, key));
      continue;
    }
    dropComment(words_);
    if (key == "v") {
      vertex(words_);
    } else if (key == "vn") {
      normal(words_);
    } else if (key == "vt") {
      ++texcoords_;
    } else if (key == "f") {
      face(words_);
    }
    // "o", "g", "s", "l", "p", free-form geometry: nothing to trace.
  }
  if (scene_.triangles.empty()) throw InputError(fmt::format("{}: scene has no triangles", name_));
  finishMaterials();
  if (anyNormals_) {
    scene_.normals.reserve(scene_.triangles.size());
    for (size_t t = 0; t < scene_.triangles.size(); ++t) {
      std::array<const glm::vec3*, 3> file{};
      for (int k = 0; k < 3; ++k) file[k] = normalIds_[t][k] < 0 ? nullptr : &normals_[size_t(normalIds_[t][k])];
      scene_.normals.push_back(shadingNormals(scene_.triangles[t], file));
    }
  }
  scene_.computeBounds();
  return std::move(scene_);
}

void ObjReader::vertex(const std::vector<std::string_view>& words) {
  if (words.size() < 4) fail(fmt::format("a vertex takes 3 coordinates, this line has {}", words.size() - 1));
  glm::vec3 p;
  for (size_t i = 1; i < words.size(); ++i) {
    const std::optional<float> value = parseFloat(words[i]);
    if (!value) fail(fmt::format("'{}' is not a number", words[i]));
    if (i > 3) continue;  // w, or a vertex colour
    if (!std::isfinite(*value)) fail(fmt::format("vertex coordinate '{}' is not a finite float", words[i]));
    p[int(i - 1)] = *value;
  }
  positions_.push_back(p);
}

// A normal that is zero or beyond float range is kept: the triangle's
// geometric normal stands in for it (scene/surface.h).
void ObjReader::normal(const std::vector<std::string_view>& words) {
  if (words.size() != 4) fail(fmt::format("a normal takes 3 numbers, this line has {}", words.size() - 1));
  glm::vec3 n;
  for (int i = 0; i < 3; ++i) {
    const std::optional<float> value = parseFloat(words[size_t(i) + 1]);
    if (!value) fail(fmt::format("'{}' is not a number", words[size_t(i) + 1]));
    n[i] = *value;
  }
  normals_.push_back(n);
}

uint32_t ObjReader::resolve(std::string_view index, std::string_view corner, size_t count, const char* what) const {
  const std::optional<int64_t> i = parseInteger(index);
  if (!i) fail(fmt::format("face corner '{}': '{}' is not an index", corner, index));
  if (*i == 0) fail(fmt::format("face corner '{}': {} index 0 (OBJ counts from 1)", corner, what));
  const int64_t at = *i > 0 ? *i - 1 : int64_t(count) + *i;
  if (at < 0 || at >= int64_t(count)) {
    fail(fmt::format("face corner '{}': {} index {} is out of range ({} before this line)", corner, what, *i, count));
  }
  return uint32_t(at);
}

void ObjReader::face(const std::vector<std::string_view>& words) {
  const size_t n = words.size() - 1;
  if (n < 3) fail(fmt::format("a face needs at least 3 vertices, this one has {}", n));
  cornerPositions_.clear();
  cornerNormals_.clear();
  for (size_t k = 1; k < words.size(); ++k) {
    // v, v/vt, v//vn or v/vt/vn
    const std::string_view corner = words[k];
    std::array<std::string_view, 3> part{};
    size_t parts = 0;
    for (size_t begin = 0;;) {
      const size_t slash = std::min(corner.find('/', begin), corner.size());
      if (parts == 3) fail(fmt::format("face corner '{}' has more than v/vt/vn", corner));
      part[parts++] = corner.substr(begin, slash - begin);
      if (slash == corner.size()) break;
      begin = slash + 1;
    }
    cornerPositions_.push_back(resolve(part[0], corner, positions_.size(), "vertex"));
    if (parts >= 2 && !part[1].empty()) resolve(part[1], corner, texcoords_, "texture coordinate");
    if (parts == 3) {
      cornerNormals_.push_back(resolve(part[2], corner, normals_.size(), "normal"));
      anyNormals_ = true;
    } else {
      cornerNormals_.push_back(-1);
    }
  }
  const auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
    const std::vector<uint32_t>& p = cornerPositions_;
    scene_.triangles.push_back({positions_[p[a]], positions_[p[b]], positions_[p[c]]});
    scene_.materialOf.push_back(slot_);  // a slot until finishMaterials()
    normalIds_.push_back({cornerNormals_[a], cornerNormals_[b], cornerNormals_[c]});
  };
  // A triangle stays as written, even with no area (it is a triangle id the
  // file's author can count on, and no ray hits it); a quad is two triangles.
  if (n == 3) {
    emit(0, 1, 2);
    return;
  }
  outline_.clear();
  for (const uint32_t p : cornerPositions_) outline_.push_back(positions_[p]);
  if (n == 4) {
    for (const auto& [a, b, c] : splitQuad(std::span<const glm::vec3, 4>(outline_.data(), 4))) emit(a, b, c);
    return;
  }
  const PolygonTriangles cut = triangulatePolygon(outline_);
  // A polygon with no area adds nothing a ray could hit; one that crosses
  // itself has no surface we could say the author meant.
  if (cut.fault == PolygonFault::NoArea) return;
  if (cut.fault != PolygonFault::None) fail(fmt::format("face of {} vertices {}", n, describe(cut.fault)));
  for (const auto& [a, b, c] : cut.triangles) emit(a, b, c);
}

void ObjReader::useMaterial(std::string_view name) {
  const auto [it, fresh] = slotOf_.try_emplace(std::string(name), uint32_t(slotNames_.size()));
  if (fresh) {
    slotNames_.emplace_back(name);
    slotLines_.push_back(line_);
  }
  slot_ = it->second;
}

// "mtllib a.mtl b.mtl": several files, each relative to the OBJ's folder, unless
// the whole line names one file (a name with blanks).
void ObjReader::materialLibraries(std::string_view files) {
  std::vector<std::string_view> names;
  std::error_code error;
  if (!files.empty() && std::filesystem::is_regular_file(folder_ / files, error)) {
    names.push_back(files);
  } else {
    splitWords(files, names);
  }
  const auto read = [&](const std::string& path) {
    if (std::find(libraryFiles_.begin(), libraryFiles_.end(), path) != libraryFiles_.end()) return;
    libraryFiles_.push_back(path);
    library_.read(readFileBytes(path), path);
  };
  for (const std::string_view file : names) {
    const std::string path = (folder_ / file).string();
    if (std::filesystem::is_regular_file(path, error)) {
      read(path);
      continue;
    }
    // Go on, as assimp did: the geometry is what Lancer traces, and OBJ files
    // often travel without their MTL or with it renamed. assimp's fallback, the
    // OBJ's own name with .mtl, is tried too.
    std::string fallback = (folder_ / std::filesystem::path(name_).filename().replace_extension(".mtl")).string();
    if (std::filesystem::is_regular_file(fallback, error)) {
      read(fallback);
      fallback = fmt::format(": read {} instead", fallback);
    } else {
      fallback = ": its materials are drawn with the default material";
    }
    scene_.warnings.push_back(fmt::format("{}:{}: MTL file {} not found{}", name_, line_, path, fallback));
  }
}

// Slots become materials: the MTL files' materials in the order of their
// newmtl, then, as faces first used them, the default material for faces
// without usemtl and one default material for each name no MTL file defines
// (named as usemtl names it, with a warning).
void ObjReader::finishMaterials() {
  scene_.materials = library_.materials();
  std::vector<bool> used(slotNames_.size(), false);
  for (const uint32_t s : scene_.materialOf) used[s] = true;
  std::vector<uint32_t> materialOfSlot(slotNames_.size(), 0);
  for (size_t s = 0; s < slotNames_.size(); ++s) {
    if (const std::optional<uint32_t> m = library_.find(slotNames_[s])) {
      materialOfSlot[s] = *m;
      continue;
    }
    if (!used[s]) continue;
    if (s > 0) {
      scene_.warnings.push_back(fmt::format("{}:{}: usemtl '{}': no MTL file defines it: drawn with the default "
                                            "material",
                                            name_, slotLines_[s], slotNames_[s]));
    }
    Material fallback;
    fallback.name = s == 0 ? "default" : slotNames_[s];
    materialOfSlot[s] = uint32_t(scene_.materials.size());
    scene_.materials.push_back(fallback);
  }
  for (uint32_t& m : scene_.materialOf) m = materialOfSlot[m];
}

}  // namespace

Scene readObj(std::string_view text, const std::string& name, const std::filesystem::path& folder) {
  return ObjReader(name, folder).read(text);
}

Scene loadObj(const std::string& path) {
  return readObj(readFileBytes(path), path, std::filesystem::path(path).parent_path());
}

std::vector<Material> readMtl(std::string_view text, const std::string& name) {
  MtlLibrary library;
  library.read(text, name);
  return library.materials();
}

}  // namespace lancer
