#include "radiosity/lightmap/directional_lightmap.h"

#include <atomic>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/spherical_harmonics.h"

namespace cpgi {
namespace {

// One texel's S = ∫ L dω and V = ∫ L ω dω per channel from its samples, scaled per channel so that V · n
// is the solve's irradiance `e`. A channel the gather found no light in (the solve did) gets it all from
// the normal: V = e n, S = e. Returns how many channels that was.
int texelCoefficients(const std::vector<ArrivalSample>& samples, const glm::vec3& n, const glm::vec3& e,
                      std::array<glm::vec3, 4>& sh, glm::vec3& gathered) {
  glm::vec3 s(0.0f);
  std::array<glm::vec3, 3> v{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};  // [channel] = V
  for (const ArrivalSample& a : samples) {
    s += a.light;
    for (int c = 0; c < 3; ++c) v[size_t(c)] += a.light[c] * a.towards;
  }
  int undirected = 0;
  for (int c = 0; c < 3; ++c) {
    glm::vec3& vc = v[size_t(c)];
    const float found = glm::dot(vc, n);
    gathered[c] = found;
    if (found > 1e-6f * e[c] && found > 0.0f) {
      const float scale = e[c] / found;
      vc *= scale, s[c] *= scale;
    } else {
      undirected += e[c] > 0.0f;
      vc = e[c] * n, s[c] = e[c];
    }
    sh[0][c] = kShY00 * s[c];
    sh[1][c] = kShY1 * vc.y;
    sh[2][c] = kShY1 * vc.z;
    sh[3][c] = kShY1 * vc.x;
  }
  return undirected;
}

}  // namespace

DirectionalLightmap gatherDirectionalLightmap(const Scene& scene, const LightmapAtlas& atlas,
                                              const std::vector<glm::vec3>& radiosity,
                                              const std::vector<glm::vec3>& irradiance,
                                              const GatherParams& params, Context& ctx,
                                              std::chrono::steady_clock::time_point deadline) {
  auto timer = ctx.time("directional lightmap");
  const auto start = std::chrono::steady_clock::now();
  DirectionalLightmap map;
  for (auto& c : map.sh) c.assign(atlas.texelCount(), glm::vec3(0.0f));
  map.gathered.assign(atlas.texelCount(), glm::vec3(0.0f));
  if (std::chrono::steady_clock::now() >= deadline) {  // not even the ray scene's set-up
    map.complete = false;
    return map;
  }
  const RayScene rays(scene);
  const BakedRadiance baked(scene, rays, atlas, radiosity);
  std::atomic<size_t> texels{0}, undirected{0};
  std::atomic<bool> stopped{false};
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, atlas.texelCount(), 64), [&](const tbb::blocked_range<size_t>& r) {
        std::vector<ArrivalSample> samples;
        size_t count = 0, lost = 0;
        for (size_t i = r.begin(); i < r.end(); ++i) {
          if ((i - r.begin()) % 64 == 0 && (stopped || std::chrono::steady_clock::now() >= deadline)) {
            stopped = true;
            break;
          }
          if (atlas.patch[i] < 0) continue;
          baked.gather(atlas.position[i], atlas.normal[i], uint64_t(i), params, samples);
          std::array<glm::vec3, 4> sh;
          lost += size_t(texelCoefficients(samples, atlas.normal[i], irradiance[i], sh, map.gathered[i]));
          for (size_t k = 0; k < 4; ++k) map.sh[k][i] = sh[k];
          ++count;
        }
        texels += count, undirected += lost;
      });
  map.texels = texels, map.undirected = undirected;
  map.complete = !stopped;
  map.rays = baked.raysTraced();
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

std::array<glm::vec3, 4> texelSh(const DirectionalLightmap& map, size_t i) {
  return {map.sh[0][i], map.sh[1][i], map.sh[2][i], map.sh[3][i]};
}

}  // namespace cpgi
