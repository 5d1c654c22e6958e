// Lancer's readers against an independent one: assimp, on every scene of
// Debian's assimp-testmodels that both read. The glTF reader places assimp's
// meshes at nodes it walks itself, so its placement is checked against
// assimp's own (aiProcess_PreTransformVertices); Lancer's OBJ, PLY and STL
// readers are checked against assimp's reading of the same file. A triangle
// is three vertices in order (a rotation of the order is the same triangle,
// its mirror image is not: the winding is kept); the two scenes must hold the
// same triangles as multisets, within a named tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <ostream>
#include <string_view>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/assimp_scene.h"
#include "scene/scene.h"
#include "scene/text.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

using test::kAssimpModels;

// glTF: Lancer and assimp each compose a node's world transform in float and
// apply it to the buffer's floats, by different formulas (quaternion to
// matrix, the order of the products); one float transform of a point x gives
// x' = sum_j m_ij x_j + t_i with a rounding error of a few units in the last
// place of the largest term. Both sides' errors are bounded by this many
// float epsilons of the scene's largest coordinate (measured: the largest
// difference over the corpus is below 2 of them).
constexpr float kOneTransformRounding = 8.0f;

// OBJ, PLY, STL: Lancer's numbers are correctly rounded, assimp's fast_atof
// can be one unit in the last place off (docs/scenes.md, "Numbers"); binary
// numbers are the same floats on both sides.
constexpr int kReaderUlps = 1;

// A polygon of more than four corners has many triangulations, and both
// readers clip ears in their own order; Lancer drops the zero-area triangles
// of collinear or repeated corners that assimp keeps (docs/scenes.md, "OBJ
// and MTL"). Triangles that find no match are checked as one surface: the
// same corners, and the same vector area (the sum of the triangles' cross
// products, which every triangulation of an outline shares), within this
// fraction of the sum of their areas.
constexpr double kAreaAgreement = 1e-5;

// Files where Lancer differs from assimp's aiProcess_PreTransformVertices
// reading, each with its reason.
enum class Reference : uint8_t {
  Refused,     // Lancer refuses the file on purpose (it must, naming the file)
  PreTransform,  // compared with a tolerance of its own
  NodeWalk,    // compared with assimp's nodes' transforms applied here, not by PreTransformVertices
};
struct KnownDifference {
  std::string_view path;  // relative to the models' folder
  std::string_view reason;
  Reference reference;
  float transformRounding = kOneTransformRounding;  // the placement tolerance for the file
};
constexpr std::array<KnownDifference, 8> kKnownDifferences{{
    {"OBJ/number_formats.obj", "'3.1+e2' is not a number; assimp's fast_atof reads its prefix 3.1", Reference::Refused},
    {"invalid/malformed2.obj", "a face of no vertices; assimp skips it", Reference::Refused},
    {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "its vertices are infinite; assimp keeps them",
     Reference::Refused},
    {"ASE/ThreeCubesGreen_UTF16BE.ASE", "assimp reads UTF-16 as triangles that are all points", Reference::Refused},
    {"ASE/ThreeCubesGreen_UTF16LE.ASE", "assimp reads UTF-16 as triangles that are all points", Reference::Refused},
    {"OFF/invalid.off", "assimp reads two triangles that are both one point", Reference::Refused},
    // The node's rotation (-0.383, 0, 0, 0.92375) has |q|^2 = 1 + 3.1e-6: Lancer
    // normalises it (glTF requires a unit quaternion), assimp uses it as it is,
    // which scales the points by up to that much: about 26 float epsilons.
    {"glTF2/cameras/Cameras.gltf", "a rotation that is not a unit quaternion, which Lancer normalises",
     Reference::PreTransform, 32.0f},
    // 20 of its meshes are each placed by two nodes; PreTransformVertices puts 81
    // triangles where neither node's transform does, and assimp's own node
    // transforms, applied here, agree with Lancer.
    {"IFC/AC14-FZK-Haus.ifc", "assimp 5.2's PreTransformVertices misplaces 81 triangles of shared meshes",
     Reference::NodeWalk},
}};

const KnownDifference* knownDifference(const std::string& relative) {
  for (const KnownDifference& known : kKnownDifferences) {
    if (known.path == relative) return &known;
  }
  return nullptr;
}

struct Reading {
  std::vector<Triangle> triangles;
  Aabb bounds;
};

void addTriangles(const aiMesh& mesh, const aiMatrix4x4& transform, Reading& out) {
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines are not traced
    const auto vertex = [&](int k) {
      const aiVector3D v = transform * mesh.mVertices[face.mIndices[k]];
      return glm::vec3(v.x, v.y, v.z);
    };
    out.triangles.push_back({vertex(0), vertex(1), vertex(2)});
    out.bounds.extend(out.triangles.back().bounds());
  }
}

