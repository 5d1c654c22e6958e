#include "oracle/embree_accel.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"

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

}  // namespace

EmbreeAccel::EmbreeAccel(const Scene& scene) {
  device_ = rtcNewDevice("threads=1");
  if (!device_) throw std::runtime_error("embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = scene.triangles.size();
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const Triangle& t = scene.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& v = k == 0 ? t.v0 : (k == 1 ? t.v1 : t.v2);
      vertices[9 * i + 3 * k + 0] = v.x;
      vertices[9 * i + 3 * k + 1] = v.y;
      vertices[9 * i + 3 * k + 2] = v.z;
      indices[3 * i + k] = unsigned(3 * i + k);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
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
  return Hit{rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v};
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
