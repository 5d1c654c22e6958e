// Lancer's OBJ and MTL reader (sw/scene/obj.h): coordinates correctly rounded
// and exact under a power-of-two scale, every face form, triangulation, file
// order, materials as the assimp path read them, and an error naming the file
// and line for every malformed statement.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <fmt/format.h>

#include "common/error.h"
#include "scene/obj.h"
#include "text_cases.h"

namespace lancer {
namespace {

using namespace std::string_literals;  // "...\0..."s keeps the NUL

namespace fs = std::filesystem;

// A folder of this test's own (CTest runs the tests in parallel), emptied.
fs::path testFolder() {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("lancer_obj_{}", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Scene parse(const std::string& text) { return readObj(text, "t.obj", testFolder()); }

std::string errorOf(const std::string& text, const fs::path& folder = testFolder()) {
  try {
    readObj(text, "t.obj", folder);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string hex(float f) { return fmt::format("{:a}", f); }
uint32_t bitsOf(float f) { return std::bit_cast<uint32_t>(f); }

// Every vertex of the scene's triangles, in order.
std::vector<glm::vec3> cornersOf(const Scene& s) {
  std::vector<glm::vec3> out;
  for (const Triangle& t : s.triangles) out.insert(out.end(), {t.v0, t.v1, t.v2});
  return out;
}

// ---- Numbers ----------------------------------------------------------------------------

// Each decimal as x, y and z of a triangle's corners, against strtof.
TEST(Obj, CoordinatesAreStrtofBitForBit) {
  std::vector<std::string> texts = test::kExtremeDecimals;
  for (const test::Halfway& h : test::kHalfwayDecimals) texts.emplace_back(h.text);
  std::string obj;
  for (const std::string& t : texts) obj += fmt::format("v {} {} {}\n", t, t, t);
  for (size_t i = 0; i < texts.size(); ++i) obj += fmt::format("f {} {} {}\n", i + 1, i + 1, i + 1);
  const Scene scene = parse(obj);
  ASSERT_EQ(scene.size(), texts.size());
  for (size_t i = 0; i < texts.size(); ++i) {
    const float want = std::strtof(texts[i].c_str(), nullptr);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(bitsOf(scene.triangles[i].v0[axis]), bitsOf(want)) << texts[i] << " read as " << hex(scene.triangles[i].v0[axis]);
    }
  }
  EXPECT_EQ(hex(parse("v 3.1377567211166024e-10 0 0\nf 1 1 1\n").triangles[0].v0.x), "0x1.59p-32");
  for (const test::Halfway& h : test::kHalfwayDecimals) {
    EXPECT_EQ(hex(parse(fmt::format("v {} 0 0\nf 1 1 1\n", h.text)).triangles[0].v0.x), h.nearest) << h.text;
  }
}

// A scene exported at full precision (%.17g of doubles) and the same scene
// scaled by 2^k read as exactly 2^k times each other: every coordinate is the
// float nearest to its text, and so is its scaled copy's.
TEST(Obj, ScaledByAPowerOfTwoReadsAsExactlyThatMultiple) {
  std::mt19937_64 rng(60);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 300; ++i) {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a) p[a] = std::ldexp(double(rng() >> 11) * 0x1p-53 - 0.5, int(rng() % 20) - 10) + 1000.0 * (a == 0);
    points.push_back(p);
  }
  const auto objAt = [&](int k) {
    std::string obj;
    for (const glm::dvec3& p : points) {
      obj += fmt::format("v {:.17g} {:.17g} {:.17g}\n", std::ldexp(p.x, k), std::ldexp(p.y, k), std::ldexp(p.z, k));
    }
    for (size_t i = 0; i + 2 < points.size(); i += 3) obj += fmt::format("f {} {} {}\n", i + 1, i + 2, i + 3);
    return obj;
  };
  const std::vector<glm::vec3> base = cornersOf(parse(objAt(0)));
  for (const int k : {-60, -40, 40, 60}) {
    const std::vector<glm::vec3> scaled = cornersOf(parse(objAt(k)));
    ASSERT_EQ(scaled.size(), base.size());
    size_t exact = 0;
    for (size_t i = 0; i < base.size(); ++i) {
      for (int a = 0; a < 3; ++a) exact += bitsOf(scaled[i][a]) == bitsOf(std::ldexp(base[i][a], k));
    }
    EXPECT_EQ(exact, 3 * base.size()) << "scale 2^" << k;
  }
}

TEST(Obj, VertexBeyondFloatRangeIsAnError) {
  EXPECT_EQ(errorOf("v 0 0 0\nv 1e39 0 0\n"), "t.obj:2: vertex coordinate '1e39' is not a finite float");
  EXPECT_EQ(errorOf("v nan 0 0\n"), "t.obj:1: vertex coordinate 'nan' is not a finite float");
  // Below the range it reads as zero, as strtof.
  EXPECT_EQ(parse("v 1e-50 -1e-50 0\nf 1 1 1\n").triangles[0].v0, glm::vec3(0.0f));
}

// ---- Statements -------------------------------------------------------------------------

TEST(Obj, EveryFaceFormAndNegativeIndices) {
  const Scene scene = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f 1 2 3\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\n"
      "f -3 -2 -1\nf -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
      "v 5 5 5\nf -4 -1 2\n");  // relative to the vertices defined so far
  ASSERT_EQ(scene.size(), 7u);
  for (uint32_t t = 0; t < 6; ++t) {
    EXPECT_EQ(scene.triangles[t].v0, glm::vec3(0, 0, 0)) << t;
    EXPECT_EQ(scene.triangles[t].v1, glm::vec3(1, 0, 0)) << t;
    EXPECT_EQ(scene.triangles[t].v2, glm::vec3(0, 1, 0)) << t;
  }
  EXPECT_EQ(scene.triangles[6].v1, glm::vec3(5, 5, 5));
  EXPECT_EQ(scene.triangles[6].v2, glm::vec3(1, 0, 0));
}

// w and vertex colours after x y z are numbers, not coordinates; the other
// statements (groups, objects, smoothing, lines, points, free-form) add nothing.
TEST(Obj, ExtrasAndIgnoredStatements) {
  const Scene scene = parse(
      "# exported\no box\ng side\ns 1\nmg 1\n"
      "v 1 2 3 0.5\nv 4 5 6 1 0 0\nv 7 8 9 0.2 0.3 0.4 1\n"
      "vp 0.5\ncstype bezier\nl 1 2\np 3\nusemap none\n"
      "f 1 2 3 # a comment after the face\ns off\n");
  ASSERT_EQ(scene.size(), 1u);
  EXPECT_EQ(scene.triangles[0].v0, glm::vec3(1, 2, 3));  // w is not divided by (assimp did)
  EXPECT_EQ(scene.triangles[0].v2, glm::vec3(7, 8, 9));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(Obj, ContinuedLinesCrLfAndByteOrderMark) {
  const Scene scene = parse("\xEF\xBB\xBFv 1 \\\n 2 3\r\nv 4 5 6\r\nv 7 8 \\\r\n9\r\nf 1 \\\n2 \\\n3\r\nf 3 2 1");
  ASSERT_EQ(scene.size(), 2u);
  EXPECT_EQ(scene.triangles[0].v0, glm::vec3(1, 2, 3));
  EXPECT_EQ(scene.triangles[0].v2, glm::vec3(7, 8, 9));
  EXPECT_EQ(scene.triangles[1].v0, glm::vec3(7, 8, 9));  // the last line needs no line end
  // A message names the line a continued statement starts on.
  EXPECT_EQ(errorOf("v 1 2 3\nf 1 \\\n 1 \\\n 9\n"), "t.obj:2: face corner '9': vertex index 9 is out of range (1 before this line)");
}

// Triangles follow the faces in file order whatever their materials (assimp
// grouped them by material); a quad is two triangles, a larger polygon as many
// as ear clipping makes, concave or not, wound as written.
TEST(Obj, FileOrderAndPolygons) {
  const fs::path dir = testFolder();
  std::ofstream(dir / "m.mtl") << "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n";
  const Scene scene = readObj(
      "mtllib m.mtl\n"
      "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 1 1 0\nv 0 1 0\n"
      "usemtl b\nf 1 2 3\nusemtl a\nf 1 2 3 4\nusemtl b\nf 1 2 3\n"
      "f 1 2 3 5 4\n",  // a concave pentagon (a notch at vertex 5, on the diagonal 1-3): 2 triangles
      "t.obj", dir);
  ASSERT_EQ(scene.size(), 1u + 2u + 1u + 2u);
  const auto materialName = [&](uint32_t t) { return scene.materials[scene.materialOf[t]].name; };
  EXPECT_EQ(materialName(0), "b");
  EXPECT_EQ(materialName(1), "a");
  EXPECT_EQ(materialName(2), "a");
  EXPECT_EQ(materialName(3), "b");
  double pentagon = 0.0;
  for (uint32_t t = 4; t < 6; ++t) {
    const Triangle& tri = scene.triangles[t];
    const glm::vec3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    EXPECT_GT(n.z, 0.0f) << "triangle " << t << " keeps the polygon's winding";
    pentagon += 0.5 * n.z;
  }
  EXPECT_DOUBLE_EQ(pentagon, 3.0);  // the square (4) less the notch (1)
  // A twisted quad has no plane to clip ears in; it is split at corner 0.
  const Scene twisted = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\n");
  ASSERT_EQ(twisted.size(), 2u);
  EXPECT_EQ(twisted.triangles[1].v2, glm::vec3(0, 0, 1));
  // A concave quad is split from its concave corner, so both halves lie inside it.
  const Scene dart = parse("v 0 0 0\nv 2 1 0\nv 0 2 0\nv 1 1 0\nf 1 2 3 4\n");
  ASSERT_EQ(dart.size(), 2u);
  for (const Triangle& t : dart.triangles) EXPECT_GT(glm::cross(t.v1 - t.v0, t.v2 - t.v0).z, 0.0f);
}

// A polygon's triangles keep each corner's own vn, named relatively here
// (Scene.VertexNormalsAreShadingNormals has the rest: unit length, zero and
// missing normals, none at all).
TEST(Obj, PolygonCornersKeepTheirNormals) {
  const Scene scene = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvn 0 0 -1\n"
                            "f 1//-4 2//-3 3//-2 4//-1\n");
  ASSERT_EQ(scene.size(), 2u);
  ASSERT_EQ(scene.normals.size(), 2u);
  const auto normalAt = [&](const glm::vec3& p) {
    for (size_t t = 0; t < scene.size(); ++t) {
      const Triangle& tri = scene.triangles[t];
      const ShadingNormals& n = scene.normals[t];
      if (tri.v0 == p) return n.n0;
      if (tri.v1 == p) return n.n1;
      if (tri.v2 == p) return n.n2;
    }
    return glm::vec3(0.0f);
  };
  EXPECT_EQ(normalAt({0, 0, 0}), glm::vec3(1, 0, 0));
  EXPECT_EQ(normalAt({1, 0, 0}), glm::vec3(0, 1, 0));
  EXPECT_EQ(normalAt({1, 1, 0}), glm::vec3(0, 0, 1));
  EXPECT_EQ(normalAt({0, 1, 0}), glm::vec3(0, 0, -1));
}

// ---- Materials --------------------------------------------------------------------------

// The MTL files of tests/fuzz/corpus/mtl, behind the fuzz target's OBJ, read
// as the assimp path read them (its values, printed with %a).
TEST(Obj, CorpusMaterialsAsTheAssimpPathReadThem) {
  const fs::path corpus = fs::path(LANCER_TEST_DATA) / "../fuzz/corpus/mtl";
  const fs::path dir = testFolder();
  const auto load = [&](const std::string& mtl) {
    fs::copy_file(corpus / mtl, dir / mtl, fs::copy_options::overwrite_existing);
    return readObj(fmt::format("mtllib {}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl m\nf 1 2 3\nusemtl n\nf 1 3 4\n", mtl),
                   "t.obj", dir);
  };
  struct Terms {
    const char *kd, *ks, *shine, *t, *ior, *diffuse[3], *emission[3];
  };
  const auto expectTerms = [](const Material& m, const Terms& want) {
    SCOPED_TRACE(m.name);
    EXPECT_EQ(hex(m.kd), want.kd);
    EXPECT_EQ(hex(m.ks), want.ks);
    EXPECT_EQ(hex(m.shine), want.shine);
    EXPECT_EQ(hex(m.transmittance), want.t);
    EXPECT_EQ(hex(m.ior), want.ior);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(hex(m.diffuse[i]), want.diffuse[i]);
      EXPECT_EQ(hex(m.emission[i]), want.emission[i]);
    }
  };
  const Scene whitted = load("whitted.mtl");
  expectTerms(whitted.materials[whitted.materialOf[0]],
              {"0x1p+0", "0x1p-1", "0x1p+5", "0x0p+0", "0x1p+0", {"0x1.99999ap-1", "0x1.99999ap-3", "0x1.99999ap-3"}, {"0x0p+0", "0x0p+0", "0x0p+0"}});
  expectTerms(whitted.materials[whitted.materialOf[1]],
              {"0x1p+0", "0x0p+0", "0x0p+0", "0x1.8p-1", "0x1.8p+0", {"0x1.99999ap-4", "0x1.99999ap-4", "0x1.ccccccp-1"}, {"0x0p+0", "0x0p+0", "0x0p+0"}});
  const Scene emissive = load("emissive.mtl");
  expectTerms(emissive.materials[emissive.materialOf[0]],
              {"0x1p+0", "0x0p+0", "0x0p+0", "0x0p+0", "0x1p+0", {"0x0p+0", "0x0p+0", "0x0p+0"}, {"0x1.4p+3", "0x1.4p+3", "0x1p+3"}});
  expectTerms(emissive.materials[emissive.materialOf[1]],
              {"0x1p+0", "0x0p+0", "0x0p+0", "0x0p+0", "0x1p+0", {"0x1p-1", "0x1p-1", "0x1p-1"}, {"0x0p+0", "0x0p+0", "0x0p+0"}});
  // The files the assimp path refused, refused again, naming the MTL file and line.
  for (const auto& [mtl, message] :
       {std::pair{"bad_ior.mtl", "bad_ior.mtl:1: material 'm': index of refraction -1 must be > 0 on a transmitting material"},
        std::pair{"infinite_terms.mtl", "infinite_terms.mtl:1: material 'm': shininess (Ns) inf must be finite and >= 0"},
        std::pair{"negative_nan_ks.mtl", "negative_nan_ks.mtl:1: material 'm': specular weight (Ks) -5 must be finite and >= 0"},
        std::pair{"assimp_segv_statement_before_newmtl.mtl",
                  "assimp_segv_statement_before_newmtl.mtl:2: a statement before the first newmtl (no material to apply it to)"},
        std::pair{"assimp_segv_nul_bytes.mtl", "assimp_segv_nul_bytes.mtl:1: a NUL byte (not a text file; UTF-16 is not read)"}}) {
    try {
      load(mtl);
      ADD_FAILURE() << mtl << ": expected an error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  // A comment and nothing else (assimp leaked on it): no materials, so both
  // names take the default material, with a warning each.
  const Scene comment = load("assimp_leak_comment_no_newline.mtl");
  EXPECT_EQ(comment.warnings.size(), 2u);
}

// MTL's terms as Whitted terms: illum >= 3 reflects with Ks's largest
// component; d < 1 and Tr transmit (the last one written counts); Ns < 0 is 0;
// one number is a grey; Ni 0 on an opaque material is 1; Ka, Tf, maps and PBR
// statements change nothing.
TEST(Obj, MtlTermsAsWhittedTerms) {
  const std::vector<Material> m = readMtl(
      "# a file\nnewmtl mirror\nKd 0.1 0.2 0.3\nKs 0.5 0.9 0.7\nillum 3\nNs 50\n"
      "newmtl highlight\nKs 1 1 1\nillum 2\nNs -4\nNi 0\n"
      "NEWMTL glass\nkd 0.5\nd 0.25\nNi 1.5\nTr 0.5\nKa 1 1 1\nTf 1 1 1\nmap_Kd a b.png\nPr 0.5\n"
      "newmtl halo\nd -halo 0.5\nKe 1 2 3\nNi 1.2\n"
      "newmtl Material #25\nKd spectral wood.rfl\n",
      "t.mtl");
  ASSERT_EQ(m.size(), 5u);
  EXPECT_FLOAT_EQ(m[0].ks, 0.9f);
  EXPECT_EQ(m[0].diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(m[0].shine, 50.0f);
  EXPECT_FLOAT_EQ(m[1].ks, 0.0f);
  EXPECT_FLOAT_EQ(m[1].shine, 0.0f);
  EXPECT_FLOAT_EQ(m[1].ior, 1.0f);
  EXPECT_EQ(m[2].name, "glass");
  EXPECT_EQ(m[2].diffuse, glm::vec3(0.5f));
  EXPECT_FLOAT_EQ(m[2].transmittance, 0.5f);  // Tr 0.5 after d 0.25
  EXPECT_FLOAT_EQ(m[2].ior, 1.5f);
  EXPECT_FLOAT_EQ(m[3].transmittance, 0.5f);
  EXPECT_EQ(m[3].emission, glm::vec3(1, 2, 3));
  EXPECT_EQ(m[4].name, "Material #25");  // a name is the rest of the line
  EXPECT_EQ(m[4].diffuse, Material{}.diffuse);  // no Kd Lancer reads: the default grey
}

TEST(Obj, MaterialLibraries) {
  const fs::path dir = testFolder();
  fs::create_directories(dir / "mat");
  std::ofstream(dir / "mat" / "a.mtl") << "newmtl a\nKd 1 0 0\n";
  std::ofstream(dir / "mat" / "b c.mtl") << "newmtl b\nKd 0 1 0\n";
  std::ofstream(dir / "d.mtl") << "newmtl d\nKd 0 0 1\nnewmtl a\nKs 1 1 1\nillum 3\n";
  const std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nusemtl d\nf 1 2 3\n";
  // Several files on one line, relative to the OBJ's folder; a name with a blank
  // when the whole line is one file. A material named again goes on with it.
  const Scene scene = readObj("mtllib mat/a.mtl d.mtl\nmtllib mat/b c.mtl\n" + faces, (dir / "s.obj").string(), dir);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  const auto material = [&](const Scene& s, uint32_t t) { return s.materials[s.materialOf[t]]; };
  EXPECT_EQ(material(scene, 0).diffuse, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(material(scene, 0).ks, 1.0f);
  EXPECT_EQ(material(scene, 1).diffuse, glm::vec3(0, 1, 0));
  EXPECT_EQ(material(scene, 2).diffuse, glm::vec3(0, 0, 1));
  // A missing MTL file: a warning, and the OBJ's own name with .mtl if there is one (as assimp).
  std::ofstream(dir / "s.mtl") << "newmtl a\nKd 0.5 0.5 0.5\n";
  const Scene fallback = readObj("mtllib gone.mtl\n" + faces, (dir / "s.obj").string(), dir);
  ASSERT_EQ(fallback.warnings.size(), 3u);  // the file, then b and d
  EXPECT_EQ(fallback.warnings[0], fmt::format("{}:1: MTL file {} not found: read {} instead", (dir / "s.obj").string(),
                                              (dir / "gone.mtl").string(), (dir / "s.mtl").string()));
  EXPECT_EQ(material(fallback, 0).diffuse, glm::vec3(0.5f));
  EXPECT_EQ(fallback.warnings[1], fmt::format("{}:7: usemtl 'b': no MTL file defines it: drawn with the default material",
                                              (dir / "s.obj").string()));
  EXPECT_EQ(material(fallback, 1).name, "b");
  EXPECT_EQ(material(fallback, 1).diffuse, Material{}.diffuse);
  fs::remove(dir / "s.mtl");
  const Scene none = readObj("mtllib gone.mtl\n" + faces, (dir / "s.obj").string(), dir);
  EXPECT_NE(none.warnings[0].find("gone.mtl not found: its materials are drawn with the default material"), std::string::npos);
  // No usemtl: the default material, named so, without a warning.
  const Scene plain = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(plain.materials.at(plain.materialOf[0]).name, "default");
  EXPECT_TRUE(plain.warnings.empty());
}

// ---- Errors -----------------------------------------------------------------------------

TEST(Obj, MalformedStatementsNameTheFileAndLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"v 1 x 3\n", "t.obj:1: 'x' is not a number"},
           {"v 1 2\n", "t.obj:1: a vertex takes 3 coordinates, this line has 2"},
           {"v 1 2 3 1.5.2\n", "t.obj:1: '1.5.2' is not a number"},
           {tri + "vn 0 1\n", "t.obj:4: a normal takes 3 numbers, this line has 2"},
           {tri + "vn 0 1 z\n", "t.obj:4: 'z' is not a number"},
           {tri + "f 1 2 0\n", "t.obj:4: face corner '0': vertex index 0 (OBJ counts from 1)"},
           {tri + "f 1 2 4\n", "t.obj:4: face corner '4': vertex index 4 is out of range (3 before this line)"},
           {tri + "f 1 2 -4\n", "t.obj:4: face corner '-4': vertex index -4 is out of range (3 before this line)"},
           {"f 1 2 3\n" + tri, "t.obj:1: face corner '1': vertex index 1 is out of range (0 before this line)"},
           {tri + "f 1/1 2 3\n", "t.obj:4: face corner '1/1': texture coordinate index 1 is out of range (0 before this line)"},
           {tri + "f 1//2 2 3\n", "t.obj:4: face corner '1//2': normal index 2 is out of range (0 before this line)"},
           {tri + "f 1/x 2 3\n", "t.obj:4: face corner '1/x': 'x' is not an index"},
           {tri + "f 1.5 2 3\n", "t.obj:4: face corner '1.5': '1.5' is not an index"},
           {tri + "f 1/1/1/1 2 3\n", "t.obj:4: face corner '1/1/1/1' has more than v/vt/vn"},
           {tri + "f 1 2\n", "t.obj:4: a face needs at least 3 vertices, this one has 2"},
           {tri + "f\n", "t.obj:4: a face needs at least 3 vertices, this one has 0"},
           {tri + "v 1 1 0\nv 0 0 1\n" + "f 1 2 4 3 5\n", "no error"},  // a non-planar pentagon clips fine
           {"v 3 0 0\nv 3 1 0\nv 1 3 0\nv 1 1 0\nv 2 4 0\nf 1 2 3 4 5\n",  // two loops, no ear to clip
            "t.obj:6: face of 5 vertices cannot be triangulated (it crosses itself)"},
           {tri + "f 1 2 3\n\nv 0 0\0 0\n"s, "t.obj:6: a NUL byte (not a text file; UTF-16 is not read)"},
           {"", "t.obj: scene has no triangles"},
           {"# nothing\n", "t.obj: scene has no triangles"},
           {tri + "l 1 2\np 3\n", "t.obj: scene has no triangles"},
       }) {
    EXPECT_EQ(errorOf(text), message) << text;
  }
  // A polygon with no area adds no triangles (a ray could not hit them).
  EXPECT_EQ(errorOf(tri + "v 2 0 0\nv 3 0 0\nf 1 2 4 5 1\n"), "t.obj: scene has no triangles");
}

TEST(Obj, MalformedMtlNamesTheFileAndLine) {
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"Kd 1 1 1\nnewmtl m\n", "t.mtl:1: a statement before the first newmtl (no material to apply it to)"},
           {"newmtl m\nKd 1 1\n", "t.mtl:2: Kd takes 1 or 3 numbers, this line has 2"},
           {"newmtl m\nNs\n", "t.mtl:2: Ns takes one number, this line has 0"},
           {"newmtl m\nNi one\n", "t.mtl:2: 'one' is not a number"},
           {"newmtl m\nillum 2.5\n", "t.mtl:2: illum takes one whole number, got '2.5'"},
           {"newmtl m\nKs nan 0 0\nillum 3\n", "t.mtl:1: material 'm': specular weight (Ks) nan must be finite and >= 0"},
           {"newmtl m\nKd inf 0 0\n", "t.mtl:1: material 'm': diffuse colour (Kd) (inf, 0, 0) is not finite"},
           {"newmtl m\nKe 1e39 1 1\n", "t.mtl:1: material 'm': emission (Ke) (inf, 1, 1) is not finite"},
           {"newmtl m\nd nan\n", "t.mtl:1: material 'm': transmittance (1 - d) nan must be finite and >= 0"},
           {"newmtl m\nd 0.5\nNi 0\n", "t.mtl:1: material 'm': index of refraction 0 must be > 0 on a transmitting material"},
           {"newmtl m\n\0"s, "t.mtl:2: a NUL byte (not a text file; UTF-16 is not read)"},
       }) {
    try {
      readMtl(text, "t.mtl");
      ADD_FAILURE() << text << ": expected an error";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), message) << text;
    }
  }
}

}  // namespace
}  // namespace lancer
