#pragma once

#include <compare>
#include <cstdint>
#include <string>
#include <string_view>

namespace lancer {

// The classes of ray the integrators spawn (docs/effects.md, docs/incoherent.md).
// Part of the WaveTracer contract in effects/whitted.h. The Whitted loop's
// four come first; Camera is the eye ray of the other integrators (as Primary
// is Whitted's), Bounce a path's continuation, Ao an occlusion segment.
enum class RayClass : uint8_t { Primary, Shadow, Reflection, Refraction, Camera, Bounce, Ao };

inline constexpr int kRayClassCount = 7;
inline constexpr int kWhittedClassCount = 4;  // Primary .. Refraction

// "primary", "shadow", "reflection", "refraction", "camera", "bounce", "ao":
// the --effects names and report keys.
std::string_view toString(RayClass cls);

// A ray that starts at the camera (no parent in the previous wave).
constexpr bool fromCamera(RayClass cls) { return cls == RayClass::Primary || cls == RayClass::Camera; }

// What the report counts a ray under: its class and, for a bounce, which
// (1: the first bounce off a camera ray's hit).
struct ClassKey {
  constexpr ClassKey(RayClass c = RayClass::Primary, uint16_t b = 0) : cls(c), bounce(b) {}  // NOLINT: a class is its key
  RayClass cls;
  uint16_t bounce;
  auto operator<=>(const ClassKey&) const = default;
};

// "bounce3" for the third bounce, else the class's name.
std::string toString(ClassKey key);

}  // namespace lancer
