// The lamps' first shot by rays with and without the cull of texels hidden behind one occluder piece
// (radiosity/lightmap/lamp_light.h, LampCull): CPU and wall seconds, rays traced, texels × lamps found
// hidden, and whether the two irradiances are the same to the bit.
//
//   cpgi_lamp_cull_bench SCENE [--density D] [--rays N] [--only cull|all]
//
// SCENE is a .glb/.gltf/.obj in metres; the atlas is laid out at D texels per metre (default 8: the
// 108-room office's --density auto bake holds 543 274 texels, this 548 thousand), N rays per texel and
// lamp (default 64, a bake's on the CPU).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/lamp_light.h"
#include "radiosity/lightmap/ray_scene.h"

namespace {

struct Run {
  cpgi::LampLight light;
  double cpu = 0.0, wall = 0.0;
};

cpgi::LampLight shoot(const cpgi::Scene& scene, const cpgi::RayScene& rays, const cpgi::LightmapAtlas& atlas,
                      int count, cpgi::LampCull cull, Run& run) {
  cpgi::Context ctx;
  const std::clock_t cpu = std::clock();
  const auto wall = std::chrono::steady_clock::now();
  run.light = cpgi::shootLampsByRays(scene, rays, atlas, cpgi::lampPatches(scene, atlas), count, ctx,
                                     std::chrono::steady_clock::time_point::max(), cull);
  run.cpu = double(std::clock() - cpu) / CLOCKS_PER_SEC;
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  return run.light;
}

void print(const char* name, const Run& r) {
  std::printf(
      "%-6s cpu %7.2f s  wall %7.2f s  rays %11llu  texels x lamps: culled %10llu, traced and all hidden "
      "%10llu  landed %.9g W\n",
      name, r.cpu, r.wall, static_cast<unsigned long long>(r.light.rays),
      static_cast<unsigned long long>(r.light.hiddenTexels),
      static_cast<unsigned long long>(r.light.tracedHiddenTexels), r.light.landed);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: cpgi_lamp_cull_bench SCENE [--density D] [--rays N] [--only cull|all]\n");
    return 1;
  }
  float density = 8.0f;
  int count = 64;
  std::string only;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--density")) density = std::strtof(argv[i + 1], nullptr);
    if (!std::strcmp(argv[i], "--rays")) count = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--only")) only = argv[i + 1];
  }
  try {
    const cpgi::LoadedScene loaded = cpgi::loadScene(argv[1]);
    cpgi::Context ctx;
    const cpgi::LightmapAtlas atlas = cpgi::buildAtlas(loaded.scene, cpgi::findQuads(loaded.scene),
                                                       cpgi::AtlasParams{.density = density}, ctx);
    const cpgi::RayScene rays(loaded.scene);
    std::printf("%s: %zu triangles, %zu texels at %.2f a metre, %d rays\n", argv[1],
                loaded.scene.triangles.size(), atlas.validTexels(), double(density), count);
    Run culled, all;
    if (only != "all") {
      shoot(loaded.scene, rays, atlas, count, cpgi::LampCull::Occluders, culled);
      print("cull", culled);
    }
    if (only != "cull") {
      shoot(loaded.scene, rays, atlas, count, cpgi::LampCull::None, all);
      print("all", all);
    }
    if (only.empty()) {
      size_t differ = 0;
      for (size_t t = 0; t < all.light.irradiance.size(); ++t)
        differ += all.light.irradiance[t] != culled.light.irradiance[t];
      std::printf("texels that differ: %zu; CPU ratio all/cull %.2f\n", differ, all.cpu / culled.cpu);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 1;
  }
  return 0;
}
