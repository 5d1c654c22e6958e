#include "ref/triangle.h"

#include <cmath>
#include <type_traits>
#include <utility>

namespace lancer {

int dominantAxis(const glm::vec3& v) {
  const glm::vec3 a = glm::abs(v);
  if (a.x >= a.y && a.x >= a.z) return 0;
  return a.y >= a.z ? 1 : 2;
}

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), dir(ray.dir), tMax(ray.tMax) {
  kz = dominantAxis(ray.dir);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  // Keep the winding of the triangle in the sheared frame.
  if (ray.dir[kz] < 0.0f) std::swap(kx, ky);
  sx = ray.dir[kx] / ray.dir[kz];
  sy = ray.dir[ky] / ray.dir[kz];
}

namespace {

// The steps of the test after the edge functions, shared by both precisions.
template <typename Real>
std::optional<Hit> finishHit(Real u, Real v, Real w, const Triangle& tri, const glm::vec3& origin,
                             const glm::vec3& dir, float tMax, uint32_t prim) {
  // Step 3: outside if the edge functions disagree in sign (zero counts as inside
  // for both orientations, so an edge is owned by both triangles sharing it).
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::nullopt;
  // Step 4: the determinant is zero for a ray in the plane of the triangle and
  // for degenerate triangles; there is no single hit point then.
  const Real det = u + v + w;
  if (det == 0) return std::nullopt;
  // Step 5: the hit distance from the plane equation, in double at least:
  // t = ((v0 - o) . n) / (d . n). The sheared form (u az + v bz + w cz) / det
  // loses every digit on a sliver, whose det is a small difference of large
  // edge functions (a 900 x 0.5 triangle of regr01.obj: t off by 0.5 % in
  // float); in double the products of floats are exact and the error stays near
  // 1e-15 relative. An origin exactly in the plane gives t = 0 exactly: no hit.
  using Wide = std::conditional_t<(sizeof(Real) > sizeof(double)), Real, double>;
  using V3 = glm::vec<3, Wide>;
  const V3 v0(tri.v0);
  const V3 n = glm::cross(V3(tri.v1) - v0, V3(tri.v2) - v0);
  const Wide den = glm::dot(V3(dir), n);
  if (den == 0) return std::nullopt;
  const float t = static_cast<float>(glm::dot(v0 - V3(origin), n) / den);
  // Written so that a NaN is a miss; rounding to float keeps t <= tMax (tMax is a float).
  if (!(t > 0.0f && t <= tMax)) return std::nullopt;
  const Real rcp = Real(1) / det;  // the sign of det makes u, v, w non-negative
  return Hit{prim, t, static_cast<float>(v * rcp), static_cast<float>(w * rcp)};
}

}  // namespace

std::optional<Hit> intersectTriangle(const WatertightRay& r, const Triangle& tri,
                                     uint32_t prim) {
  // Step 1: vertices relative to the ray origin.
  const glm::vec3 a = tri.v0 - r.origin;
  const glm::vec3 b = tri.v1 - r.origin;
  const glm::vec3 c = tri.v2 - r.origin;
  // Step 2: shear so the ray runs along the kz axis through (0,0).
  const float ax = a[r.kx] - r.sx * a[r.kz];
  const float ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz];
  const float by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz];
  const float cy = c[r.ky] - r.sy * c[r.kz];
  // 2D edge functions: u weighs v0, v weighs v1, w weighs v2.
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  // A zero may be a rounding artefact on an edge; decide it in double, where the
  // products of floats are exact.
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    u = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
    v = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
    w = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
  }
  return finishHit<float>(u, v, w, tri, r.origin, r.dir, r.tMax, prim);
}

std::optional<Hit> intersectTriangleExtended(const Ray& ray, const Triangle& tri,
                                             uint32_t prim) {
  using Real = long double;
  using V3 = glm::vec<3, Real>;
  const int kz = dominantAxis(ray.dir);
  int kx = (kz + 1) % 3;
  int ky = (kx + 1) % 3;
  if (ray.dir[kz] < 0.0f) std::swap(kx, ky);
  const V3 d(ray.dir);
  const V3 o(ray.origin);
  const V3 a = V3(tri.v0) - o;
  const V3 b = V3(tri.v1) - o;
  const V3 c = V3(tri.v2) - o;
  const Real sx = d[kx] / d[kz], sy = d[ky] / d[kz];
  const Real ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const Real bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const Real cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  return finishHit<Real>(cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax, tri, ray.origin, ray.dir,
                         ray.tMax, prim);
}

}  // namespace lancer
