// The irradiance a receiver texel gets from a shooter patch sending 1 W/m² from every texel, by k × k
// points per shooter texel, each seen by its own ray: nothing shared with the rays engine's shots but the
// ray scene. The oracle of the rays engine's tests.
#pragma once

#include <cmath>
#include <cstddef>

#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi::testing {

inline double exactIrradiance(const LightmapAtlas& atlas, const RayScene& rays, int shooter, size_t t,
                              int k) {
  constexpr double kPi = 3.14159265358979323846;
  const Patch& sp = atlas.patches[size_t(shooter)];
  const glm::vec3 x = atlas.position[t], n = atlas.normal[t];
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

}  // namespace cpgi::testing
