#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/isect_job.h"

namespace lancer {

// A record's fields as hex, in wire order: "ray_id=0x.. org=[0x..,..] ...".
std::string hexFields(const fx::QRay& ray);
std::string hexFields(const fx::QTriangle& tri);
std::string hexFields(const fx::IsectResult& res);

// The multi-line reproducer of a mismatch: ray id, inputs in hex, both records,
// the differing bits (XOR of the two wire images), and the replay command.
std::string describeMismatch(const Mismatch& mismatch, const std::string& replayCommand);

// How the hardware's closest hits differ from the floating-point reference on
// the original rays. t errors are distances along the ray in lattice units
// (the position format's quantum), the reference t re-evaluated in long double.
struct ReferenceComparison {
  uint64_t disagreements = 0;  // rays where hit/miss or the triangle differs
  uint64_t hitMissDiffers = 0;
  uint64_t primDiffers = 0;
  uint64_t compared = 0;       // rays where both hit the same triangle
  double maxTError = 0;
  double meanTError = 0;
  std::optional<uint32_t> firstDisagreement;
};

ReferenceComparison compareWithReference(const Scene& scene, std::span<const Ray> rays,
                                         std::span<const std::optional<Hit>> reference,
                                         const IsectJobResult& job, const Quantizer& quantizer);

// The hardware's closest hit as a scene-space Hit (t in the original ray's units).
std::optional<Hit> sceneHit(const IsectJobResult& job, size_t ray);

}  // namespace lancer
