#pragma once

#include <cstdint>
#include <string_view>

namespace lancer {

// The classes of ray a Whitted tracer spawns (docs/effects.md). Part of the
// WaveTracer contract in effects/whitted.h.
enum class RayClass : uint8_t { Primary, Shadow, Reflection, Refraction };

inline constexpr int kRayClassCount = 4;

// "primary", "shadow", "reflection", "refraction": the --effects names and report keys.
std::string_view toString(RayClass cls);

}  // namespace lancer
