// Noise against time of the reference path tracer on the seed scenes (design.md §4): for every scene,
// resolution and spp, one line with texels, rays, seconds, rays per second, and the relative standard
// error with and without the lamps' texels (the floor a comparison against this reference can resolve).
// Usage: cpgi_reference_bench [--scenes 1,2,3] [--res 0] [--spp 64,256,1024]
//   (res 0 = the default density of 10 texels/m, N > 0 = N×N texels per quad)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/quads.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/reference/reference_tracer.h"
#include "scenes/seed_scenes.h"

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes = {"1", "2", "3"}, resolutions = {"0"}, spps = {"64", "256", "1024"};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--scenes")
      scenes = split(value);
    else if (key == "--res")
      resolutions = split(value);
    else if (key == "--spp")
      spps = split(value);
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 1;
    }
  }
  std::printf("scene res  texels   spp        rays  seconds  Mrays/s  noise%%  noise_nonemissive%%\n");
  for (const std::string& s : scenes) {
    const cpgi::SeedScene seed = cpgi::makeSeedScene(std::atoi(s.c_str()));
    const cpgi::QuadSet quads = cpgi::findQuads(seed.scene);
    for (const std::string& res : resolutions) {
      cpgi::AtlasParams atlasParams;
      atlasParams.texelsPerQuad = std::atoi(res.c_str());
      cpgi::Context ctx;
      const cpgi::LightmapAtlas atlas = cpgi::buildAtlas(seed.scene, quads, atlasParams, ctx);
      std::vector<float> reflectorArea = atlas.area;
      for (size_t i = 0; i < atlas.texelCount(); ++i)
        if (atlas.emission[i] != glm::vec3(0.0f)) reflectorArea[i] = 0.0f;
      for (const std::string& spp : spps) {
        cpgi::ReferenceParams params;
        params.spp = std::atoi(spp.c_str());
        const auto start = std::chrono::steady_clock::now();
        const cpgi::ReferenceResult r = cpgi::traceReference(seed.scene, atlas, params, ctx);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%5s %3s %7zu %5d %11llu %8.2f %8.2f %7.3f %18.3f\n", s.c_str(), res.c_str(),
                    atlas.validTexels(), r.spp, static_cast<unsigned long long>(r.rays), seconds,
                    r.rays / seconds / 1e6, 100.0 * cpgi::relativeStandardError(r, atlas.area),
                    100.0 * cpgi::relativeStandardError(r, reflectorArea));
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
