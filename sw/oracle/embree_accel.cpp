#include "oracle/embree_accel.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/quadric.h"

namespace lancer {

namespace {

RTCRayHit toEmbree(const Ray& ray) {
  RTCRayHit rh;
  std::memset(&rh, 0, sizeof rh);
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = ray.tMax;
  rh.ray.mask = std::numeric_limits<unsigned>::max();
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// One triangle geometry whose vertices are per-triangle copies of the scene's.
void attachTriangles(RTCDevice device, RTCScene scene, const std::vector<Triangle>& triangles) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = triangles.size();
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const Triangle& t = triangles[i];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& v = k == 0 ? t.v0 : (k == 1 ? t.v1 : t.v2);
      vertices[9 * i + 3 * k + 0] = v.x;
      vertices[9 * i + 3 * k + 1] = v.y;
      vertices[9 * i + 3 * k + 2] = v.z;
      indices[3 * i + k] = unsigned(3 * i + k);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}

// ---- The quadrics' user geometry -------------------------------------------------

const std::vector<Quadric>& quadricsOf(void* user) { return *static_cast<const std::vector<Quadric>*>(user); }

void quadricBounds(const RTCBoundsFunctionArguments* args) {
  const Aabb box = quadricsOf(args->geometryUserPtr)[args->primID].bounds();
  *args->bounds_o = RTCBounds{box.lo.x, box.lo.y, box.lo.z, 0.0f, box.hi.x, box.hi.y, box.hi.z, 0.0f};
}

// Ray i of an Embree packet of N, its segment (0, tfar].
Ray rayOfPacket(RTCRayN* ray, unsigned n, unsigned i) {
  return {{RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)},
          {RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)},
          RTCRayN_tfar(ray, n, i)};
}

void quadricIntersect(const RTCIntersectFunctionNArguments* args) {
  const Quadric& quadric = quadricsOf(args->geometryUserPtr)[args->primID];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const std::optional<QuadricHit> hit = intersectQuadric(rayOfPacket(rays, args->N, i), quadric, args->primID);
    if (!hit) continue;
    RTCRayN_tfar(rays, args->N, i) = hit->hit.t;
    RTCHitN_Ng_x(hits, args->N, i) = float(hit->normal.x);
    RTCHitN_Ng_y(hits, args->N, i) = float(hit->normal.y);
    RTCHitN_Ng_z(hits, args->N, i) = float(hit->normal.z);
    RTCHitN_u(hits, args->N, i) = hit->hit.u;
    RTCHitN_v(hits, args->N, i) = hit->hit.v;
    RTCHitN_primID(hits, args->N, i) = args->primID;
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
  }
}

void quadricOccluded(const RTCOccludedFunctionNArguments* args) {
  const Quadric& quadric = quadricsOf(args->geometryUserPtr)[args->primID];
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (intersectQuadric(rayOfPacket(args->ray, args->N, i), quadric, args->primID)) {
      RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
  }
}

}  // namespace

EmbreeAccel::EmbreeAccel(const Scene& scene)
    : triangleCount_(static_cast<uint32_t>(scene.triangles.size())), quadrics_(scene.quadrics) {
  device_ = rtcNewDevice("threads=1");
  if (!device_) throw std::runtime_error("embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  if (!scene.triangles.empty()) attachTriangles(device_, scene_, scene.triangles);
  if (!quadrics_.empty()) {
    RTCGeometry user = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(user, static_cast<unsigned>(quadrics_.size()));
    rtcSetGeometryUserData(user, &quadrics_);
    rtcSetGeometryBoundsFunction(user, quadricBounds, nullptr);
    rtcSetGeometryIntersectFunction(user, quadricIntersect);
    rtcSetGeometryOccludedFunction(user, quadricOccluded);
    rtcCommitGeometry(user);
    quadricGeometry_ = rtcAttachGeometry(scene_, user);
    rtcReleaseGeometry(user);
  }
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) {
    throw std::runtime_error(fmt::format("embree: scene build failed (error {})", int(rtcGetDeviceError(device_))));
  }
}

EmbreeAccel::~EmbreeAccel() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

namespace {

// Embree asserts (and aborts) on a ray with a NaN or infinite component.
void checkEmbreeRay(const Ray& ray) {
  if (!allFinite(ray.origin) || !allFinite(ray.dir) || std::isnan(ray.tMax)) {
    throw InputError(fmt::format("embree: ray ({}, {}, {}) + t ({}, {}, {}) has a NaN or infinite component",
                                 ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z));
  }
}

}  // namespace

std::optional<Hit> EmbreeAccel::intersect(const Ray& ray, TraversalStats*) const {
  checkEmbreeRay(ray);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = toEmbree(ray);
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  // A quadric's id follows the triangles' (Scene's one id space).
  const uint32_t prim = rh.hit.geomID == quadricGeometry_ ? triangleCount_ + rh.hit.primID : rh.hit.primID;
  return Hit{prim, rh.ray.tfar, rh.hit.u, rh.hit.v};
}

bool EmbreeAccel::intersectP(const Ray& ray) const {
  checkEmbreeRay(ray);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = toEmbree(ray).ray;
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0.0f;  // Embree marks an occluded ray with tfar = -inf
}

}  // namespace lancer
