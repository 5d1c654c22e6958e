// The NFF reader (sw/scene/nff.h): every entity of NFF.TXT, triangulation of
// concave polygons, watertight tessellations of spheres and cones, and the
// error messages for malformed files.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/nff.h"

namespace lancer {
namespace {

Scene parse(const std::string& text, const NffOptions& options = {}) {
  std::istringstream in(text);
  return readNff(in, "test.nff", options);
}

std::string errorOf(const std::string& text, const NffOptions& options = {}) {
  try {
    parse(text, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

glm::dvec3 normalOf(const Triangle& t) {
  return glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0));
}

double areaOf(const Scene& s) {
  double a = 0;
  for (const Triangle& t : s.triangles) a += 0.5 * glm::length(normalOf(t));
  return a;
}

// Every undirected edge of the mesh and how many triangles use it; a closed
// mesh uses each exactly twice, once in each direction (consistent winding).
std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> directedEdges(const Scene& s) {
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
  for (const Triangle& t : s.triangles) {
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int i = 0; i < 3; ++i) {
      const glm::vec3 a = v[i], b = v[(i + 1) % 3];
      ++edges[{{a.x, a.y, a.z}, {b.x, b.y, b.z}}];
    }
  }
  return edges;
}

TEST(Nff, ReadsViewBackgroundLightsMaterialsAndPolygons) {
  const Scene s = parse(R"(# a comment line
v
from 0 0 10
at 0 0 0
up 0 1 0
angle 40
hither 1
resolution 64 48
b 0.1 0.2 0.3
l 1 2 3
l 4 5 6 0.5 0.5 0.5   # with a colour
f 1 0 0 0.7 0.3 12 0 1
p 4
0 0 0
1 0 0
1 1 0
0 1 0
f 0 0 1 0.1 0.2 3 0.9 1.5
pp 3
0 0 1 0 0 1
1 0 1 0 0 1
0 1 1 0 1 1
)");
  ASSERT_TRUE(s.view);
  EXPECT_EQ(s.view->eye, glm::vec3(0, 0, 10));
  EXPECT_EQ(s.view->width, 64);
  EXPECT_EQ(s.view->height, 48);
  // 40 degrees between the centres of the outer rows of 48: a bit more edge to edge.
  EXPECT_NEAR(s.view->fovYDegrees, 2 * std::atan(std::tan(20 * std::numbers::pi / 180) * 48 / 47) * 180 / std::numbers::pi, 1e-4);
  EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.3f));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f));
  EXPECT_EQ(s.lights[1].position, glm::vec3(4, 5, 6));
  EXPECT_EQ(s.lights[1].color, glm::vec3(0.5f));
  ASSERT_EQ(s.triangles.size(), 3u);
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& red = s.materials[s.materialOf[0]];
  EXPECT_EQ(red.diffuse, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(red.ks, 0.3f);
  EXPECT_FLOAT_EQ(red.shine, 12.0f);
  const Material& glass = s.materials[s.materialOf[2]];
  EXPECT_FLOAT_EQ(glass.transmittance, 0.9f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  // Counter-clockwise seen from +z: normals along +z.
  for (const Triangle& t : s.triangles) EXPECT_GT(normalOf(t).z, 0.0);
  ASSERT_EQ(s.normals.size(), 3u);
  EXPECT_EQ(s.normals[0].n0, glm::vec3(0, 0, 1));  // a plain polygon: its plane's normal
  EXPECT_NEAR(s.normals[2].n2.y, std::sqrt(0.5f), 1e-6);  // a patch: its own, normalized
}

// A concave outline: the triangles cover exactly its area, with its winding.
void expectTriangulated(const std::vector<glm::dvec2>& outline, double area) {
  std::string text = fmt::format("p {}\n", outline.size());
  for (const glm::dvec2& p : outline) text += fmt::format("{} {} 2\n", p.x, p.y);
  const Scene s = parse(text);
  // n - 2 triangles, less any that clipping left with no area (dropped).
  EXPECT_LE(s.triangles.size(), outline.size() - 2);
  EXPECT_GE(s.triangles.size(), outline.size() / 2);
  EXPECT_NEAR(areaOf(s), area, 1e-4 * area);
  for (const Triangle& t : s.triangles) EXPECT_GT(normalOf(t).z, 0.0);
}

TEST(Nff, TriangulatesConcavePolygons) {
  // An L and a comb.
  expectTriangulated({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 3.0);
  expectTriangulated({{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}},
                     15.0 - 2 * 2.0);
  // A gear as the SPD draws it: 36 teeth of 4 vertices each, 144 vertices.
  std::vector<glm::dvec2> gear;
  for (int tooth = 0; tooth < 36; ++tooth) {
    for (int k = 0; k < 4; ++k) {
      const double angle = 2 * std::numbers::pi * (tooth + k / 4.0) / 36;
      const double radius = (k == 1 || k == 2) ? 10.0 : 8.0;
      gear.push_back({radius * std::cos(angle), radius * std::sin(angle)});
    }
  }
  double area = 0;
  for (size_t i = 0; i < gear.size(); ++i) {
    const glm::dvec2 p = gear[i], q = gear[(i + 1) % gear.size()];
    area += 0.5 * (p.x * q.y - q.x * p.y);
  }
  // The printed coordinates round; the area check allows it.
  expectTriangulated(gear, area);
}

TEST(Nff, ClockwisePolygonKeepsItsWinding) {
  const Scene s = parse("p 4\n0 0 0\n0 1 0\n1 1 0\n1 0 0\n");
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const Triangle& t : s.triangles) EXPECT_LT(normalOf(t).z, 0.0);
}

TEST(Nff, SpheresAreWatertightOnTheSurfaceAndFaceOut) {
  NffOptions options;
  options.sphereDivisions = 4;
  const Scene s = parse("s 1 2 3 0.5\n", options);
  EXPECT_EQ(s.triangles.size(), 6u * 2 * 16);
  const auto edges = directedEdges(s);
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << "an edge without its twin";
  }
  const glm::dvec3 c(1, 2, 3);
  for (size_t i = 0; i < s.triangles.size(); ++i) {
    const Triangle& t = s.triangles[i];
    EXPECT_NEAR(glm::length(glm::dvec3(t.v0) - c), 0.5, 1e-6);
    const glm::dvec3 centroid = (glm::dvec3(t.v0) + glm::dvec3(t.v1) + glm::dvec3(t.v2)) / 3.0;
    EXPECT_GT(glm::dot(normalOf(t), centroid - c), 0.0);
    EXPECT_GT(glm::dot(glm::dvec3(s.normals[i].n0), centroid - c), 0.0);
  }
  // Only the inside visible: wound inwards.
  const Scene inner = parse("s 0 0 0 -1\n", options);
  const Triangle& t = inner.triangles[0];
  EXPECT_LT(glm::dot(normalOf(t), (glm::dvec3(t.v0) + glm::dvec3(t.v1) + glm::dvec3(t.v2)) / 3.0), 0.0);
}

