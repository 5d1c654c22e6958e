#pragma once

#include <optional>
#include <span>

#include "common/png.h"
#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// Shades one pixel per ray from its closest hit: the material's diffuse colour
// lit by a headlight (|cos| between the geometric normal and the ray), plus
// emission; misses are a dark background. Used for the reference renders and
// for images drawn from the hardware's own hits, so the two are comparable.
Image shadeHits(const Scene& scene, std::span<const Ray> rays,
                std::span<const std::optional<Hit>> hits, int width, int height);

}  // namespace lancer
