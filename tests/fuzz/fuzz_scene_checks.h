#pragma once

// Properties every scene a loader accepts must have (fuzz_nff, fuzz_obj,
// fuzz_ply; fuzz_mtl checks its materials): the tracers, the camera and the
// quantizer rely on them without checking.

#include <cmath>

#include "fuzz_support.h"
#include "scene/scene.h"

namespace lancer::fuzz {

inline bool inside(const Aabb& box, const glm::vec3& p) {
  return p.x >= box.lo.x && p.y >= box.lo.y && p.z >= box.lo.z && p.x <= box.hi.x && p.y <= box.hi.y &&
         p.z <= box.hi.z;
}

inline void checkMaterial(const Material& m, size_t i) {
  FUZZ_CHECK(allFinite(m.diffuse) && allFinite(m.emission), "material {} has a non-finite colour", i);
  FUZZ_CHECK(m.kd >= 0 && m.ks >= 0 && m.shine >= 0 && std::isfinite(m.kd + m.ks + m.shine),
             "material {}: kd {} ks {} shine {}", i, m.kd, m.ks, m.shine);
  FUZZ_CHECK(m.transmittance >= 0 && std::isfinite(m.transmittance), "material {}: T {}", i, m.transmittance);
  FUZZ_CHECK(m.ior > 0 && std::isfinite(m.ior), "material {}: ior {}", i, m.ior);
}

inline void checkScene(const Scene& scene) {
  FUZZ_CHECK(!scene.triangles.empty(), "a scene without triangles was accepted");
  FUZZ_CHECK(scene.materialOf.size() == scene.triangles.size(), "{} material indices for {} triangles",
             scene.materialOf.size(), scene.triangles.size());
  FUZZ_CHECK(scene.normals.empty() || scene.normals.size() == scene.triangles.size(),
             "{} shading normals for {} triangles", scene.normals.size(), scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      FUZZ_CHECK(allFinite(v), "triangle {} has a non-finite vertex ({}, {}, {})", i, v.x, v.y, v.z);
      FUZZ_CHECK(inside(scene.bounds, v), "triangle {} lies outside the scene bounds", i);
    }
    FUZZ_CHECK(scene.materialOf[i] < scene.materials.size(), "triangle {}: material {} of {}", i,
               scene.materialOf[i], scene.materials.size());
    if (!scene.normals.empty()) {
      const ShadingNormals& n = scene.normals[i];
      FUZZ_CHECK(allFinite(n.n0) && allFinite(n.n1) && allFinite(n.n2), "triangle {} has a non-finite normal", i);
    }
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) checkMaterial(scene.materials[i], i);
  for (const Light& l : scene.lights) {
    FUZZ_CHECK(allFinite(l.position) && allFinite(l.direction) && allFinite(l.color), "light {} is not finite",
               l.name);
  }
  FUZZ_CHECK(allFinite(scene.background), "non-finite background");
  if (scene.view) {
    const View& v = *scene.view;
    FUZZ_CHECK(allFinite(v.eye) && allFinite(v.target) && allFinite(v.up), "non-finite view");
    FUZZ_CHECK(v.eye != v.target, "view eye and target coincide");
    FUZZ_CHECK(v.fovYDegrees > 0 && v.fovYDegrees < 180, "view field of view {} degrees", v.fovYDegrees);
    FUZZ_CHECK(v.width >= 0 && v.height >= 0, "view resolution {}x{}", v.width, v.height);
  }
}

}  // namespace lancer::fuzz
