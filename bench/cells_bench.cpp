// Cells solves on a seed scene (design.md §4): where the time goes (per GPU pass, per cell) and what
// on-demand bakes cost and how far they are from the whole cells solve.
// Usage: cpgi_cells_bench [--scene 1|2|3] [--res N] [--unshot F] [--item-buffer N] [--jobs N]
//                         [--profile 0|1] [--on-demand 0|1]
// Prints the whole cells solve (seconds, shots, per-pass totals with --profile 1, per cell), then with
// --on-demand 1 one line per selection (each cell alone with coarse and with dark boundaries, and each
// cell with depth 1): seconds, shots, texels solved, and the area-weighted relative RMSE of the baked
// cells' texels against the whole solve.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "core/quads.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "scenes/seed_scenes.h"

namespace {

double seconds(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  int level = 3, res = 4, itemBuffer = 512, jobs = 1;
  double unshot = 0.05;
  bool profile = false, onDemand = true;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--scene")
      level = std::atoi(value.c_str());
    else if (key == "--res")
      res = std::atoi(value.c_str());
    else if (key == "--unshot")
      unshot = std::atof(value.c_str());
    else if (key == "--item-buffer")
      itemBuffer = std::atoi(value.c_str());
    else if (key == "--jobs")
      jobs = std::atoi(value.c_str());
    else if (key == "--profile")
      profile = value == "1";
    else if (key == "--on-demand")
      onDemand = value == "1";
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 1;
    }
  }
  const cpgi::SeedScene seed = cpgi::makeSeedScene(level);
  cpgi::Context ctx;
  cpgi::EglContext context(ctx);
  cpgi::GlShotEngine gl(context);
  cpgi::CellSolveParams params;
  params.atlas.texelsPerQuad = res;
  params.solver.unshotFraction = unshot;
  params.solver.itemBuffer = itemBuffer;
  params.solver.profilePasses = profile;
  params.jobs = jobs;
  const cpgi::LightmapAtlas atlas =
      cpgi::buildAtlas(seed.scene, cpgi::findQuads(seed.scene), params.atlas, ctx);
  std::printf("# seed%d, %d^2 texels per quad, unshot %g, item buffer %d, jobs %d, renderer %s\n", level, res,
              unshot, itemBuffer, jobs, context.renderer().c_str());

  cpgi::Context wholeCtx;
  auto start = std::chrono::steady_clock::now();
  const cpgi::SolveResult whole = cpgi::solveCells(seed.scene, seed.cells, atlas, params, gl, wholeCtx);
  std::printf("whole cells solve: %.2f s, %d shots, %d rounds, %zu texels\n", seconds(start), whole.shots,
              whole.perCell->rounds, atlas.validTexels());
  std::map<std::string, double> stages;
  for (const auto& t : wholeCtx.timings()) stages[t.stage] += t.seconds;
  for (const auto& [stage, s] : stages) std::printf("#   %-26s %8.3f s\n", stage.c_str(), s);
  for (const cpgi::CellEnergy& c : whole.perCell->cells)
    std::printf("#   cell %-4s %2d solves %5d shots %8zu texels %7.2f s (%.1f ms/shot)\n", c.name.c_str(),
                c.solves, c.shots, c.texels, c.seconds, c.shots ? 1000.0 * c.seconds / c.shots : 0.0);
  if (!onDemand) return 0;

  // Cell of every global texel, for the errors.
  const std::vector<int> cellOfTexel = cpgi::cellOfTexels(atlas, seed.cells, seed.scene.triangles.size());

  std::printf("baked    boundary  mode    seconds  shots  solved_texels  rel_rmse_baked\n");
  auto run = [&](const std::vector<int>& baked, cpgi::BoundaryMode mode) {
    const cpgi::CellSelection sel = cpgi::selectCells(seed.cells, baked);
    cpgi::Context c;
    const auto t0 = std::chrono::steady_clock::now();
    const cpgi::SolveResult r =
        cpgi::solveCellsOnDemand(seed.scene, seed.cells, sel, mode, atlas, params, gl, c);
    const double s = seconds(t0);
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < atlas.texelCount(); ++i) {
      const int cell = cellOfTexel[i];
      if (cell < 0 || std::find(baked.begin(), baked.end(), cell) == baked.end()) continue;
      const glm::dvec3 d = glm::dvec3(r.radiosity[i]) - glm::dvec3(whole.radiosity[i]);
      num += atlas.area[i] * glm::dot(d, d);
      den += atlas.area[i] * glm::dot(glm::dvec3(whole.radiosity[i]), glm::dvec3(whole.radiosity[i]));
    }
    size_t texels = 0;
    for (const cpgi::CellEnergy& e : r.perCell->cells) texels += e.texels;
    auto names = [&](const std::vector<int>& cells) {
      std::string out;
      for (int k : cells) out += (out.empty() ? "" : ",") + seed.cells.cells[k].name;
      return out.empty() ? std::string("-") : out;
    };
    std::printf("%-8s %-9s %-6s %8.2f %6d %14zu %15.4f\n", names(sel.baked).c_str(),
                names(sel.boundary).c_str(), cpgi::boundaryModeName(mode), s, r.shots, texels,
                den > 0.0 ? std::sqrt(num / den) : 0.0);
    std::fflush(stdout);
  };
  for (size_t c = 0; c < seed.cells.cells.size(); ++c) {
    run({int(c)}, cpgi::BoundaryMode::Coarse);
    run({int(c)}, cpgi::BoundaryMode::Dark);
  }
  for (size_t c = 0; c < seed.cells.cells.size(); ++c) {
    const std::vector<int> within = cpgi::cellsWithin(seed.cells, int(c), 1);
    if (within.size() < seed.cells.cells.size()) run(within, cpgi::BoundaryMode::Coarse);
  }
  return 0;
}
