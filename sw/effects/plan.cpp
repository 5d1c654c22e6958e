#include "effects/plan.h"

#include <algorithm>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

std::string_view toString(RayClass cls) {
  switch (cls) {
    case RayClass::Primary: return "primary";
    case RayClass::Shadow: return "shadow";
    case RayClass::Reflection: return "reflection";
    case RayClass::Refraction: return "refraction";
    case RayClass::Camera: return "camera";
    case RayClass::Bounce: return "bounce";
    case RayClass::Ao: return "ao";
  }
  return "?";
}

std::string toString(ClassKey key) {
  return key.cls == RayClass::Bounce ? fmt::format("bounce{}", key.bounce) : std::string(toString(key.cls));
}

namespace {

constexpr std::array<RayClass, kWhittedClassCount> kClasses = {RayClass::Primary, RayClass::Shadow,
                                                          RayClass::Reflection, RayClass::Refraction};

std::string_view kindName(Light::Kind kind) {
  switch (kind) {
    case Light::Kind::Point: return "point";
    case Light::Kind::Spot: return "spot";
    case Light::Kind::Directional: return "directional";
  }
  return "?";
}

std::string lightReason(const Light& light, size_t index) {
  const std::string name = light.name.empty() ? fmt::format("#{}", index) : light.name;
  if (light.kind == Light::Kind::Directional) {
    return fmt::format("{} light {} along ({:g}, {:g}, {:g})", kindName(light.kind), name, light.direction.x,
                       light.direction.y, light.direction.z);
  }
  return fmt::format("{} light {} at ({:g}, {:g}, {:g})", kindName(light.kind), name, light.position.x,
                     light.position.y, light.position.z);
}

std::string materialName(const Material& m, size_t index) {
  return m.name.empty() ? fmt::format("#{}", index) : m.name;
}

// Reasons that many materials share ("T 0.8, index of refraction 1.1" on 13 gears)
// become one line naming the first few, in the order first met.
class MaterialReasons {
 public:
  void add(const std::string& what, const std::string& material) {
    for (auto& [w, names] : groups_) {
      if (w == what) {
        names.push_back(material);
        return;
      }
    }
    groups_.push_back({what, {material}});
  }
  void appendTo(std::vector<std::string>& reasons) const {
    constexpr size_t kNamed = 3;
    for (const auto& [what, names] : groups_) {
      if (names.size() == 1) {
        reasons.push_back(fmt::format("material {}: {}", names[0], what));
        continue;
      }
      const size_t shown = std::min(kNamed, names.size());
      reasons.push_back(fmt::format("{} materials ({}{}): {}", names.size(),
                                    fmt::join(names.begin(), names.begin() + long(shown), ", "),
                                    names.size() > shown ? ", ..." : "", what));
    }
  }

 private:
  std::vector<std::pair<std::string, std::vector<std::string>>> groups_;
};

}  // namespace

