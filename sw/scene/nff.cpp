#include "scene/nff.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/polygon.h"
#include "scene/text.h"

namespace lancer {

namespace {

// ---- Lines and tokens ---------------------------------------------------------

// The file as lines of tokens, comments ("#" to the end of the line) and blank
// lines dropped, each line with its number for messages.
class Lines {
 public:
  Lines(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  // The next non-empty line's tokens, or nullopt at the end of the file.
  std::optional<std::vector<std::string>> next() {
    if (pushedBack_) {
      pushedBack_ = false;
      return last_;
    }
    std::string text;
    while (std::getline(in_, text)) {
      ++number_;
      if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
      std::istringstream words(text);
      std::vector<std::string> tokens;
      for (std::string w; words >> w;) tokens.push_back(std::move(w));
      if (!tokens.empty()) {
        last_ = std::move(tokens);
        return last_;
      }
    }
    return std::nullopt;
  }
  // The line last returned by next() is returned again by the next call.
  void pushBack() { pushedBack_ = true; }

  int number() const { return number_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", name_, number_, what));
  }

 private:
  std::istream& in_;
  std::string name_;
  int number_ = 0;
  std::vector<std::string> last_;
  bool pushedBack_ = false;
};

// Correctly rounded (scene/text.h); a number beyond float range is an error,
// one below it reads as zero.
float parseNumber(const Lines& lines, const std::string& token) {
  const std::optional<float> value = parseFloat(token);
  if (!value || !std::isfinite(*value)) lines.fail(fmt::format("expected a finite number, got '{}'", token));
  return *value;
}

int parseCount(const Lines& lines, const std::string& token) {
  int value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) lines.fail(fmt::format("expected a whole number, got '{}'", token));
  return value;
}

// The numbers of one line after its first `skip` tokens; exactly `count` of them
// (or any of `counts`).
std::vector<float> numbersOf(const Lines& lines, const std::vector<std::string>& tokens, size_t skip,
                             std::initializer_list<size_t> counts, std::string_view what) {
  const size_t have = tokens.size() - skip;
  if (std::find(counts.begin(), counts.end(), have) == counts.end()) {
    lines.fail(fmt::format("{} takes {} numbers, this line has {}", what, fmt::join(counts, " or "), have));
  }
  std::vector<float> out;
  for (size_t i = skip; i < tokens.size(); ++i) out.push_back(parseNumber(lines, tokens[i]));
  return out;
}

// `count` numbers from the lines after an entity's header, however they are
// split across lines (generators differ); the entity started at `startLine`.
std::vector<float> numbersAfter(Lines& lines, size_t count, std::string_view what, int startLine) {
  std::vector<float> out;
  while (out.size() < count) {
    const auto tokens = lines.next();
    if (!tokens) lines.fail(fmt::format("{} started at line {} is truncated: the file ends", what, startLine));
    for (const std::string& t : *tokens) {
      if (out.size() == count) lines.fail(fmt::format("{} started at line {} has too many numbers", what, startLine));
      out.push_back(parseNumber(lines, t));
    }
  }
  return out;
}

glm::vec3 vec(const std::vector<float>& n, size_t at) { return {n[at], n[at + 1], n[at + 2]}; }

// ---- Building the scene -------------------------------------------------------------

class Builder {
 public:
  Builder(Scene& scene, const Lines& lines) : scene_(scene), lines_(lines) {}

  void setMaterial(const Material& m) {
    for (size_t i = 0; i < scene_.materials.size(); ++i) {
      const Material& o = scene_.materials[i];
      if (o.diffuse == m.diffuse && o.kd == m.kd && o.ks == m.ks && o.shine == m.shine &&
          o.transmittance == m.transmittance && o.ior == m.ior) {
        current_ = uint32_t(i);
        return;
      }
    }
    scene_.materials.push_back(m);
    current_ = uint32_t(scene_.materials.size() - 1);
  }

  // The material of the next primitive: the last "f", or a default one.
  uint32_t material() {
    if (!current_) {
      Material fallback;
      fallback.name = "default";
      setMaterial(fallback);
    }
    return *current_;
  }

