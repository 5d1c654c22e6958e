#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "common/aabb.h"

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

// A native quadric (issue #40, docs/quadrics.md): an NFF sphere ("s") or cone
// ("c": a truncated cone open at both ends, a cylinder when the radii are
// equal). The numbers are kept as read: a negative radius is NFF's "only the
// inside visible" (a sphere's; a cone's when a radius is negative), and the
// geometry is that of |radius|. Storage only: the tests are in
// sw/ref/quadric.h (float reference) and sw/oracle/exact.h (exact).
struct Quadric {
  enum class Kind : uint8_t { Sphere, Cone };
  Kind kind = Kind::Sphere;
  glm::vec3 base{0.0f};     // the sphere's center; the cone's base center
  float baseRadius = 1.0f;  // the sphere's radius; the cone's at its base
  glm::vec3 apex{0.0f};     // cone only: the apex center
  float apexRadius = 0.0f;  // cone only: the radius at the apex

  static Quadric sphere(const glm::vec3& center, float radius) { return {Kind::Sphere, center, radius, {}, 0.0f}; }
  static Quadric cone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius) {
    return {Kind::Cone, base, baseRadius, apex, apexRadius};
  }
  const glm::vec3& center() const { return base; }  // sphere
  float radius() const { return baseRadius; }        // sphere
  // NFF's negative radius: the inside is the visible side.
  bool insideVisible() const { return baseRadius < 0.0f || (kind == Kind::Cone && apexRadius < 0.0f); }
  // A box holding the surface, rounded outwards to floats: a sphere's is
  // center +- |r|; a cone's holds its two end disks (radius r around the
  // axis point spans r sqrt(1 - w_i^2 / |w|^2) on axis i). Infinite where the
  // surface reaches beyond float range.
  Aabb bounds() const;
};

// How a reader gives NFF's spheres and cones (issue #40): as triangles (the
// default while the hardware's traversal units take triangles only) or as
// native quadrics (Scene::quadrics).
enum class QuadricForm : uint8_t {
  Tessellate,  // triangles: every structure and model takes them
  Native,      // Scene::quadrics: the float side, the exact arbiter, --accel isect
};
const char* toString(QuadricForm form);

// A suggested viewpoint stored with a scene (the Cornell box has its classic one).
struct View {
  glm::vec3 eye{0.0f};
  glm::vec3 target{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDegrees = 40.0f;
  // The scene's own image size, when it names one (NFF "resolution"); 0 = none.
  int width = 0, height = 0;
};

// Per-vertex shading normals of one triangle (NFF "pp", tessellated spheres
// and cones), in the order of its vertices.
struct ShadingNormals {
  glm::vec3 n0, n1, n2;
};

// A surface's colour and its Whitted shading terms (NFF's "f" line, MTL's
// Kd/Ks/Ns/d/Ni). Defaults: a diffuse grey that neither reflects nor transmits.
struct Material {
  std::string name;
  glm::vec3 diffuse{0.8f};     // colour (NFF: the fill colour; the diffuse term is kd * diffuse)
  glm::vec3 emission{0.0f};    // non-zero: an area light
  float kd = 1.0f;             // diffuse weight
  float ks = 0.0f;             // specular weight: > 0 spawns reflection rays
  float shine = 0.0f;          // Phong exponent of the highlight
  float transmittance = 0.0f;  // T: > 0 spawns refraction rays (two-sided)
  float ior = 1.0f;            // index of refraction, > 0
};

// A light that casts shadows. NFF's lights are points with an optional colour;
// glTF's KHR_lights_punctual adds spot and directional lights. Area lights are
// not listed here: they are the triangles whose material has an emission.
struct Light {
  enum class Kind : uint8_t { Point, Spot, Directional };
  Kind kind = Kind::Point;
  glm::vec3 position{0.0f};                   // point and spot
  glm::vec3 direction{0.0f, 0.0f, -1.0f};     // spot and directional: where the light travels (unit)
  glm::vec3 color{1.0f};                      // colour times intensity
  float innerConeCos = 1.0f, outerConeCos = 0.0f;  // spot: full inside inner, none outside outer
  std::string name;                           // for the effects plan and errors
};

// How a scene's numbers were read (docs/scenes.md, "Numbers"): the report's
// `scene_numbers`. The stability suite's invariance promise holds for the
// first two; an assimp_text scene's numbers may each be a float off the
// file's decimals.
enum class SceneNumbers : uint8_t {
  Exact,             // binary floats as the file stores them (or a float transform of them)
  CorrectlyRounded,  // decimals read by Lancer's own readers, each the float nearest its text
  AssimpText,        // decimals parsed by assimp: maybe a float off
};
// "exact", "correctly_rounded", "assimp_text".
const char* toString(SceneNumbers numbers);

// A scene of triangles and (issue #40) native quadrics, in one id space:
// primitive ids ("prim") 0 .. T-1 are the triangles, in the order of
// `triangles`, and T + i is quadrics[i] (T = triangles.size()). The triangles'
// order is stable and documented in docs/scenes.md: faces in file order (OBJ,
// PLY, STL, NFF), a polygon's triangles in its ear-clipping order; glTF's
// meshes in the order of their nodes. Quadrics come only from the NFF reader
// with QuadricForm::Native, in file order; the quantizer and the writers do
// not take them yet and refuse such a scene (requireTrianglesOnly); the float
// reference's quadric test and structures, the effects' float tracer, the
// exact arbiter and Embree do.
struct Scene {
  std::string name;  // file path, or "builtin:<name>"
  std::vector<Triangle> triangles;
  std::vector<Quadric> quadrics;     // ids triangles.size() + i
  std::vector<uint32_t> materialOf;  // one per primitive (triangles, then quadrics), index into materials
  std::vector<Material> materials;
  Aabb bounds;
  std::optional<View> view;  // used by the camera's auto-framing when present
  std::vector<Light> lights;
  glm::vec3 background{0.0f};
  // Empty, or one per triangle (a triangle without its own normals holds its
  // geometric normal three times).
  std::vector<ShadingNormals> normals;
  // What the loader went on past, one line each naming the file (and line): an
  // OBJ's missing MTL file, a material no MTL file defines. The CLI prints them.
  std::vector<std::string> warnings;
  // How its numbers were read; built-in scenes are C++ literals, correctly
  // rounded by the compiler.
  SceneNumbers numbers = SceneNumbers::CorrectlyRounded;