// Every node's meshes at the node's world transform, by assimp's own matrices.
void walkNodes(const aiScene& ai, const aiNode& node, const aiMatrix4x4& parent, Reading& out) {
  const aiMatrix4x4 world = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) addTriangles(*ai.mMeshes[node.mMeshes[k]], world, out);
  for (unsigned c = 0; c < node.mNumChildren; ++c) walkNodes(ai, *node.mChildren[c], world, out);
}

// assimp's reading of a file, with every node's transform applied (by
// aiProcess_PreTransformVertices, or `byNodeWalk` here) and every polygon
// triangulated; nullopt when assimp does not read the file.
std::optional<Reading> assimpReading(const std::string& path, bool byNodeWalk, std::string& error) {
  Assimp::Importer importer;
  const aiScene* ai =
      importer.ReadFile(path, aiProcess_Triangulate | (byNodeWalk ? 0u : unsigned(aiProcess_PreTransformVertices)));
  if (!ai || !ai->mRootNode) {
    error = importer.GetErrorString();
    return std::nullopt;
  }
  Reading out;
  if (byNodeWalk) {
    walkNodes(*ai, *ai->mRootNode, aiMatrix4x4(), out);
  } else {
    for (unsigned m = 0; m < ai->mNumMeshes; ++m) addTriangles(*ai->mMeshes[m], aiMatrix4x4(), out);
  }
  return out;
}

float largestCoordinate(const Aabb& bounds) {
  return std::max({std::abs(bounds.lo.x), std::abs(bounds.lo.y), std::abs(bounds.lo.z), std::abs(bounds.hi.x),
                   std::abs(bounds.hi.y), std::abs(bounds.hi.z)});
}

// How two coordinates may differ, and the most they can differ by in a scene
// whose coordinates are at most `scale` (for the spatial hash's cells).
struct Tolerance {
  std::function<bool(float, float)> agree;
  float largest = 0.0f;
};

Tolerance transformTolerance(float scale, float epsilons) {
  const float allowed = epsilons * std::numeric_limits<float>::epsilon() * scale;
  return {[allowed](float a, float b) { return std::abs(a - b) <= allowed; }, allowed};
}

Tolerance readerTolerance(float scale) {
  return {[](float a, float b) {
            for (int k = 0; k < kReaderUlps && a != b; ++k) a = std::nextafter(a, b);
            return a == b;
          },
          kReaderUlps * (std::nextafter(scale, std::numeric_limits<float>::infinity()) - scale)};
}

bool agree(const Triangle& a, const Triangle& b, const Tolerance& tolerance) {
  const auto close = [&](const glm::vec3& p, const glm::vec3& q) {
    return tolerance.agree(p.x, q.x) && tolerance.agree(p.y, q.y) && tolerance.agree(p.z, q.z);
  };
  // The same corners in the same cyclic order.
  return (close(a.v0, b.v0) && close(a.v1, b.v1) && close(a.v2, b.v2)) ||
         (close(a.v0, b.v1) && close(a.v1, b.v2) && close(a.v2, b.v0)) ||
         (close(a.v0, b.v2) && close(a.v1, b.v0) && close(a.v2, b.v1));
}

std::string show(const Triangle& t) {
  return fmt::format("({:.9g} {:.9g} {:.9g}) ({:.9g} {:.9g} {:.9g}) ({:.9g} {:.9g} {:.9g})", t.v0.x, t.v0.y, t.v0.z,
                     t.v1.x, t.v1.y, t.v1.z, t.v2.x, t.v2.y, t.v2.z);
}