  void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const ShadingNormals& n) {
    const uint32_t m = material();
    // A sphere or cone near the edge of float range can put its tessellated
    // vertices beyond it (found by tests/fuzz/fuzz_nff).
    if (!allFinite(a) || !allFinite(b) || !allFinite(c)) {
      lines_.fail("the primitive reaches beyond float range (a tessellated vertex is infinite)");
    }
    scene_.triangles.push_back({a, b, c});
    scene_.materialOf.push_back(m);
    scene_.normals.push_back(n);
  }

  // A native sphere or cone (checked by checkSphere / checkCone first); its
  // material joins materialOf after the triangles' (finish()).
  void quadric(const Quadric& q) {
    const uint32_t m = material();
    if (!allFinite(q.bounds().lo) || !allFinite(q.bounds().hi)) {
      lines_.fail("the primitive reaches beyond float range (its bounding box is infinite)");
    }
    scene_.quadrics.push_back(q);
    quadricMaterials_.push_back(m);
  }
  // Ends the scene's id space: the quadrics' materials after the triangles'.
  void finish() {
    scene_.materialOf.insert(scene_.materialOf.end(), quadricMaterials_.begin(), quadricMaterials_.end());
  }

  void checkSphere(float radius) const {
    if (radius == 0.0f) lines_.fail("sphere of radius 0");
  }
  void checkCone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius) const {
    if (base == apex) lines_.fail("cone whose base and apex coincide");
    if ((baseRadius < 0) != (apexRadius < 0) && baseRadius != 0 && apexRadius != 0) {
      lines_.fail("cone radii of opposite signs (both negative means inside visible)");
    }
    if (baseRadius == 0 && apexRadius == 0) lines_.fail("cone of radius 0");
  }

  // `start`: the line the polygon's entity began on, for its messages.
  void polygon(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>* normals, int start);
  void sphere(const glm::vec3& center, float radius, int divisions);
  void cone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius, int slices);

 private:
  Scene& scene_;
  const Lines& lines_;
  std::optional<uint32_t> current_;
  std::vector<uint32_t> quadricMaterials_;
};

// Ear clipping in the polygon's plane (scene/polygon.h); triangles keep the
// polygon's winding, a "p" polygon's normals are its plane's.
void Builder::polygon(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>* normals, int start) {
  const PolygonTriangles cut = triangulatePolygon(points);
  if (cut.fault != PolygonFault::None) {
    lines_.fail(fmt::format("polygon started at line {} {}", start, describe(cut.fault)));
  }
  const auto normalOf = [&](uint32_t i) { return normals ? (*normals)[i] : cut.normal; };
  for (const auto& [a, b, c] : cut.triangles) {
    triangle(points[a], points[b], points[c], {normalOf(a), normalOf(b), normalOf(c)});
  }
}

// A cube projected onto the sphere. Grid coordinates are -1 + 2k/N on every
// face, so a point on an edge shared by two faces is computed from the same
// doubles by both and rounds to the same floats: the mesh is watertight.
void Builder::sphere(const glm::vec3& center, float radius, int divisions) {
  checkSphere(radius);
  const bool inside = radius < 0.0f;  // only the inside visible: wind inwards
  const double r = std::fabs(double(radius));
  const int n = divisions;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {1.0, -1.0}) {
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      std::vector<glm::vec3> grid, normal;
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          glm::dvec3 p;
          p[axis] = side;
          p[b] = -1.0 + 2.0 * i / n;
          p[c] = -1.0 + 2.0 * j / n;
          const glm::dvec3 u = glm::normalize(p);
          grid.push_back(glm::vec3(glm::dvec3(center) + r * u));
          normal.push_back(glm::vec3(inside ? -u : u));
        }
      }
      // (e_b x e_c) = e_axis: counter-clockwise from outside on the + side.
      const bool flip = (side < 0) != inside;
      const auto id = [n](int i, int j) { return size_t(i * (n + 1) + j); };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const size_t p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1), p01 = id(i, j + 1);
          using Corner = std::array<size_t, 3>;
          for (const auto& [x, y, z] : {Corner{p00, p10, p11}, Corner{p00, p11, p01}}) {
            if (flip) {
              triangle(grid[x], grid[z], grid[y], {normal[x], normal[z], normal[y]});
            } else {
              triangle(grid[x], grid[y], grid[z], {normal[x], normal[y], normal[z]});
            }
          }
        }
      }
    }
  }
}

