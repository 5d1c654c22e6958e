// Lancer's PLY and STL readers (sw/scene/ply.h, sw/scene/stl.h): ASCII
// coordinates correctly rounded, binary ones exact in both byte orders and
// every scalar type, faces and normals, and an error naming the file and
// where for every malformed file.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/ply.h"
#include "scene/stl.h"
#include "text_cases.h"

namespace lancer {
namespace {

using namespace std::string_literals;

uint32_t bitsOf(float f) { return std::bit_cast<uint32_t>(f); }

template <class Read>
std::string errorOf(Read read, const std::string& bytes) {
  try {
    read(bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string plyError(const std::string& bytes) {
  return errorOf([](const std::string& b) { readPly(b, "t.ply"); }, bytes);
}
std::string stlError(const std::string& bytes) {
  return errorOf([](const std::string& b) { readStl(b, "t.stl"); }, bytes);
}

// `value`'s bytes in little- or big-endian order.
template <class T>
std::string bytesOf(T value, bool big) {
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &value, sizeof(T));
  if (big) std::reverse(out.begin(), out.end());
  return out;
}

// ---- PLY --------------------------------------------------------------------------------

TEST(Ply, AsciiCoordinatesAreStrtofBitForBit) {
  std::vector<std::string> texts = test::kExtremeDecimals;
  for (const test::Halfway& h : test::kHalfwayDecimals) texts.emplace_back(h.text);
  std::string ply = fmt::format("ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty float y\n"
                                "property int z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
                                texts.size(), texts.size());
  for (const std::string& t : texts) ply += fmt::format("{} {} {}\n", t, t, t);
  for (size_t i = 0; i < texts.size(); ++i) ply += fmt::format("3 {} {} {}\n", i, i, i);
  const Scene scene = readPly(ply, "t.ply");
  ASSERT_EQ(scene.size(), texts.size());
  for (size_t i = 0; i < texts.size(); ++i) {
    const float want = std::strtof(texts[i].c_str(), nullptr);
    for (int axis = 0; axis < 3; ++axis) {  // whatever type the header declares: the text decides
      EXPECT_EQ(bitsOf(scene.triangles[i].v0[axis]), bitsOf(want)) << texts[i];
    }
  }
  EXPECT_TRUE(scene.normals.empty());
  EXPECT_EQ(scene.materials.size(), 1u);
}

// Both byte orders, every scalar type for coordinates, indices and counts;
// other properties and elements skipped, lists among them.
TEST(Ply, BinaryIsExact) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big-endian" : "little-endian");
    std::string ply = fmt::format(
        "ply\r\nformat {} 1.0\r\ncomment made by hand\r\nelement vertex 4\r\nproperty float x\r\nproperty double y\r\n"
        "property list uchar short junk\r\nproperty short z\r\nproperty uchar red\r\nelement face 1\r\n"
        "property uint flags\r\nproperty list ushort uint vertex_index\r\nelement edge 1\r\nproperty int a\r\nend_header\r\n",
        big ? "binary_big_endian" : "binary_little_endian");
    const float xs[4] = {0x1.59p-32f, 0x1p-149f, -0x1.fffffep127f, 0.1f};
    const double ys[4] = {0x1.0000010000001p0, 1e-40, 0.1, -3.0};  // rounded once to float
    const int16_t zs[4] = {-32768, 7, 0, 32767};
    for (int i = 0; i < 4; ++i) {
      ply += bytesOf(xs[i], big) + bytesOf(ys[i], big) + bytesOf(uint8_t(2), big) + bytesOf(int16_t(1), big) +
             bytesOf(int16_t(2), big) + bytesOf(zs[i], big) + bytesOf(uint8_t(255), big);
    }
    ply += bytesOf(uint32_t(9), big) + bytesOf(uint16_t(4), big);
    for (const uint32_t v : {0u, 1u, 2u, 3u}) ply += bytesOf(v, big);
    ply += bytesOf(int32_t(5), big);
    const Scene scene = readPly(ply, "t.ply");
    ASSERT_EQ(scene.size(), 2u);  // the quad
    std::vector<glm::vec3> corners;
    for (const Triangle& t : scene.triangles) corners.insert(corners.end(), {t.v0, t.v1, t.v2});
    for (const glm::vec3& c : corners) {
      const int i = int(std::find(xs, xs + 4, c.x) - xs);
      ASSERT_LT(i, 4) << c.x;
      EXPECT_EQ(bitsOf(c.y), bitsOf(float(ys[i])));
      EXPECT_EQ(c.z, float(zs[i]));
    }
  }
}

TEST(Ply, NormalsPolygonsAndFileOrder) {
  const Scene scene = readPly(
      "ply\nformat ascii 1.0\nCreated by Blender3D 247 (a header line without its keyword)\n"
      "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty float s\n"
      "element face 3\nproperty list uchar uint vertex_indices\nend_header\n"
      "0 0 0 0 0 2 0.5\n2 0 0 0 0 0 0.5\n2 2 0 0 3 4 0.5\n0 2 0 0 0 1 0.5\n1 1 0 0 0 1 0.5\n0 1 0 0 0 1 0.5\n"
      "3 0 1 2\n5 0 1 2 4 3\n3 2 3 0\n",
      "t.ply");
  ASSERT_EQ(scene.size(), 1u + 2u + 1u);  // the pentagon's notch lies on its diagonal: 2 triangles
  ASSERT_EQ(scene.normals.size(), scene.size());
  EXPECT_EQ(scene.normals[0].n0, glm::vec3(0, 0, 1));
  EXPECT_EQ(scene.normals[0].n1, glm::vec3(0, 0, 1));  // zero in the file: the geometric normal
  EXPECT_NEAR(scene.normals[0].n2.z, 0.8f, 1e-6f);
  double pentagon = 0.0;
  for (uint32_t t = 1; t < 3; ++t) {
    const Triangle& tri = scene.triangles[t];
    pentagon += 0.5 * glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0).z;
  }
  EXPECT_DOUBLE_EQ(pentagon, 3.0);  // the concave pentagon, wound as written
  EXPECT_EQ(scene.triangles[3].v0, glm::vec3(2, 2, 0));
}

TEST(Ply, MalformedFilesNameTheFileAndWhere) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  // Three zero vertices and a face list, in binary; a binary message names the byte from the file's start.
  const auto binary = [](const char* order, int faces) {
    return fmt::format("ply\nformat binary_{}_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
                       order, faces) +
           std::string(36, '\0') + "\x03";
  };
  const size_t littleHeader = binary("little", 2).size() - 37, bigHeader = binary("big", 1).size() - 37;
  for (const auto& [bytes, message] : std::vector<std::pair<std::string, std::string>>{
           {"", "t.ply:1: the header has no end_header line"},
           {"solid x\n", "t.ply:1: not a PLY file (it does not start with the line 'ply')"},
           {"ply\nformat ebcdic 1.0\nend_header\n", "t.ply:2: unknown format 'ebcdic' (ascii, binary_little_endian, binary_big_endian)"},
           {"ply\nelement vertex 1\nproperty float x\nend_header\n", "t.ply: the header has no 'format' line"},
           {"ply\nformat ascii 1.0\nproperty float x\n", "t.ply:3: a property before the first element"},
           {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\n", "t.ply:4: unknown type 'float128'"},
           {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n", "t.ply:4: a list's length must be of an integer type"},
           {"ply\nformat ascii 1.0\nelement vertex -1\n", "t.ply:3: 'element' takes a name and a count"},
           {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
            "t.ply:3: the vertex element needs scalar properties x, y and z"},
           {"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n3 0 1 2\n",
            "t.ply:3: the face element's vertex_indices must be a list of integers"},
           {"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n" + std::string(12, '\0'),
            "t.ply:3: element 'vertex' declares 1000000000000 instances, more than the file's 12 bytes of data hold"},
           {head + "0 0 0\n1 0 0\n", "t.ply:12: the data ends before the header's counts are read"},
           {head + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "t.ply:11: 'x' is not a number"},
           {head + "0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", "t.ply:11: vertex 1 (inf, 0, 0) is not finite"},
           {head + verts + "3 0 1 3\n", "t.ply:13: face 0: vertex index 3 is out of range (3 vertices)"},
           {head + verts + "3 0 1 -1\n", "t.ply:13: face 0: vertex index -1 is out of range (3 vertices)"},
           {head + verts + "2 0 1\n", "t.ply:13: face 0: 2 vertices (at least 3)"},
           {head + verts + "3 0 1 2.5\n", "t.ply:13: '2.5' is not a whole number"},
           {head + verts + "200 0 1 2\n", "t.ply:13: vertex_indices of 200 values: more than the rest of the file holds"},
           {binary("little", 2) + bytesOf(0, false) + bytesOf(1, false) + bytesOf(2, false),
            fmt::format("t.ply: byte {}: the data ends before the header's counts are read", littleHeader + 49)},
           {binary("big", 1) + bytesOf(0, true),
            fmt::format("t.ply: byte {}: vertex_indices of 3 values: more than the rest of the file holds", bigHeader + 37)},
           {head.substr(0, head.find("element face")) + "end_header\n" + verts, "t.ply: scene has no triangles"},
       }) {
    EXPECT_EQ(plyError(bytes), message) << bytes;
  }
}

// ---- STL --------------------------------------------------------------------------------

TEST(Stl, AsciiIsStrtofBinaryIsExact) {
  std::vector<std::string> texts = test::kExtremeDecimals;
  for (const test::Halfway& h : test::kHalfwayDecimals) texts.emplace_back(h.text);
  std::string stl = "solid test\n";
  for (const std::string& t : texts) {
    stl += fmt::format("  FACET NORMAL 0 0 0\n    outer loop\n      vertex {0} {0} {0}\n      vertex 1 0 0\n"
                       "      vertex 0 1 0\n    endloop\n  endfacet\n",
                       t);
  }
  stl += "endsolid test\nsolid second\nfacet normal 0 0 2\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
         "endloop\nendfacet\n";  // a second solid, its endsolid missing
  const Scene ascii = readStl(stl, "t.stl");
  ASSERT_EQ(ascii.size(), texts.size() + 1);
  for (size_t i = 0; i < texts.size(); ++i) {
    EXPECT_EQ(bitsOf(ascii.triangles[i].v0.x), bitsOf(std::strtof(texts[i].c_str(), nullptr))) << texts[i];
  }
  // The facet normal is the shading normal at every corner.
  EXPECT_EQ(ascii.normals.back().n0, glm::vec3(0, 0, 1));
  EXPECT_EQ(ascii.normals.back().n2, glm::vec3(0, 0, 1));

  // Binary: 80 bytes (here starting with "solid", as many do), the count, 50 bytes a triangle.
  std::string bin = "solid but binary" + std::string(64, ' ') + bytesOf(uint32_t(1), false);
  for (const float f : {0.0f, 0.0f, -1.0f, 0x1.59p-32f, 0x1p-149f, 3.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) {
    bin += bytesOf(f, false);
  }
  bin += std::string(2, '\0');
  const Scene binary = readStl(bin, "t.stl");
  ASSERT_EQ(binary.size(), 1u);
  EXPECT_EQ(binary.triangles[0].v0, glm::vec3(0x1.59p-32f, 0x1p-149f, 3.0f));
  EXPECT_EQ(binary.normals[0].n1, glm::vec3(0, 0, -1));
}

TEST(Stl, MalformedFilesNameTheFileAndWhere) {
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  for (const auto& [bytes, message] : std::vector<std::pair<std::string, std::string>>{
           {"", "t.stl: not an STL file: it does not start with 'solid' (ASCII), and a binary STL of 0 triangles would be 84 bytes, not 0"},
           {std::string(84, '\0') + "x", "t.stl: not an STL file: it does not start with 'solid' (ASCII), and a binary STL of 0 triangles would be 84 bytes, not 85"},
           {"solid a\nvertex 0 0 0\n", "t.stl:2: expected 'facet' or 'endsolid', found 'vertex'"},
           {"solid a\nfacet 0 0 1\n", "t.stl:2: expected 'facet normal nx ny nz'"},
           {"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 x\n", "t.stl:4: 'x' is not a number"},
           {"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1e39\n", "t.stl:4: vertex 0 0 1e39 is not a finite float"},
           {"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
            "t.stl:6: a facet of 2 vertices (STL facets are triangles)"},
           {"solid a\n" + facet.substr(0, facet.find("endloop")) + "vertex 1 1 0\n", "t.stl:7: a facet of more than 3 vertices (STL facets are triangles)"},
           {"solid a\n" + facet.substr(0, facet.find("endfacet")), "t.stl: the file ends inside a facet"},
           {"solid a\nendsolid a\n", "t.stl: scene has no triangles"},
           {std::string(80, ' ') + bytesOf(uint32_t(1), false) + std::string(12, '\0') + bytesOf(NAN, false) + std::string(34, '\0'),
            "t.stl: triangle 0: a vertex is not finite"},
       }) {
    EXPECT_EQ(stlError(bytes), message) << bytes;
  }
  const std::string nul = stlError("solid a\n" + facet + "\0"s);
  EXPECT_TRUE(nul.starts_with("t.stl:9: a NUL byte in an ASCII STL (a binary STL of")) << nul;
}

}  // namespace
}  // namespace lancer