// Matches every triangle of `ours` to one of `theirs` that agrees with it,
// each used once.
struct Matching {
  std::vector<Triangle> oursLeft, theirsLeft;  // the triangles that found no match
};
Matching match(const std::vector<Triangle>& ours, const std::vector<Triangle>& theirs, const Tolerance& tolerance) {
  // Theirs hashed by the cell of their lowest corner (sorted, so a rotation
  // of the corners hashes alike); a match lies in a neighbouring cell.
  const float cell = std::max(4.0f * tolerance.largest, std::numeric_limits<float>::min());
  const auto key = [&](const Triangle& t) {
    const glm::vec3 lo = glm::min(t.v0, glm::min(t.v1, t.v2));
    return glm::ivec3(glm::floor(lo / cell));
  };
  const auto hash = [](const glm::ivec3& k) {
    return (int64_t(k.x) * 73856093) ^ (int64_t(k.y) * 19349663) ^ (int64_t(k.z) * 83492791);
  };
  std::unordered_multimap<int64_t, size_t> cells;
  for (size_t i = 0; i < theirs.size(); ++i) cells.emplace(hash(key(theirs[i])), i);
  std::vector<bool> used(theirs.size(), false);
  Matching out;
  for (const Triangle& t : ours) {
    const glm::ivec3 k = key(t);
    std::optional<size_t> found;
    for (int dx = -1; dx <= 1 && !found; ++dx) {
      for (int dy = -1; dy <= 1 && !found; ++dy) {
        for (int dz = -1; dz <= 1 && !found; ++dz) {
          const auto [begin, end] = cells.equal_range(hash(k + glm::ivec3(dx, dy, dz)));
          for (auto it = begin; it != end && !found; ++it) {
            if (!used[it->second] && agree(t, theirs[it->second], tolerance)) found = it->second;
          }
        }
      }
    }
    if (found) {
      used[*found] = true;
    } else {
      out.oursLeft.push_back(t);
    }
  }
  for (size_t i = 0; i < theirs.size(); ++i) {
    if (!used[i]) out.theirsLeft.push_back(theirs[i]);
  }
  return out;
}

// How far the nearest of `theirs` is from `t`: the largest coordinate
// difference, over the rotations of its corners (for a failure's message).
float nearest(const Triangle& t, const std::vector<Triangle>& theirs) {
  float best = std::numeric_limits<float>::infinity();
  for (const Triangle& u : theirs) {
    for (const Triangle& r : {u, Triangle{u.v1, u.v2, u.v0}, Triangle{u.v2, u.v0, u.v1}}) {
      const glm::vec3 d = glm::max(glm::abs(t.v0 - r.v0), glm::max(glm::abs(t.v1 - r.v1), glm::abs(t.v2 - r.v2)));
      best = std::min(best, std::max({d.x, d.y, d.z}));
    }
  }
  return best;
}

glm::dvec3 vectorArea(const Triangle& t) {
  return glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0));
}

// Whether the triangles left over on both sides are the same surface cut
// differently (kAreaAgreement); `why` says how not.
bool sameSurface(const Matching& left, const Tolerance& tolerance, std::string& why) {
  glm::dvec3 ours(0.0), theirs(0.0);
  double size = 0.0;
  std::vector<glm::vec3> corners;
  for (const Triangle& t : left.theirsLeft) {
    theirs += vectorArea(t);
    size += glm::length(vectorArea(t));
    corners.insert(corners.end(), {t.v0, t.v1, t.v2});
  }
  for (const Triangle& t : left.oursLeft) {
    ours += vectorArea(t);
    size += glm::length(vectorArea(t));
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      const bool known = std::any_of(corners.begin(), corners.end(), [&](const glm::vec3& c) {
        return tolerance.agree(v.x, c.x) && tolerance.agree(v.y, c.y) && tolerance.agree(v.z, c.z);
      });
      if (!known) {
        why = fmt::format("triangle {} has a corner none of assimp's unmatched triangles has", show(t));
        return false;
      }
    }
  }
  if (glm::length(ours - theirs) > kAreaAgreement * size) {
    why = fmt::format("their vector areas differ: ({} {} {}) against assimp's ({} {} {})", ours.x, ours.y, ours.z,
                      theirs.x, theirs.y, theirs.z);
    return false;
  }
  return true;
}

enum class Check { Placement, Reader };

struct CorpusFile {
  std::string path;  // relative to the models' folder
  Check check;
};

// Files assimp's own reading (the reference) cannot take: assimp 5.2's
// aiProcess_PreTransformVertices fails an assertion on two OpenGEX cameras
// without a node and crashes on RAW's node, which counts children it never
// makes; OutOfMemory.off claims trillions of vertices, and assimp would try to
// hold them (Lancer caps its address space). tests/corpus/check_corpus.py
// runs Lancer on them all the same.
constexpr std::array<std::string_view, 5> kNoReference{
    "OpenGEX/camera.ogex", "OpenGEX/collada.ogex", "RAW/WithColor.raw", "RAW/WithTexture.raw", "invalid/OutOfMemory.off"};