  size_t size() const { return triangles.size(); }  // the triangles (the ids below the quadrics')
  size_t primitiveCount() const { return triangles.size() + quadrics.size(); }
  // Its primitives by kind, for reports: {triangles, spheres, cones}.
  struct PrimitiveCounts {
    size_t triangles = 0, spheres = 0, cones = 0;
  };
  PrimitiveCounts primitivesByKind() const;
  // "N triangles", with ", N spheres, N cones" where there are any.
  std::string primitivesText() const;
  bool isQuadric(uint32_t prim) const { return prim >= triangles.size(); }
  // The quadric of id `prim` (isQuadric(prim), prim < primitiveCount()).
  const Quadric& quadricOf(uint32_t prim) const { return quadrics[prim - triangles.size()]; }
  // Throws InputError ("<who>: <scene> has N quadrics: quadrics not supported
  // yet ...") when the scene has quadrics: the entry points that would
  // otherwise drop them (the quantizer, the writers) call it.
  void requireTrianglesOnly(std::string_view who) const;
  // The box of every triangle and quadric.
  void computeBounds();
  // The area lights: ids of the triangles whose material's emission has a
  // positive component, in id order (the Cornell box's lamp, glTF/MTL emissive
  // materials). Empty when the scene has none.
  std::vector<uint32_t> emissiveTriangles() const;
};

// Names accepted by loadScene() besides files.
inline constexpr const char* kDefaultSceneName = "builtin:cornell";
// What loadScene() reads, for messages and help.
inline constexpr const char* kSceneFormats =
    "OBJ (.obj, with its .mtl), PLY (.ply), STL (.stl), glTF 2.0 (.gltf, .glb), NFF (.nff), every other format "
    "assimp 5.2 imports (.blend, .fbx, .dae, .3ds, .ifc, ...), or builtin:cornell, builtin:cube, builtin:spd-tetra, "
    "builtin:spd-gears (builtin:spd-NAME@N: the SPD's size factor N)";

// Loads a scene file by its extension (kSceneFormats; docs/scenes.md): OBJ,
// PLY, STL and NFF by Lancer's own readers with correctly rounded numbers,
// glTF 2.0 by assimp's buffers at nodes Lancer places, every other format
// assimp imports through assimp (Scene::numbers says which numbers may be a
// float off, and a text format adds a warning), or a built-in scene by name.
// Throws InputError naming the file (and line) on any failure, including an
// extension nothing reads, assimp's own reason, and a scene with no triangles.
// `quadrics`: how NFF's spheres and cones come (the NFF files and the SPD's
// built-in scenes; no other format has them).
Scene loadScene(const std::string& nameOrPath, QuadricForm quadrics = QuadricForm::Tessellate);

// The embedded Cornell box: closed walls, a glass block, a mirror block, an area
// lamp and a point light (docs/scenes.md lists its triangle ids). Needs no file.
Scene makeCornellBox();

// The 12 triangles of the closed box [lo, hi], wound outwards (counter-clockwise
// seen from outside); the 8 corners are shared bit-identically.
std::vector<Triangle> boxTriangles(const glm::vec3& lo, const glm::vec3& hi);

// The built-in `builtin:cube`: the unit cube, each face its own colour, a point
// light, and a view from outside onto three faces. Every face lies on the
// scene's bounding box (docs/scenes.md).
Scene makeCube();

// A closed unit sphere: an icosahedron whose triangles are split in four
// `levels` times, the new vertices pushed onto the sphere (20 * 4^levels
// triangles). Vertices are shared by index, so every copy of one is
// bit-identical and the mesh is watertight.
Scene makeIcosphere(int levels);

// Splits every triangle into four at its edge midpoints (shared midpoints are
// bit-identical, so the mesh stays watertight). Used to build large test meshes.
Scene subdivide(const Scene& scene, int times);

}  // namespace lancer