TEST(Nff, ConesAndCylindersAreOpenTubesFacingOut) {
  NffOptions options;
  options.coneSlices = 12;
  const Scene s = parse("c\n0 0 0 1\n0 0 3 0.5\n", options);
  EXPECT_EQ(s.triangles.size(), 24u);
  int border = 0;
  const auto edges = directedEdges(s);
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    border += edges.count({edge.second, edge.first}) == 0;
  }
  EXPECT_EQ(border, 24);  // the two open rims
  for (const Triangle& t : s.triangles) {
    const glm::dvec3 centroid = (glm::dvec3(t.v0) + glm::dvec3(t.v1) + glm::dvec3(t.v2)) / 3.0;
    EXPECT_GT(glm::dot(normalOf(t), glm::dvec3(centroid.x, centroid.y, 0)), 0.0);
  }
  // A pointed cone drops the apex's zero-area triangles.
  EXPECT_EQ(parse("c\n0 0 0 1\n0 0 3 0\n", options).triangles.size(), 12u);
}

TEST(Nff, ConeNumbersOnTheLineOfTheCAsTheSpdWritesThem) {
  NffOptions options;
  options.coneSlices = 12;
  const Scene twoLines = parse("c\n0 0 0 1\n0 0 3 0.5\n", options);
  const Scene oneLine = parse("c 0 0 0 1 0 0 3 0.5\n", options);
  ASSERT_EQ(oneLine.triangles.size(), twoLines.triangles.size());
  for (size_t i = 0; i < oneLine.triangles.size(); ++i) {
    EXPECT_EQ(oneLine.triangles[i].v0, twoLines.triangles[i].v0);
    EXPECT_EQ(oneLine.triangles[i].v1, twoLines.triangles[i].v1);
    EXPECT_EQ(oneLine.triangles[i].v2, twoLines.triangles[i].v2);
  }
  EXPECT_NE(errorOf("c 0 0 0 1 0 0 3\n").find("test.nff:1: 'c' takes 8 numbers, this line has 7"), std::string::npos);
  EXPECT_NE(errorOf("c 0 0 0 1\n0 0 3 0.5\n").find("test.nff:1: 'c' takes 8 numbers, this line has 4"),
            std::string::npos);
}

