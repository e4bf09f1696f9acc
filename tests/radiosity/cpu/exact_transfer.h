// The irradiance a receiver texel gets from a shooter patch sending 1 W/m² from every texel, by k × k
// points per shooter texel, each seen by its own ray: nothing shared with the rays engine's shots but the
// ray scene. The oracle of the rays engine's tests.
#pragma once

#include <cmath>
#include <cstddef>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi::testing {

inline double exactIrradianceAt(const LightmapAtlas& atlas, const RayScene& rays, int shooter, glm::vec3 x,
                                glm::vec3 n, int k) {
  constexpr double kPi = 3.14159265358979323846;
  const Patch& sp = atlas.patches[size_t(shooter)];
  const float eps = 1e-4f * rays.diagonal();
  double sum = 0.0;
  for (size_t s = 0; s < atlas.texelCount(); ++s) {
    if (atlas.patch[s] != shooter) continue;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const glm::vec3 y = atlas.position[s] + ((float(i) + 0.5f) / float(k) - 0.5f) * sp.texelU +
                            ((float(j) + 0.5f) / float(k) - 0.5f) * sp.texelV;
        const glm::vec3 v = y - x;
        const float r2 = glm::dot(v, v), r = std::sqrt(r2);
        const float ci = glm::dot(n, v) / r, cs = -glm::dot(sp.normal, v) / r;
        if (ci <= 0.0f || cs <= 0.0f) continue;
        const glm::vec3 from = x + n * eps, to = y + sp.normal * eps;
        const float length = glm::distance(from, to);
        if (rays.occluded(from, (to - from) / length, 0.0f, length - eps)) continue;
        sum += atlas.area[s] / double(k * k) * ci * cs / (kPi * r2);
      }
  }
  return sum;
}

inline double exactIrradiance(const LightmapAtlas& atlas, const RayScene& rays, int shooter, size_t t,
                              int k) {
  return exactIrradianceAt(atlas, rays, shooter, atlas.position[t], atlas.normal[t], k);
}

/// The mean of exactIrradiance over m × m points of receiver texel t (its whole parallelogram).
inline double exactTexelIrradiance(const LightmapAtlas& atlas, const RayScene& rays, int shooter, size_t t,
                                   int k, int m) {
  const Patch& rp = atlas.patches[size_t(atlas.patch[t])];
  double sum = 0.0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const glm::vec3 x = atlas.position[t] + ((float(i) + 0.5f) / float(m) - 0.5f) * rp.texelU +
                          ((float(j) + 0.5f) / float(m) - 0.5f) * rp.texelV;
      sum += exactIrradianceAt(atlas, rays, shooter, x, atlas.normal[t], k);
    }
  return sum / double(m * m);
}

}  // namespace cpgi::testing
