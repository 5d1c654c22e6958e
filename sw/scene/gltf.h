#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace lancer {

// Reads a glTF 2.0 file (.gltf, or a .glb container; docs/scenes.md, "glTF
// 2.0"): assimp reads the meshes' buffers (binary floats, exact) and the core
// material factors; Lancer reads the JSON itself for what assimp 5.2 drops or
// mangles, and places every mesh at its node's world transform. The JSON's
// numbers are read correctly rounded to float. Throws InputError naming the
// file (readGltfExtras' errors, assimp's, a non-finite vertex, material terms
// out of range, "scene has no triangles").
Scene loadGltf(const std::string& path);

// What Lancer reads from a glTF 2.0 file's JSON itself, because assimp 5.2
// drops or mangles it: the punctual lights with their names and their nodes'
// world transforms, the scene's camera, the per-material factors assimp does
// not keep, and the nodes' transforms (assimp reads their numbers through
// double, a second rounding, and takes a world transform within 0.01 of the
// identity for the identity).
struct GltfExtras {
  // KHR_lights_punctual: one Light per node that carries a light, in the
  // depth-first order of the default scene's nodes.
  std::vector<Light> lights;
  // The first perspective camera in that order, at its node's world transform.
  std::optional<View> view;
  // Per glTF material (the same index assimp gives it): its name, and the
  // extensions' factors, read whether or not the file lists them in
  // "extensionsUsed" (assimp reads an extension only when it is listed).
  struct MaterialExtras {
    std::string name;
    float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
    float transmission = 0.0f;      // KHR_materials_transmission
    float ior = 1.5f;               // KHR_materials_ior (glTF's default: 1.5)
  };
  std::vector<MaterialExtras> materials;
  // The nodes that carry a mesh, in the same walk order, each with its world
  // transform: Lancer places the meshes itself (loadGltf).
  struct MeshInstance {
    size_t mesh = 0;         // index into the file's meshes
    glm::mat4 world{1.0f};   // its parents' transforms times its own, in float
    std::string node;        // "node 3 'name'", for messages
  };
  std::vector<MeshInstance> meshInstances;
  // Per mesh of the file, how many primitives it has (assimp makes one aiMesh
  // of each, in order).
  std::vector<size_t> primitiveCounts;
};

// Reads the JSON of a .gltf file, or the JSON chunk of a .glb container.
// Throws InputError naming the file, and the light, camera, node or material at
// fault: malformed JSON, a wrong container, a field of the wrong type, a node
// or light index out of range, a cycle in the node graph, an unknown light
// type, a spot light without its cone, a negative intensity or colour, spot cones outside 0 <= inner < outer <= pi/2,
// a light or camera whose world position or direction is not finite.
GltfExtras readGltfExtras(const std::string& path);

}  // namespace lancer
