// Times the GPU solver on the seed scenes (design.md §4) for every resolution and visibility mode and
// prints one line per run: seconds (setup + shots + read back), shots, texels, unshot fraction,
// energy escaped. Usage: cpgi_solver_bench [--scenes 1,2,3] [--res 16,32,64,128,0] [--vis hemicube,hemisphere]
//   [--unshot F] [--max-shots N] [--item-buffer N] [--min-texels N] [--cull 0|1]   (res 0 = the default density of 10 texels/m, dT = T texels/m)
//   A scene is a seed number or a .glb/.gltf/.obj file (loaded as `cpgi bake` loads it).
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/gpu/gl_shot_engine.h"
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
  std::vector<std::string> scenes = {"1", "2", "3"}, resolutions = {"16", "32", "64", "128", "0"},
                           modes = {"hemicube", "hemisphere"};
  cpgi::SolverParams base;
  int minTexels = cpgi::AtlasParams{}.minTexels;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--scenes") scenes = split(value);
    else if (key == "--res") resolutions = split(value);
    else if (key == "--vis") modes = split(value);
    else if (key == "--unshot") base.unshotFraction = std::atof(value.c_str());
    else if (key == "--max-shots") base.maxShots = std::atoi(value.c_str());
    else if (key == "--item-buffer") base.itemBuffer = std::atoi(value.c_str());
    else if (key == "--far-field") base.farField = float(std::atof(value.c_str()));
    else if (key == "--regions") base.maxRegions = std::atoi(value.c_str());
    else if (key == "--neighbourhood") base.neighbourhood = std::atoi(value.c_str());
    else if (key == "--profile") base.profilePasses = value == "1";
    else if (key == "--cull") base.cullItemBuffers = value == "1";
    else if (key == "--min-texels") minTexels = std::atoi(value.c_str());
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 1;
    }
  }
  cpgi::Context ctx;
  cpgi::EglContext gl(ctx);
  std::printf("# renderer: %s\n", gl.renderer().c_str());
  std::printf("scene\tres\tvisibility\ttexels\tatlas\tshots\tunshot\tescaped\tsetup_s\tsolve_s\tms_per_shot\n");
  for (const std::string& s : scenes) {
    const bool file = s.find('.') != std::string::npos;
    cpgi::SeedScene seed;
    if (file)
      seed.scene = cpgi::loadScene(s).scene;
    else
      seed = cpgi::makeSeedScene(std::atoi(s.c_str()));
    const cpgi::QuadSet quads = cpgi::findQuads(seed.scene);
    for (const std::string& r : resolutions) {
      cpgi::AtlasParams ap;
      ap.minTexels = minTexels;
      // "dT": a density of T texels per metre instead of texels per quad.
      if (!r.empty() && r[0] == 'd')
        ap.density = float(std::atof(r.c_str() + 1));
      else
        ap.texelsPerQuad = std::atoi(r.c_str());
      const cpgi::LightmapAtlas atlas = cpgi::buildAtlas(seed.scene, quads, ap, ctx);
      for (const std::string& m : modes) {
        cpgi::SolverParams p = base;
        p.visibility = m == "hemisphere" ? cpgi::Visibility::Hemisphere : cpgi::Visibility::Hemicube;
        cpgi::Context run;
        const cpgi::SolveResult res = cpgi::solveProgressive(seed.scene, atlas, p, gl, run);
        const double shotSeconds = res.seconds - res.setupSeconds;
        std::printf("%s%s\t%s\t%s\t%zu\t%dx%d\t%d\t%.4f\t%.4f\t%.2f\t%.2f\t%.1f\n", file ? "" : "seed", s.c_str(),
                    r == "0" ? "density10" : r[0] == 'd' ? ("density" + r.substr(1)).c_str() : (r + "^2").c_str(), m.c_str(), atlas.validTexels(), atlas.width,
                    atlas.height, res.shots, res.unshotFraction,
                    res.energy.emitted > 0 ? res.energy.escaped() / res.energy.emitted : 0.0, res.setupSeconds,
                    res.seconds, res.shots ? 1000.0 * shotSeconds / res.shots : 0.0);
        if (p.profilePasses)
          for (const auto& t : run.timings()) std::printf("#   %-24s %.3f s\n", t.stage.c_str(), t.seconds);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
