#include "radiosity/lightmap/ray_scene.h"

#include <string>

#include <embree3/rtcore.h>

#include "core/error.h"

namespace cpgi {

namespace {

void throwOnDeviceError(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw SystemError(std::string("embree: ") + what + " failed (error " + std::to_string(int(error)) + ")");
}

}  // namespace

RayScene::RayScene(const Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw SystemError("embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust traversal: texel sample points often sit a fraction of a millimetre from walls and corners.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  const size_t count = scene.triangles.size();
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
  RTCRayHit rh{};
  rh.ray.org_x = origin.x, rh.ray.org_y = origin.y, rh.ray.org_z = origin.z;
  rh.ray.dir_x = direction.x, rh.ray.dir_y = direction.y, rh.ray.dir_z = direction.z;
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
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

}  // namespace cpgi
