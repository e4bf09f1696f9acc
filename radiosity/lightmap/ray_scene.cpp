#include "radiosity/lightmap/ray_scene.h"

#include <algorithm>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "core/error.h"

namespace cpgi {

namespace {

void throwOnDeviceError(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw SystemError(std::string("embree: ") + what + " failed (error " + std::to_string(int(error)) + ")");
}

// An intersection context that also carries the scene's normals and the back face hit first, for
// otherSideOnly.
struct FacingContext {
  RTCIntersectContext context;  // first: Embree hands the filter a pointer to it
  const std::vector<glm::vec3>* normals;
  glm::vec3 backNormal;
};

// Keeps only candidates that face the ray and lie in the back face's plane turned round: the other side
// of a zero-thickness wall, not a floor meeting that wall just beyond it (which would let the ray
// through the wall at a grazing angle).
void otherSideOnly(const RTCFilterFunctionNArguments* args) {
  const auto* facing = reinterpret_cast<const FacingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                        RTCRayN_dir_z(args->ray, args->N, i));
    const glm::vec3& n = (*facing->normals)[RTCHitN_primID(args->hit, args->N, i)];
    if (glm::dot(n, dir) >= 0.0f || glm::dot(n, facing->backNormal) > -0.999f) args->valid[i] = 0;
  }
}

RTCRayHit makeRayHit(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) {
  RTCRayHit rh{};
  rh.ray.org_x = origin.x, rh.ray.org_y = origin.y, rh.ray.org_z = origin.z;
  rh.ray.dir_x = direction.x, rh.ray.dir_y = direction.y, rh.ray.dir_z = direction.z;
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

RayScene::RayScene(const Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw SystemError("embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust traversal: texel sample points often sit a fraction of a millimetre from walls and corners.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  const size_t count = scene.triangles.size();
  normals_.reserve(count);
  for (const Triangle& t : scene.triangles) normals_.push_back(t.geometricNormal());
  if (count > 0) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), count));
    throwOnDeviceError(device_, "allocating the triangle buffers");
    for (size_t t = 0; t < count; ++t)
      for (int k = 0; k < 3; ++k) {
        const glm::vec3& p = scene.triangles[t].p[k];
        vertices[9 * t + 3 * k + 0] = p.x;
        vertices[9 * t + 3 * k + 1] = p.y;
        vertices[9 * t + 3 * k + 2] = p.z;
        indices[3 * t + k] = static_cast<uint32_t>(3 * t + k);
      }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  throwOnDeviceError(device_, "building the BVH");
  diagonal_ = glm::length(scene.bounds().size());
}

RayScene::~RayScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

RayScene::Hit RayScene::intersect(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                                  float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = makeRayHit(origin, direction, tnear, tfar);
  rtcIntersect1(scene_, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  if (glm::dot(normals_[rh.hit.primID], direction) > 0.0f) {
    // Seen from behind. Where a front face lies at the same distance (the two sides of a zero-thickness
    // wall) it is the one hit: which of two coincident triangles Embree reports is arbitrary, and the
    // back one ended the path (openings' room C, behind such a partition, came out 17 % too dark).
    const float t = rh.ray.tfar, slack = std::max(1e-4f * t, 1e-6f * diagonal_);
    FacingContext facing{{}, &normals_, normals_[rh.hit.primID]};
    rtcInitIntersectContext(&facing.context);
    facing.context.filter = otherSideOnly;
    RTCRayHit front = makeRayHit(origin, direction, std::max(tnear, t - slack), t + slack);
    rtcIntersect1(scene_, &facing.context, &front);
    if (front.hit.geomID != RTC_INVALID_GEOMETRY_ID) rh = front;
  }
  hit.triangle = static_cast<int32_t>(rh.hit.primID);
  hit.t = rh.ray.tfar;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  return hit;
}

bool RayScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
  ray.dir_x = direction.x, ray.dir_y = direction.y, ray.dir_z = direction.z;
  ray.tnear = tnear;
  ray.tfar = tfar;
  ray.mask = 0xffffffffu;
  rtcOccluded1(scene_, &context, &ray);
  // Embree marks an occluded ray by setting tfar to −∞.
  return ray.tfar < 0.0f;
}

void RayScene::occluded(std::span<const Segment> segments, std::span<uint8_t> hidden) const {
  thread_local std::vector<RTCRay> rays;
  rays.resize(segments.size());
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& g = segments[i];
    RTCRay& r = rays[i];
    r = RTCRay{};
    r.org_x = g.origin.x, r.org_y = g.origin.y, r.org_z = g.origin.z;
    r.dir_x = g.direction.x, r.dir_y = g.direction.y, r.dir_z = g.direction.z;
    r.tnear = 0.0f;
    r.tfar = g.length;
    r.mask = 0xffffffffu;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  if (!rays.empty()) rtcOccluded1M(scene_, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
  for (size_t i = 0; i < segments.size(); ++i) hidden[i] = rays[i].tfar < 0.0f;
}

}  // namespace cpgi