// Every glTF 2.0 (.gltf, .glb), every file of the other formats assimp
// imports (placed by Lancer's walk of assimp's nodes: loadAssimpScene), and
// every OBJ, PLY and STL of the corpus, but kNoReference.
std::vector<CorpusFile> corpusFiles() {
  std::vector<CorpusFile> out;
  if (!std::filesystem::is_directory(kAssimpModels)) return out;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kAssimpModels)) {
    if (!entry.is_regular_file()) continue;
    const std::string extension = lowercase(entry.path().extension().string());
    const std::string relative = std::filesystem::relative(entry.path(), kAssimpModels).string();
    if (std::find(kNoReference.begin(), kNoReference.end(), relative) != kNoReference.end()) continue;
    if ((extension == ".gltf" || extension == ".glb") && relative.starts_with("glTF2/")) {
      out.push_back({relative, Check::Placement});
    } else if (extension == ".obj" || extension == ".ply" || extension == ".stl") {
      out.push_back({relative, Check::Reader});
    } else if (extension != ".nff" && !extension.empty() &&
               assimpSceneNumbers(entry.path().string())) {
      out.push_back({relative, Check::Placement});
    }
  }
  std::sort(out.begin(), out.end(), [](const CorpusFile& a, const CorpusFile& b) { return a.path < b.path; });
  return out;
}

class AssimpCorpus : public testing::TestWithParam<CorpusFile> {};

TEST_P(AssimpCorpus, LancerReadsTheTrianglesAssimpReads) {
  const std::string path = kAssimpModels + "/" + GetParam().path;
  const KnownDifference* known = knownDifference(GetParam().path);
  std::string assimpError;
  const std::optional<Reading> theirs =
      assimpReading(path, known && known->reference == Reference::NodeWalk, assimpError);
  if (!theirs || theirs->triangles.empty() || (known && known->reference == Reference::Refused)) {
    // Not a scene assimp reads, or one Lancer refuses on purpose: Lancer must
    // refuse it, with a message naming the file.
    try {
      const Scene ours = loadScene(path);
      ADD_FAILURE() << path << ": assimp reads " << (theirs ? theirs->triangles.size() : 0) << " triangles ("
                    << (known ? known->reason : assimpError) << "), Lancer reads " << ours.size();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    return;
  }
  Scene ours;
  try {
    ours = loadScene(path);
  } catch (const InputError& e) {
    FAIL() << "assimp reads " << theirs->triangles.size() << " triangles, Lancer refuses it: " << e.what();
  }
  const float scale = std::max(largestCoordinate(ours.bounds), largestCoordinate(theirs->bounds));
  const bool placement = GetParam().check == Check::Placement;
  const Tolerance tolerance =
      placement ? transformTolerance(scale, known ? known->transformRounding : kOneTransformRounding)
                : readerTolerance(scale);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_TRUE(tolerance.agree(ours.bounds.lo[axis], theirs->bounds.lo[axis]))
        << path << ": lower bound on axis " << axis << ": " << ours.bounds.lo[axis] << " against " << theirs->bounds.lo[axis];
    EXPECT_TRUE(tolerance.agree(ours.bounds.hi[axis], theirs->bounds.hi[axis]))
        << path << ": upper bound on axis " << axis << ": " << ours.bounds.hi[axis] << " against " << theirs->bounds.hi[axis];
  }
  const Matching left = match(ours.triangles, theirs->triangles, tolerance);
  if (placement) {
    // glTF's primitives are triangles already: every one matches.
    EXPECT_EQ(ours.size(), theirs->triangles.size()) << path << ": triangle count, Lancer against assimp";
    EXPECT_TRUE(left.oursLeft.empty()) << path << ": " << left.oursLeft.size() << " of Lancer's " << ours.size()
                                       << " triangles are not among assimp's, e.g. " << show(left.oursLeft.front())
                                       << ", whose nearest is " << nearest(left.oursLeft.front(), left.theirsLeft) /
                                              (std::numeric_limits<float>::epsilon() * scale)
                                       << " float epsilons of the scene's largest coordinate " << scale << " away";
    return;
  }
  std::string why;
  EXPECT_TRUE(sameSurface(left, tolerance, why))
      << path << ": " << left.oursLeft.size() << " of Lancer's " << ours.size() << " triangles and "
      << left.theirsLeft.size() << " of assimp's " << theirs->triangles.size() << " match none: " << why;
}

std::string testName(const testing::TestParamInfo<CorpusFile>& info) {
  std::string name = info.param.path;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

// gtest's name for a test's parameter.
void PrintTo(const CorpusFile& file, std::ostream* out) { *out << file.path; }

INSTANTIATE_TEST_SUITE_P(Models, AssimpCorpus, testing::ValuesIn(corpusFiles()), testName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AssimpCorpus);

// The file that showed the bug: its default scene (roots 81 and 0, 82 nodes
// each visited once) has 121,496 triangles; Lancer read 499,131 when it took
// assimp's meshes in the file's order.
TEST(AssimpCorpusFigures, TwoCylinderEngineReadsItsDefaultScene) {
  const Scene scene = loadScene(kAssimpModels + "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  EXPECT_EQ(scene.size(), 121496u);
}

}  // namespace
}  // namespace lancer