TEST(Nff, ErrorsNameTheFileAndLine) {
  EXPECT_NE(errorOf("b 0 0 0\nq 1 2 3\n").find("test.nff:2: unknown NFF entity 'q'"), std::string::npos);
  EXPECT_NE(errorOf("f 1 1 1 1 0 0 0\n").find("test.nff:1: 'f' takes 8 numbers, this line has 7"), std::string::npos);
  EXPECT_NE(errorOf("f 1 1 1 1 0 0 0.5 0\n").find("test.nff:1: index of refraction 0 must be > 0 on a transmitting"),
            std::string::npos);
  EXPECT_NE(errorOf("f 1 1 1 1 0 0 0.5 -1.5\n").find("test.nff:1: index of refraction -1.5"), std::string::npos);
  EXPECT_NE(errorOf("f 1 1 1 1 0 0 -0.5 1\n").find("test.nff:1: transmittance T = -0.5 is negative"), std::string::npos);
  EXPECT_NE(errorOf("p 3\n0 0 0\n1 0 0\n").find("polygon started at line 1 is truncated"), std::string::npos);
  EXPECT_NE(errorOf("p 3\n0 0 0\n1 x 0\n0 1 0\n").find("test.nff:3: expected a finite number, got 'x'"),
            std::string::npos);
  EXPECT_NE(errorOf("p 2\n0 0 0\n1 0 0\n").find("polygon of 2 vertices"), std::string::npos);
  EXPECT_NE(errorOf("p 3\n0 0 0\n1 1 1\n2 2 2\n").find("polygon started at line 1 has no area"), std::string::npos);
  // A bow tie: its two halves cancel, no area to triangulate.
  EXPECT_NE(errorOf("p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n").find("test.nff:5: polygon started at line 1 has no area"), std::string::npos);
  EXPECT_NE(errorOf("s 0 0 0 0\n").find("sphere of radius 0"), std::string::npos);
  EXPECT_NE(errorOf("c\n0 0 0 1\n0 0 0 1\n").find("base and apex coincide"), std::string::npos);
  EXPECT_NE(errorOf("l 1 2 3\n").find("the scene has no triangles"), std::string::npos);
  EXPECT_NE(errorOf("v\nfrom 0 0 0\nat 0 0 0\n").find("'from' and 'at' coincide"), std::string::npos);
}

