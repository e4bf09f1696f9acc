// The interreflection's atlas of a two-level bake (radiosity/solve/two_level_solve.h) against the output's:
// its texels without and with the contacts' refinement (radiosity/lightmap/contact_density.h), and how they
// fall into charts by size. Every shot of the interreflection visits every one of these texels, so they
// set its cost per shot. The output here has one density everywhere (a --density auto output is finer at
// its contacts and shadows, which lets the contacts refine as far as maxContactDensity).
// Usage: cpgi_solve_texels_probe SCENE [OUTPUT_DENSITY=10] [MAX_CONTACT_DENSITY=20]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/contact_density.h"
#include "radiosity/lightmap/ray_scene.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [OUTPUT_DENSITY=10] [MAX_CONTACT_DENSITY=20]\n", argv[0]);
    return 1;
  }
  using namespace cpgi;
  Context ctx;
  const LoadedScene loaded = loadScene(argv[1]);
  const Scene& scene = loaded.scene;
  const float outputDensity = argc > 2 ? float(std::atof(argv[2])) : 10.0f;
  const float maxContact = argc > 3 ? float(std::atof(argv[3])) : 20.0f;
  constexpr float kSolveDensity = 5.0f;  // the two-level bake's at --density auto
  const QuadSet quads = findQuads(scene);
  AtlasParams out;
  out.density = outputDensity;
  const LightmapAtlas atlas = buildAtlas(scene, quads, out, ctx);
  std::printf("output at %.1f a metre: %zu texels, %zu charts\n", outputDensity, atlas.validTexels(),
              atlas.patches.size());
  AtlasParams coarse = out;
  coarse.density = kSolveDensity;
  coarse.minTexels = 1;
  const LightmapAtlas plain = buildAtlas(scene, quads, coarse, ctx);
  std::printf("solve atlas, no contacts: %zu texels\n", plain.validTexels());
  std::vector<float> fine = cpgi::outputDensity(atlas, scene.triangles.size());
  for (float& d : fine) d = std::min(d, std::max(maxContact, kSolveDensity));
  coarse.triangleDensity = contactDensity(scene, RayScene(scene), kSolveDensity, fine);
  size_t refined = 0;
  for (float d : coarse.triangleDensity) refined += d > kSolveDensity;
  const LightmapAtlas solve = buildAtlas(scene, quads, coarse, ctx);
  std::printf("solve atlas, contacts up to %.1f: %zu texels, %zu triangles refined\n", maxContact,
              solve.validTexels(), refined);
  std::vector<size_t> perChart(solve.patches.size(), 0);
  for (size_t t = 0; t < solve.texelCount(); ++t)
    if (solve.patch[t] >= 0) ++perChart[size_t(solve.patch[t])];
  std::map<size_t, std::pair<size_t, size_t>> bySize;  // up to N texels: charts, texels
  for (size_t n : perChart) {
    size_t bound = 1;
    while (bound < n) bound *= 4;
    bySize[bound].first += 1, bySize[bound].second += n;
  }
  for (const auto& [bound, v] : bySize)
    std::printf("  charts of up to %zu texels: %zu charts, %zu texels\n", bound, v.first, v.second);
  return 0;
}