// An open cone (or cylinder) of `slices` quads; the last seam reuses the
// first ring's vertices. Outward winding: (base_k, base_k+1, apex_k+1).
void Builder::cone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius, int slices) {
  checkCone(base, baseRadius, apex, apexRadius);
  const bool inside = baseRadius < 0 || apexRadius < 0;
  const double rb = std::fabs(double(baseRadius)), ra = std::fabs(double(apexRadius));
  const glm::dvec3 b(base), a(apex);
  const glm::dvec3 w = glm::normalize(a - b);
  const double height = glm::length(a - b);
  const glm::dvec3 helper = std::fabs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, w)), v = glm::cross(w, u);
  std::vector<glm::vec3> low, high, normal;
  for (int k = 0; k < slices; ++k) {
    const double theta = 2.0 * std::numbers::pi * k / slices;
    const glm::dvec3 dir = std::cos(theta) * u + std::sin(theta) * v;
    low.push_back(glm::vec3(b + rb * dir));
    high.push_back(glm::vec3(a + ra * dir));
    const glm::dvec3 nrm = glm::normalize(dir * height + w * (rb - ra));
    normal.push_back(glm::vec3(inside ? -nrm : nrm));
  }
  const auto emit = [&](const glm::vec3& p, const glm::vec3& q, const glm::vec3& s, const ShadingNormals& n) {
    if (p == q || q == s || s == p) return;  // the apex of a pointed cone
    if (inside) {
      triangle(p, s, q, {n.n0, n.n2, n.n1});
    } else {
      triangle(p, q, s, n);
    }
  };
  for (int k = 0; k < slices; ++k) {
    const int k1 = (k + 1) % slices;
    emit(low[k], low[k1], high[k1], {normal[k], normal[k1], normal[k1]});
    emit(low[k], high[k1], high[k], {normal[k], normal[k1], normal[k]});
  }
}

void readView(Lines& lines, Scene& scene) {
  View view;
  float angle = 45.0f;
  while (const auto tokens = lines.next()) {
    const std::string& key = (*tokens)[0];
    if (key == "from") {
      view.eye = vec(numbersOf(lines, *tokens, 1, {3}, "'from'"), 0);
    } else if (key == "at") {
      view.target = vec(numbersOf(lines, *tokens, 1, {3}, "'at'"), 0);
    } else if (key == "up") {
      view.up = vec(numbersOf(lines, *tokens, 1, {3}, "'up'"), 0);
    } else if (key == "angle") {
      angle = numbersOf(lines, *tokens, 1, {1}, "'angle'")[0];
      if (!(angle > 0.0f && angle < 180.0f)) lines.fail(fmt::format("view angle {} is not in (0, 180) degrees", angle));
    } else if (key == "hither") {
      numbersOf(lines, *tokens, 1, {1}, "'hither'");  // no hither plane in a ray tracer
    } else if (key == "resolution") {
      if (tokens->size() != 3) lines.fail("'resolution' takes two whole numbers");
      view.width = parseCount(lines, (*tokens)[1]);
      view.height = parseCount(lines, (*tokens)[2]);
      if (view.width < 1 || view.height < 1) lines.fail("resolution must be at least 1 x 1");
    } else {
      lines.pushBack();
      break;
    }
  }
  if (view.eye == view.target) lines.fail("view 'from' and 'at' coincide");
  // NFF's angle spans the centres of the top and bottom pixel rows; the
  // camera's field of view spans the image's edges, half a pixel further out.
  const double half = std::tan(double(angle) * std::numbers::pi / 360.0);
  const double rows = view.height > 1 ? double(view.height) : 2.0;
  view.fovYDegrees = float(360.0 / std::numbers::pi * std::atan(half * rows / (rows - 1.0)));
  scene.view = view;
}

}  // namespace

