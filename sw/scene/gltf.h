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

// The major version a glTF file declares: a .glb container's header, or a
// .gltf's "asset": {"version": "1.0"}. 2 when it says nothing readable
// (loadGltf then reports what is wrong with the file). assimp reads glTF 1.0
// itself (loadScene).
int gltfMajorVersion(const std::string& path);

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
    // Where the node sits in the default scene's tree: its root's position in
    // the scene's list, then each child's position in its parent's list.
    // assimp builds its node tree in the same shape, so this finds the node's
    // aiNode, and the aiNode the node's meshes (loadGltf).
    std::vector<size_t> treePath;
  };
  std::vector<MeshInstance> meshInstances;
  // How many roots the default scene lists (assimp's root node is the root
  // itself when there is one, a node above them all otherwise).
  size_t rootCount = 0;
  // Per mesh of the file, the glTF material of each primitive (nullopt: none,
  // glTF's default material). assimp makes one aiMesh of each primitive, but
  // orders meshes and materials by when its reader first met them, not by
  // their index in the file; the primitives' materials tie assimp's materials
  // to the file's.
  std::vector<std::vector<std::optional<size_t>>> primitiveMaterials;
};

// Reads the JSON of a .gltf file, or the JSON chunk of a .glb container.
// Throws InputError naming the file, and the light, camera, node or material at
// fault: malformed JSON, a wrong container, a field of the wrong type, a node
// or light index out of range, a cycle in the node graph, an unknown light
// type, a spot light without its cone, a negative intensity or colour, spot cones outside 0 <= inner < outer <= pi/2,
// a light or camera whose world position or direction is not finite.
GltfExtras readGltfExtras(const std::string& path);

}  // namespace lancer
