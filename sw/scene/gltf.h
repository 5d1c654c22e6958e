#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace lancer {

// What Lancer reads from a glTF 2.0 file's JSON itself, because assimp 5.2
// drops or mangles it (docs/scenes.md, "glTF 2.0"): the punctual lights with
// their names and their nodes' world transforms, the scene's camera, and the
// per-material factors assimp does not keep. assimp still reads the geometry
// and the material factors it keeps (loadScene merges the two).
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
};

// Reads the JSON of a .gltf file, or the JSON chunk of a .glb container.
// Throws InputError naming the file, and the light, camera, node or material at
// fault: malformed JSON, a wrong container, a field of the wrong type, a node
// or light index out of range, a cycle in the node graph, an unknown light
// type, a spot light without its cone, a negative intensity or colour, spot cones outside 0 <= inner < outer <= pi/2,
// a light or camera whose world position or direction is not finite.
GltfExtras readGltfExtras(const std::string& path);

}  // namespace lancer
