#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "effects/ray_class.h"
#include "scene/scene.h"

namespace lancer {

// What the user asks of the effects (the --effects, --max-depth and
// --light-samples options).
struct EffectsOptions {
  // Classes to keep, by name (primary, shadow, reflection, refraction); empty:
  // every class the scene calls for. Primary rays are always traced.
  std::vector<std::string> effects;
  int maxDepth = 5;      // deepest ray tree; the eye ray has depth 1 (SPD rule 7)
  int lightSamples = 1;  // shadow rays per emissive triangle per hit
};

// Which ray classes a scene calls for, and why; decided before tracing so a
// class the scene does not call for creates no ray, no wave and no model.
//   primary     always;
//   shadow      the scene has lights or emissive triangles (area lights);
//   reflection  some material in use has Ks > 0 or T > 0 (transmitters reflect, SPD rule 8);
//   refraction  some material in use has T > 0 (SPD rule 9).
// --effects then drops the classes not named.
struct EffectsPlan {
  struct Class {
    bool calledFor = false;             // the scene calls for it
    bool enabled = false;               // and --effects keeps it
    std::vector<std::string> reasons;   // the lights / materials that call for it
  };
  std::array<Class, kWhittedClassCount> classes;
  int maxDepth = 5;
  int lightSamples = 1;
  size_t lights = 0;              // point, spot and directional lights
  size_t emissiveTriangles = 0;   // area-light triangles
  bool restricted = false;        // --effects was given

  bool has(RayClass cls) const { return size_t(cls) < classes.size() && classes[size_t(cls)].enabled; }
  // A short block for the terminal, one line per class.
  std::string describe() const;
  nlohmann::json toJson() const;
};

// Throws InputError naming the option for an unknown --effects name, a
// --max-depth below 1 or a --light-samples below 1.
EffectsPlan planEffects(const Scene& scene, const EffectsOptions& options);

}  // namespace lancer
