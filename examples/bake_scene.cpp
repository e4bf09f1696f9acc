// Bakes a scene through the cpgi library, as `cpgi bake SCENE -o DIR` does: loads it, bakes it at the
// command line's defaults, and writes the result set (lightmap.exr/.png, baked.glb, report.json,
// report.html, view-*.png) into DIR. Built against the installed package: find_package(cpgi), cpgi::cpgi.
//
//   bake_scene SCENE DIR [TEXELS_PER_METRE]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "radiosity/bake/bake.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: bake_scene SCENE DIR [TEXELS_PER_METRE]\n");
    return 1;
  }
  cpgi::BakeSettings settings;  // the defaults of `cpgi bake`
  settings.input.scene = argv[1];
  settings.output.folder = argv[2];
  if (argc == 4) {  // a fixed resolution instead of texels where the light varies
    settings.atlas.densityAuto = false;
    settings.atlas.params.density = std::strtof(argv[3], nullptr);
  }
  cpgi::Context ctx;
  try {
    // Load first: the scene's own cells and its numbers are there to look at before the bake.
    const cpgi::BakeScene scene = cpgi::loadBakeScene(settings, ctx);
    std::printf("%s: %zu triangles, %zu cells\n", argv[1], scene.loaded.scene.triangles.size(),
                scene.graph.cells.size());
    const cpgi::BakeResult result = cpgi::bake(scene.loaded.scene, scene.graph, settings, ctx);
    std::printf("%s: %zu texels, %d shots, unshot %.2f %%, %.1f s\n", argv[2], result.atlas.validTexels(),
                result.shots, result.unshotFraction * 100.0, result.seconds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bake_scene: %s\n", e.what());
    return 1;
  }
  for (const std::string& warning : ctx.warnings()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  return 0;
}