EffectsPlan planEffects(const Scene& scene, const EffectsOptions& options) {
  if (options.maxDepth < 1) {
    throw InputError(fmt::format("--max-depth {} must be >= 1 (the eye ray has depth 1)", options.maxDepth));
  }
  if (options.lightSamples < 1) {
    throw InputError(fmt::format("--light-samples {} must be >= 1", options.lightSamples));
  }
  std::array<bool, kWhittedClassCount> wanted{};
  wanted.fill(options.effects.empty());
  wanted[size_t(RayClass::Primary)] = true;
  for (const std::string& name : options.effects) {
    const auto it = std::find_if(kClasses.begin(), kClasses.end(), [&](RayClass c) { return toString(c) == name; });
    if (it == kClasses.end()) {
      throw InputError(fmt::format("--effects: unknown effect '{}' (primary, shadow, reflection, refraction)", name));
    }
    wanted[size_t(*it)] = true;
  }

  EffectsPlan plan;
  plan.maxDepth = options.maxDepth;
  plan.lightSamples = options.lightSamples;
  plan.restricted = !options.effects.empty();
  plan.lights = scene.lights.size();
  auto& primary = plan.classes[size_t(RayClass::Primary)];
  auto& shadow = plan.classes[size_t(RayClass::Shadow)];
  auto& reflection = plan.classes[size_t(RayClass::Reflection)];
  auto& refraction = plan.classes[size_t(RayClass::Refraction)];
  primary.calledFor = true;
  primary.reasons.push_back("the camera");

  for (size_t i = 0; i < scene.lights.size(); ++i) shadow.reasons.push_back(lightReason(scene.lights[i], i));

  // Only materials some primitive uses call for anything; only triangles are
  // area lights (an emissive quadric glows where seen, but no shadow ray samples it).
  std::vector<size_t> used(scene.materials.size(), 0), usedByTriangles(scene.materials.size(), 0);
  MaterialReasons reflecting, refracting;
  for (size_t p = 0; p < scene.materialOf.size(); ++p) {
    ++used[scene.materialOf[p]];
    if (p < scene.size()) ++usedByTriangles[scene.materialOf[p]];
  }
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    if (!used[m]) continue;
    const Material& mat = scene.materials[m];
    const std::string name = materialName(mat, m);
    if (mat.emission != glm::vec3(0.0f) && usedByTriangles[m]) {
      const size_t n = usedByTriangles[m];
      plan.emissiveTriangles += n;
      shadow.reasons.push_back(fmt::format("material {}: {} emissive triangle{} (area light, {} sample{} each)", name,
                                           n, n == 1 ? "" : "s", options.lightSamples,
                                           options.lightSamples == 1 ? "" : "s"));
    }
    if (mat.ks > 0.0f) reflecting.add(fmt::format("Ks {:g}", mat.ks), name);
    if (mat.transmittance > 0.0f) {
      if (mat.ks <= 0.0f) reflecting.add(fmt::format("T {:g} (transmitters reflect, SPD rule 8)", mat.transmittance), name);
      refracting.add(fmt::format("T {:g}, index of refraction {:g}", mat.transmittance, mat.ior), name);
    }
  }
  reflecting.appendTo(reflection.reasons);
  refracting.appendTo(refraction.reasons);
  shadow.calledFor = !shadow.reasons.empty();
  reflection.calledFor = !reflection.reasons.empty();
  refraction.calledFor = !refraction.reasons.empty();
  // Secondary rays need room in the tree: at --max-depth 1 only eye rays exist.
  for (const RayClass c : kClasses) {
    auto& k = plan.classes[size_t(c)];
    const bool secondary = c == RayClass::Reflection || c == RayClass::Refraction;
    k.enabled = k.calledFor && wanted[size_t(c)] && !(secondary && options.maxDepth < 2);
  }
  return plan;
}

std::string EffectsPlan::describe() const {
  std::string out = fmt::format("effects plan (max depth {}, {} light sample{} per area-light triangle):\n", maxDepth,
                                lightSamples, lightSamples == 1 ? "" : "s");
  constexpr size_t kShown = 6;
  for (const RayClass c : kClasses) {
    const Class& k = classes[size_t(c)];
    const std::string_view state = k.enabled ? "yes" : k.calledFor ? "off" : "no ";
    std::string why;
    if (k.calledFor) {
      const size_t shown = std::min(kShown, k.reasons.size());
      why = fmt::format("{}", fmt::join(k.reasons.begin(), k.reasons.begin() + long(shown), "; "));
      if (k.reasons.size() > shown) why += fmt::format("; and {} more", k.reasons.size() - shown);
      if (!k.enabled) {
        why += (c == RayClass::Reflection || c == RayClass::Refraction) && maxDepth < 2
                   ? " [off: --max-depth 1 leaves only eye rays]"
                   : " [off: not in --effects]";
      }
    } else {
      why = c == RayClass::Shadow ? "the scene has no lights and no emissive triangles"
            : c == RayClass::Reflection ? "no material has Ks > 0 or T > 0"
                                        : "no material has T > 0";
    }
    out += fmt::format("  {:<10} {}  {}\n", toString(c), state, why);
  }
  return out;
}

nlohmann::json EffectsPlan::toJson() const {
  nlohmann::json j;
  j["max_depth"] = maxDepth;
  j["light_samples"] = lightSamples;
  j["lights"] = lights;
  j["emissive_triangles"] = emissiveTriangles;
  j["restricted"] = restricted;
  nlohmann::json cls = nlohmann::json::object();
  for (const RayClass c : kClasses) {
    const Class& k = classes[size_t(c)];
    cls[std::string(toString(c))] = {{"called_for", k.calledFor}, {"enabled", k.enabled}, {"reasons", k.reasons}};
  }
  j["classes"] = cls;
  return j;
}

}  // namespace lancer
