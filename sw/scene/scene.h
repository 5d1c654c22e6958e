#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/aabb.h"

namespace lancer {

// One triangle as the tracers store it. Vertices shared between triangles are
// bit-identical copies of the same loaded vertex, which is what makes the
// watertight test (and later the fixed-point quantization) agree on shared edges.
struct Triangle {
  glm::vec3 v0, v1, v2;

  Aabb bounds() const {
    Aabb b;
    b.extend(v0);
    b.extend(v1);
    b.extend(v2);
    return b;
  }
};

// A suggested viewpoint stored with a scene (the Cornell box has its classic one).
struct View {
  glm::vec3 eye{0.0f};
  glm::vec3 target{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDegrees = 40.0f;
};

struct Material {
  std::string name;
  glm::vec3 diffuse{0.8f};
  glm::vec3 emission{0.0f};
};

// A triangle scene. Triangle ids ("prim") are indices into `triangles`; their
// order is stable and documented in docs/scenes.md: meshes in the order assimp
// lists them after pre-transforming, faces in file order within each mesh.
struct Scene {
  std::string name;  // file path, or "builtin:<name>"
  std::vector<Triangle> triangles;
  std::vector<uint32_t> materialOf;  // one per triangle, index into materials
  std::vector<Material> materials;
  Aabb bounds;
  std::optional<View> view;  // used by the camera's auto-framing when present

  size_t size() const { return triangles.size(); }
  void computeBounds();
};

// Names accepted by loadScene() besides files.
inline constexpr const char* kDefaultSceneName = "builtin:cornell";

// Loads a file through assimp (OBJ/MTL, PLY, glTF 2.0, STL, ...) with node
// transforms applied and polygons triangulated, or a built-in scene by name.
// Throws InputError naming the file on any failure, including a scene with no triangles.
Scene loadScene(const std::string& nameOrPath);

// The embedded Cornell box: closed walls, two blocks, a ceiling light. Needs no file.
Scene makeCornellBox();

// Splits every triangle into four at its edge midpoints (shared midpoints are
// bit-identical, so the mesh stays watertight). Used to build large test meshes.
Scene subdivide(const Scene& scene, int times);

// Writes a Wavefront OBJ (positions and faces only), e.g. for generated scenes.
void writeObj(const Scene& scene, const std::filesystem::path& path);

}  // namespace lancer
