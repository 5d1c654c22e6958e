#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "ref/accel.h"

namespace lancer {

// Closest hits of many rays through one structure, in ray order. `onProgress`
// (optional) is called with the number of rays done every few thousand rays.
std::vector<std::optional<Hit>> traceRays(const Accel& accel, std::span<const Ray> rays,
                                          TraversalStats* stats = nullptr,
                                          const std::function<void(size_t)>& onProgress = {});

}  // namespace lancer