// QuadricForm::Native (issue #40): spheres and cones as read, after the
// triangles in the id space, each with the material of its "f".
TEST(Nff, NativeQuadricsKeepTheirNumbersAndMaterials) {
  NffOptions native;
  native.quadrics = QuadricForm::Native;
  const std::string text =
      "f 1 0 0 1 0 0 0 1\n"
      "s 0 0 5 -2\n"
      "p 3\n0 0 0\n1 0 0\n0 1 0\n"
      "f 0 1 0 1 0 0 0 1\n"
      "c\n0 0 0 1.5\n0 0 4 0\n"
      "c 1 1 1 -1 2 2 2 -0.5\n";
  const Scene scene = parse(text, native);
  ASSERT_EQ(scene.triangles.size(), 1u);
  ASSERT_EQ(scene.quadrics.size(), 3u);
  EXPECT_TRUE(scene.normals.size() == 1u);
  EXPECT_EQ(scene.primitiveCount(), 4u);
  const Quadric& sphere = scene.quadricOf(1);
  EXPECT_EQ(sphere.kind, Quadric::Kind::Sphere);
  EXPECT_EQ(sphere.center(), glm::vec3(0, 0, 5));
  EXPECT_EQ(sphere.radius(), -2.0f);  // kept as read: only the inside visible
  EXPECT_TRUE(sphere.insideVisible());
  const Quadric& cone = scene.quadricOf(2);
  EXPECT_EQ(cone.kind, Quadric::Kind::Cone);
  EXPECT_EQ(cone.base, glm::vec3(0, 0, 0));
  EXPECT_EQ(cone.baseRadius, 1.5f);
  EXPECT_EQ(cone.apex, glm::vec3(0, 0, 4));
  EXPECT_EQ(cone.apexRadius, 0.0f);
  EXPECT_FALSE(cone.insideVisible());
  EXPECT_TRUE(scene.quadricOf(3).insideVisible());
  // One material entry per primitive: the triangle's, then the quadrics' in file order.
  ASSERT_EQ(scene.materialOf.size(), 4u);
  EXPECT_EQ(scene.materials[scene.materialOf[0]].diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(scene.materials[scene.materialOf[1]].diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(scene.materials[scene.materialOf[2]].diffuse, glm::vec3(0, 1, 0));
  EXPECT_EQ(scene.materials[scene.materialOf[3]].diffuse, glm::vec3(0, 1, 0));
  // The bounds hold the sphere (z up to 7) and the cone (x down to -1.5).
  EXPECT_GE(scene.bounds.hi.z, 7.0f);
  EXPECT_LE(scene.bounds.lo.x, -1.5f);
  EXPECT_LE(scene.bounds.lo.z, 0.0f);
  // The default still tessellates: no quadrics, the same triangles as before.
  const Scene tessellated = parse(text);
  EXPECT_TRUE(tessellated.quadrics.empty());
  EXPECT_EQ(tessellated.materialOf.size(), tessellated.triangles.size());
  EXPECT_GT(tessellated.triangles.size(), 700u);
  // A file of quadrics only is a scene.
  EXPECT_EQ(parse("s 0 0 0 1\n", native).quadrics.size(), 1u);
}

TEST(Nff, NativeQuadricsAreRefusedAsTessellatedOnesAre) {
  NffOptions native;
  native.quadrics = QuadricForm::Native;
  const auto nativeError = [&](const std::string& text) { return errorOf(text, native); };
  EXPECT_NE(nativeError("s 0 0 0 0\n").find("test.nff:1: sphere of radius 0"), std::string::npos);
  EXPECT_NE(nativeError("s 0 0 0 -0\n").find("sphere of radius 0"), std::string::npos);
  EXPECT_NE(nativeError("c\n0 0 0 1\n0 0 0 1\n").find("base and apex coincide"), std::string::npos);
  EXPECT_NE(nativeError("c\n0 0 0 0\n0 0 1 0\n").find("cone of radius 0"), std::string::npos);
  EXPECT_NE(nativeError("c\n0 0 0 1\n0 0 1 -1\n").find("radii of opposite signs"), std::string::npos);
  EXPECT_NE(nativeError("s 0 nan 0 1\n").find("expected a finite number, got 'nan'"), std::string::npos);
  EXPECT_NE(nativeError("c 0 0 0 1 0 0 inf 1\n").find("expected a finite number"), std::string::npos);
  EXPECT_NE(nativeError("s 3e38 0 0 3e38\n").find("the primitive reaches beyond float range"), std::string::npos);
  EXPECT_NE(nativeError("l 1 2 3\n").find("the scene has no triangles, spheres or cones"), std::string::npos);
}

// Found by tests/fuzz/fuzz_nff: a sphere or cone near the edge of float range
// was tessellated into infinite vertices, and the shading normals of a patch
// with tiny (or huge) normals were normalized in float into NaN (or zero).
TEST(Nff, GeometryBeyondFloatRangeIsAnErrorAndNormalsStayFinite) {
  EXPECT_NE(errorOf("s 3e38 0 0 3e38\n").find("test.nff:1: the primitive reaches beyond float range"),
            std::string::npos);
  EXPECT_NE(errorOf("c\n3e38 0 0 3e38\n3e38 1 0 3e38\n").find("beyond float range"), std::string::npos);
  const Scene patch = parse("pp 3\n0 0 0 1e-30 0 0\n1 0 0 0 1e-30 0\n0 1 0 3e38 3e38 3e38\n");
  ASSERT_EQ(patch.normals.size(), 1u);
  EXPECT_EQ(patch.normals[0].n0, glm::vec3(1, 0, 0));
  EXPECT_EQ(patch.normals[0].n1, glm::vec3(0, 1, 0));
  EXPECT_NEAR(patch.normals[0].n2.x, 1.0f / std::sqrt(3.0f), 1e-6f);
}

// The SPD's generators write an index of refraction of 0 on opaque surfaces.
TEST(Nff, OpaqueSurfacesMayGiveNoIndexOfRefraction) {
  const Scene s = parse("f 1 0 0 1 0 0 0 0\np 3\n0 0 0\n1 0 0\n0 1 0\n");
  ASSERT_EQ(s.size(), 1u);
  const Material& m = s.materials[s.materialOf[0]];
  EXPECT_EQ(m.transmittance, 0.0f);
  EXPECT_EQ(m.ior, 1.0f);
}

TEST(Nff, LoadSceneReadsNffFiles) {
  const auto path = std::filesystem::temp_directory_path() / "lancer_nff_test.NFF";
  {
    std::ofstream out(path);
    out << "f 0 1 0 1 0 0 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n";
  }
  const Scene s = loadScene(path.string());
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.materials[0].diffuse, glm::vec3(0, 1, 0));
  std::filesystem::remove(path);
  EXPECT_THROW(loadNff("/nonexistent/scene.nff"), InputError);
}

}  // namespace
}  // namespace lancer