Scene readNff(std::istream& in, const std::string& name, const NffOptions& options) {
  if (options.sphereDivisions < 1 || options.coneSlices < 3) {
    throw InputError(fmt::format("NFF tessellation: sphere divisions {} (>= 1) and cone slices {} (>= 3)",
                                 options.sphereDivisions, options.coneSlices));
  }
  Scene scene;
  scene.name = name;
  Lines lines(in, name);
  Builder build(scene, lines);
  while (const auto tokens = lines.next()) {
    const std::string& key = (*tokens)[0];
    const int start = lines.number();
    if (key == "v") {
      if (tokens->size() != 1) lines.fail("'v' stands alone on its line");
      readView(lines, scene);
    } else if (key == "b") {
      scene.background = vec(numbersOf(lines, *tokens, 1, {3}, "'b'"), 0);
    } else if (key == "l") {
      const auto n = numbersOf(lines, *tokens, 1, {3, 6}, "'l'");
      Light light;
      light.position = vec(n, 0);
      if (n.size() == 6) light.color = vec(n, 3);
      light.name = fmt::format("l@{}", start);
      scene.lights.push_back(light);
    } else if (key == "f") {
      const auto n = numbersOf(lines, *tokens, 1, {8}, "'f'");
      Material m;
      m.name = fmt::format("f@{}", start);
      m.diffuse = vec(n, 0);
      m.kd = n[3];
      m.ks = n[4];
      m.shine = n[5];
      m.transmittance = n[6];
      m.ior = n[7];
      if (m.kd < 0 || m.ks < 0 || m.shine < 0) lines.fail("Kd, Ks and Shine must be >= 0");
      if (m.transmittance < 0) lines.fail(fmt::format("transmittance T = {} is negative", m.transmittance));
      // The SPD's generators write 0 on opaque surfaces, where it means nothing.
      if (m.transmittance > 0 && m.ior <= 0) {
        lines.fail(fmt::format("index of refraction {} must be > 0 on a transmitting surface (T = {})", m.ior,
                               m.transmittance));
      }
      if (m.transmittance == 0 && m.ior <= 0) m.ior = 1.0f;
      build.setMaterial(m);
    } else if (key == "p" || key == "pp") {
      if (tokens->size() != 2) lines.fail(fmt::format("'{}' takes the vertex count", key));
      const int count = parseCount(lines, (*tokens)[1]);
      if (count < 3) lines.fail(fmt::format("polygon of {} vertices (at least 3)", count));
      const size_t stride = key == "p" ? 3 : 6;
      const auto n = numbersAfter(lines, stride * size_t(count), key == "p" ? "polygon" : "patch", start);
      std::vector<glm::vec3> points, normals;
      for (int i = 0; i < count; ++i) {
        points.push_back(vec(n, stride * size_t(i)));
        if (stride == 6) {
          const glm::vec3 nrm = vec(n, stride * size_t(i) + 3);
          if (nrm == glm::vec3(0.0f)) lines.fail(fmt::format("patch started at line {}: vertex {} has a zero normal", start, i));
          // In double: in float the squared length of a tiny or huge normal
          // under- or overflows, and the normal becomes NaN or zero.
          normals.push_back(glm::vec3(glm::normalize(glm::dvec3(nrm))));
        }
      }
      build.polygon(points, stride == 6 ? &normals : nullptr, start);
    } else if (key == "s") {
      const auto n = numbersOf(lines, *tokens, 1, {4}, "'s'");
      if (options.quadrics == QuadricForm::Native) {
        build.checkSphere(n[3]);
        build.quadric(Quadric::sphere(vec(n, 0), n[3]));
      } else {
        build.sphere(vec(n, 0), n[3], options.sphereDivisions);
      }
    } else if (key == "c") {
      // NFF.TXT puts the numbers on the two lines after 'c'; the SPD's own
      // generators (rings, tree) write all eight on the line of the 'c'.
      const auto n = tokens->size() == 1 ? numbersAfter(lines, 8, "cone", start)
                                         : numbersOf(lines, *tokens, 1, {8}, "'c'");
      if (options.quadrics == QuadricForm::Native) {
        build.checkCone(vec(n, 0), n[3], vec(n, 4), n[7]);
        build.quadric(Quadric::cone(vec(n, 0), n[3], vec(n, 4), n[7]));
      } else {
        build.cone(vec(n, 0), n[3], vec(n, 4), n[7], options.coneSlices);
      }
    } else {
      lines.fail(fmt::format("unknown NFF entity '{}' (v, b, l, f, p, pp, s, c)", key));
    }
  }
  build.finish();
  if (scene.primitiveCount() == 0) {
    throw InputError(fmt::format("{}: the scene has no triangles{}", name,
                                 options.quadrics == QuadricForm::Native ? ", spheres or cones" : ""));
  }
  scene.computeBounds();
  return scene;
}

Scene loadNff(const std::string& path, const NffOptions& options) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open file", path));
  return readNff(in, path, options);
}

}  // namespace lancer
