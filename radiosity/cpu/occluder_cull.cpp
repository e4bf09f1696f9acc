#include "radiosity/cpu/occluder_cull.h"

#include <algorithm>
#include <cmath>

namespace cpgi {

ReceiverTiles receiverTiles(const LightmapAtlas& atlas, std::span<const uint32_t> texels, float lift,
                            int side) {
  ReceiverTiles out;
  out.tileOf.assign(texels.size(), 0);
  std::vector<int64_t> entry(atlas.texelCount(), -1);
  for (size_t k = 0; k < texels.size(); ++k) entry[texels[k]] = int64_t(k);
  for (size_t pi = 0; pi < atlas.patches.size(); ++pi) {
    const Patch& p = atlas.patches[pi];
    for (int tj = 0; tj < p.h; tj += side)
      for (int ti = 0; ti < p.w; ti += side) {
        glm::vec3 lo(3e38f), hi(-3e38f);
        std::vector<size_t> members;
        for (int j = tj; j < std::min(tj + side, p.h); ++j)
          for (int i = ti; i < std::min(ti + side, p.w); ++i) {
            const size_t t = size_t(p.y + j) * size_t(atlas.width) + size_t(p.x + i);
            if (atlas.patch[t] != int32_t(pi) || entry[t] < 0) continue;
            const glm::vec3 x = atlas.position[t] + atlas.normal[t] * lift;
            lo = glm::min(lo, x), hi = glm::max(hi, x);
            members.push_back(size_t(entry[t]));
          }
        if (members.empty()) continue;
        const glm::vec3 centre = 0.5f * (lo + hi);
        float radius = 0.0f;
        for (size_t k : members) {
          const uint32_t t = texels[k];
          radius = std::max(radius, glm::length(atlas.position[t] + atlas.normal[t] * lift - centre));
          out.tileOf[k] = uint32_t(out.spheres.size());
        }
        out.spheres.push_back(glm::vec4(centre, radius));
        out.normals.push_back(p.normal);
        out.counts.push_back(uint32_t(members.size()));
        out.patches.push_back(int32_t(pi));
      }
  }
  return out;
}

ConvexOccluders::ConvexOccluders(const Scene& scene, const LightmapAtlas& atlas)
    : outlineOf_(scene.triangles.size(), -1) {
  auto add = [&](std::vector<glm::vec3> corners) {
    Outline o;
    const glm::vec3 n = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    const float length = glm::length(n);
    if (!(length > 0.0f)) return int32_t(-1);
    o.normal = n / length;
    o.corners = std::move(corners);
    outlines_.push_back(std::move(o));
    return int32_t(outlines_.size() - 1);
  };
  for (const Patch& p : atlas.patches) {
    if (p.quad < 0) continue;  // a loose triangle is its own outline, below
    const glm::vec3 u = float(p.w) * p.texelU, v = float(p.h) * p.texelV;
    const int32_t o = add({p.origin, p.origin + u, p.origin + u + v, p.origin + v});
    for (int32_t t : p.triangles)
      if (t >= 0 && size_t(t) < outlineOf_.size()) outlineOf_[size_t(t)] = o;
  }
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    if (outlineOf_[t] < 0) {
      const Triangle& tri = scene.triangles[t];
      outlineOf_[t] = add({tri.p[0], tri.p[1], tri.p[2]});
    }
}

bool ConvexOccluders::hides(const RayScene& rays, const glm::vec3& eye, const glm::vec4& sphere,
                            float margin) const {
  const glm::vec3 centre(sphere);
  const float radius = sphere.w;
  glm::vec3 axis = centre - eye;
  const float distance = glm::length(axis);
  if (!(distance > 1.01f * (radius + margin))) return false;
  axis /= distance;
  // The first few surfaces along the axis, each a candidate blocker.
  float from = 0.0f;
  for (int tries = 0; tries < kBlockersTried; ++tries) {
    const RayScene::Hit hit = rays.intersect(eye, axis, from, distance - radius - margin);
    if (!hit) return false;
    if (blocks(hit.triangle, eye, axis, distance, sphere, margin)) return true;
    from = hit.t + 1e-4f * distance;
  }
  return false;
}

bool ConvexOccluders::hidesFromEvery(const RayScene& rays, std::span<const glm::vec3> eyes,
                                     const glm::vec4& sphere, float margin) const {
  if (eyes.empty()) return false;
  const glm::vec3 centre(sphere);
  const float radius = sphere.w;
  // Every eye's axis to the sphere; an eye too close makes the group unsure.
  auto axisOf = [&](const glm::vec3& eye, float& distance) {
    const glm::vec3 axis = centre - eye;
    distance = glm::length(axis);
    return axis / distance;
  };
  float distance0 = 0.0f;
  const glm::vec3 axis0 = axisOf(eyes[0], distance0);
  for (const glm::vec3& eye : eyes)
    if (!(glm::distance(centre, eye) > 1.01f * (radius + margin))) return false;
  float from = 0.0f;
  for (int tries = 0; tries < kBlockersTried; ++tries) {
    const RayScene::Hit hit = rays.intersect(eyes[0], axis0, from, distance0 - radius - margin);
    if (!hit) return false;
    bool all = true;
    for (size_t e = 0; e < eyes.size() && all; ++e) {
      float distance = 0.0f;
      const glm::vec3 axis = axisOf(eyes[e], distance);
      all = blocks(hit.triangle, eyes[e], axis, distance, sphere, margin);
    }
    if (all) return true;
    from = hit.t + 1e-4f * distance0;
  }
  return false;
}

bool ConvexOccluders::blocks(int32_t triangle, const glm::vec3& eye, const glm::vec3& axis, float distance,
                             const glm::vec4& sphere, float margin) const {
  const glm::vec3 centre(sphere);
  const float radius = sphere.w;
  const int32_t index = outlineOf_[size_t(triangle)];
  if (index < 0) return false;
  const Outline& o = outlines_[size_t(index)];
  // The eye on one side of the blocker's plane, the whole sphere (and the `margin` its segments stop
  // short by) on the other.
  const float eyeSide = glm::dot(o.normal, eye - o.corners[0]);
  const float side = eyeSide < 0.0f ? 1.0f : -1.0f;
  const float depth = std::abs(eyeSide);
  if (!(depth > 0.0f) || side * glm::dot(o.normal, centre - o.corners[0]) < radius + margin) return false;
  // The cone from the eye round the sphere (half-angle theta) meets the plane in an ellipse; every point
  // of it lies within `reach` of where the axis meets the plane: |t dir − t0 axis| ≤ |t − t0| + 2 t0
  // sin(θ/2), with t between depth / cos(α ∓ θ).
  const float theta = std::asin(std::min(radius / distance, 1.0f));
  const float cosAlpha = side * glm::dot(o.normal, axis);
  if (!(cosAlpha > 0.0f)) return false;
  const float alpha = std::acos(std::min(cosAlpha, 1.0f));
  if (alpha + theta > 1.5f) return false;  // near grazing the ellipse runs far: unsure
  const float t0 = depth / cosAlpha;
  const float tNear = depth / std::cos(std::max(alpha - theta, 0.0f)), tFar = depth / std::cos(alpha + theta);
  const float reach = std::max(tFar - t0, t0 - tNear) + 2.0f * t0 * std::sin(0.5f * theta);
  const glm::vec3 at = eye + t0 * axis;
  // Inside the convex outline by `reach` from every edge, with a little to spare for rounding.
  const float spare = 1e-4f * (reach + t0);
  const size_t n = o.corners.size();
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 edge = o.corners[(i + 1) % n] - o.corners[i];
    const glm::vec3 inward = glm::cross(o.normal, edge);
    const float length = glm::length(inward);
    if (!(length > 0.0f) || glm::dot(inward, at - o.corners[i]) / length < reach + spare) return false;
  }
  return true;
}

}  // namespace cpgi
