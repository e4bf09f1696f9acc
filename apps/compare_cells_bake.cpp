#include "apps/compare_cells_bake.h"

#include "apps/compare_light_cells.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/quads.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/lightmap/finite_result.h"
#include "radiosity/metrics/cell_metrics.h"
#include "radiosity/metrics/metrics.h"
#include "radiosity/solve/ambient.h"

namespace cpgi::cli {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

LightmapAtlas atlasOf(const CellsToBake& cells, const AtlasParams& params, Context& ctx) {
  const QuadSet quads = findQuads(cells.scene);
  LightmapAtlas atlas = buildAtlas(cells.scene, quads, params, ctx);
  if (atlas.patches.empty()) throw InputError(cells.source, "no surface to bake");
  return atlas;
}

// Texel for texel the same layout: then one reference serves both bakes.
bool sameAtlas(const LightmapAtlas& x, const LightmapAtlas& y) {
  return x.width == y.width && x.height == y.height && x.patch == y.patch && x.position == y.position &&
         x.area == y.area;
}

// The texel areas without the lamps: their B (≈ E, e.g. 100 W/m²) would otherwise dominate Σ a|R|², and
// the decompositions differ in how light reaches the other surfaces (as `cpgi reference` does).
std::vector<float> nonEmissiveArea(const LightmapAtlas& atlas) {
  std::vector<float> area = atlas.area;
  const std::vector<float> lamp = emissiveMask(atlas);
  for (size_t i = 0; i < area.size(); ++i)
    if (lamp[i] > 0.0f) area[i] = 0.0f;
  return area;
}

struct Reference {
  ReferenceResult result;
  std::vector<float> nonEmissive;
  nlohmann::json report;
};

Reference trace(const std::string& scene, const CellsToBake& cells, const LightmapAtlas& atlas,
                const ReferenceParams& params, Context& ctx) {
  const Clock::time_point start = Clock::now();
  Reference r;
  r.result = traceReference(cells.scene, atlas, params, ctx);
  requireFiniteResult(scene, atlas, r.result.radiosity);
  r.nonEmissive = nonEmissiveArea(atlas);
  r.report = {{"scene_of", cells.source},
              {"texels", atlas.validTexels()},
              {"seconds", secondsSince(start)},
              {"spp", r.result.spp},
              {"noise", relativeStandardError(r.result, atlas.area)},
              {"noise_nonemissive", relativeStandardError(r.result, r.nonEmissive)}};
  return r;
}

nlohmann::json bake(const std::string& scene, const CellsToBake& cells, const LightmapAtlas& atlas,
                    const CellBakeComparison& params, ShotEngine& engine, Context& ctx,
                    std::vector<glm::vec3>& radiosity) {
  CellSolveParams solve;
  solve.solver = params.solver;
  solve.atlas = params.atlas;
  solve.maxRounds = params.maxRounds;
  solve.portals = params.portals;
  solve.maxAmbientShare = kDefaultAmbientShare;  // `cpgi bake`'s stop per cell
  const Clock::time_point start = Clock::now();
  SolveResult solved = solveCells(cells.scene, cells.graph, atlas, solve, engine, ctx);
  // As `cpgi bake` does: the ambient term for what the stop left unshot (radiosity/solve/ambient.h).
  addAmbient(atlas, solved.residual, glm::dvec3(solved.energy.unshot / 3.0),
             cellChannel(atlas, cells.scene, cells.graph).values, cells.graph, solved.radiosity);
  const double seconds = secondsSince(start);
  const std::pair<const char*, double> totals[] = {
      {"emitted", solved.energy.emitted}, {"shot", solved.energy.shot}, {"unshot", solved.energy.unshot}};
  requireFiniteResult(scene, atlas, solved.radiosity, totals);
  radiosity = std::move(solved.radiosity);
  return {{"source", cells.source},
          {"cells", cells.graph.cells.size()},
          {"portals", cells.graph.portals.size()},
          {"texels", atlas.validTexels()},
          {"seconds", seconds},
          {"solve_seconds", solved.seconds},
          {"shots", solved.shots},
          {"rounds", solved.perCell->rounds},
          {"unshot_fraction", solved.unshotFraction},
          {"max_cell_texels", solved.perCell->maxCellTexels}};
}

// Each cell of the side's own graph against the reference (radiosity/metrics/cell_metrics.h), lamps left
// out as in the whole figures: the room lit through doors is the one a whole figure cannot see.
void addCellErrors(nlohmann::json& side, const std::vector<glm::vec3>& radiosity, const LightmapAtlas& atlas,
                   const CellsToBake& cells, const Reference& ref) {
  std::vector<float> sigma(atlas.texelCount());
  for (size_t i = 0; i < sigma.size(); ++i) sigma[i] = glm::length(ref.result.standardError[i]);
  const ExrChannel cell = cellChannel(atlas, cells.scene, cells.graph);
  const std::vector<CellError> errors =
      compareCells(radiosity, ref.result.radiosity, ref.nonEmissive, sigma, cell.values, {},
                   atlas.validTexels(), cellNames(cells.graph));
  side["cells_error"] = cellsJson(errors);  // as compare-light --json gives them
  const std::optional<size_t> worst = worstCell(errors);
  side["worst_cell"] = worst ? nlohmann::json(errors[*worst].name) : nlohmann::json(nullptr);
}

void addErrors(nlohmann::json& side, const std::vector<glm::vec3>& radiosity, const LightmapAtlas& atlas,
               const Reference& ref, int refIndex) {
  const LightmapError all = compareLightmaps(radiosity, ref.result.radiosity, atlas.area);
  const LightmapError reflectors = compareLightmaps(radiosity, ref.result.radiosity, ref.nonEmissive);
  side["rel_rmse"] = all.relRmse;
  side["rel_mean_error"] = all.relMeanError;
  side["rel_rmse_nonemissive"] = reflectors.relRmse;
  side["rel_mean_error_nonemissive"] = reflectors.relMeanError;
  side["reference"] = refIndex;
  side["reference_noise"] = ref.report["noise"];
  side["reference_noise_nonemissive"] = ref.report["noise_nonemissive"];
}

// The first number of `j` that is inf or NaN, depth first in the order the keys were written, with its
// path below `path` ("a.rel_rmse_nonemissive").
std::optional<std::pair<std::string, double>> firstNonFinite(const nlohmann::json& j,
                                                             const std::string& path) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return std::pair{path, j.get<double>()};
  if (!j.is_structured()) return std::nullopt;
  size_t index = 0;
  for (auto it = j.begin(); it != j.end(); ++it, ++index) {
    const std::string key = j.is_object() ? it.key() : std::to_string(index);
    if (auto found = firstNonFinite(*it, path.empty() ? key : path + "." + key)) return found;
  }
  return std::nullopt;
}

}  // namespace

void requireFiniteFigures(const std::string& scene, const nlohmann::json& figures) {
  const auto bad = firstNonFinite(figures, "");
  if (!bad) return;
  throw InputError(scene,
                   "the bake's figure " + bad->first + " is " + (std::isnan(bad->second) ? "NaN" : "inf") +
                       ", not a measurement (a relative error over texels the reference left dark?); no "
                       "figures given");
}

nlohmann::json compareCellBakes(const std::string& scene, const CellsToBake& a, const CellsToBake& b,
                                const CellBakeComparison& params, Context& ctx) {
  const LightmapAtlas atlasA = atlasOf(a, params.atlas, ctx), atlasB = atlasOf(b, params.atlas, ctx);
  const bool shared = sameAtlas(atlasA, atlasB);
  const auto gl = std::make_unique<EglContext>(ctx);

  std::vector<glm::vec3> radiosityA, radiosityB;
  GlShotEngine engine(*gl);
  nlohmann::json sideA = bake(scene, a, atlasA, params, engine, ctx, radiosityA);
  nlohmann::json sideB = bake(scene, b, atlasB, params, engine, ctx, radiosityB);

  const Reference refA = trace(scene, a, atlasA, params.reference, ctx);
  nlohmann::json references = nlohmann::json::array({refA.report});
  addErrors(sideA, radiosityA, atlasA, refA, 0);
  addCellErrors(sideA, radiosityA, atlasA, a, refA);
  if (shared) {
    addErrors(sideB, radiosityB, atlasB, refA, 0);
    addCellErrors(sideB, radiosityB, atlasB, b, refA);
  } else {
    const Reference refB = trace(scene, b, atlasB, params.reference, ctx);
    references.push_back(refB.report);
    addErrors(sideB, radiosityB, atlasB, refB, 1);
    addCellErrors(sideB, radiosityB, atlasB, b, refB);
  }

  nlohmann::json out = {{"texels_per_quad", params.atlas.texelsPerQuad},
                        {"density", params.atlas.texelsPerQuad > 0 ? 0.0f : params.atlas.density},
                        {"unshot_target", params.solver.unshotFraction},
                        {"item_buffer", params.solver.itemBuffer},
                        {"visibility", visibilityName(params.solver.visibility)},
                        {"portals", portalLightName(params.portals)},
                        {"renderer", gl->renderer()},
                        {"same_atlas", shared},
                        {"references", references},
                        {"a", sideA},
                        {"b", sideB}};
  out["difference_points"] = {
      {"rel_rmse", 100.0 * (sideA["rel_rmse"].get<double>() - sideB["rel_rmse"].get<double>())},
      {"rel_rmse_nonemissive",
       100.0 * (sideA["rel_rmse_nonemissive"].get<double>() - sideB["rel_rmse_nonemissive"].get<double>())}};
  requireFiniteFigures(scene, out);
  return out;
}

void printCellBakes(const nlohmann::json& bake) {
  const int tpq = bake["texels_per_quad"].get<int>();
  if (tpq > 0)
    std::printf("bake: %dx%d texels per quad", tpq, tpq);
  else
    std::printf("bake: %g texels per metre", bake["density"].get<double>());
  std::printf(", unshot %g, --method cells, %s portals, %s\n", bake["unshot_target"].get<double>(),
              bake["portals"].get<std::string>().c_str(), bake["renderer"].get<std::string>().c_str());
  for (const auto& r : bake["references"])
    std::printf("reference on %s's atlas: %zu texels, %d spp, %.1f s, noise %.3f%% (%.3f%% without lamps)\n",
                r["scene_of"].get<std::string>().c_str(), r["texels"].get<size_t>(), r["spp"].get<int>(),
                r["seconds"].get<double>(), 100.0 * r["noise"].get<double>(),
                100.0 * r["noise_nonemissive"].get<double>());
  if (!bake["same_atlas"].get<bool>())
    std::printf(
        "(the scenes differ, e.g. triangles split on portal planes: each bake has its own reference)\n");
  for (const char* key : {"a", "b"}) {
    const auto& s = bake[key];
    std::printf(
        "  %s %-24s %d cells  %7.2f s  %6d shots  %2d rounds  rel RMSE %.3f%% (%.3f%% without lamps)\n",
        key[0] == 'a' ? "A" : "B", s["source"].get<std::string>().c_str(), s["cells"].get<int>(),
        s["seconds"].get<double>(), s["shots"].get<int>(), s["rounds"].get<int>(),
        100.0 * s["rel_rmse"].get<double>(), 100.0 * s["rel_rmse_nonemissive"].get<double>());
    std::printf("    per cell (without lamps), ratio of means and rel RMSE:");
    for (const auto& c : s["cells_error"]) {
      if (c["ratio_of_means"].is_null()) continue;
      std::printf(" %s %.3f (%.1f%%)%s", c["name"].get<std::string>().c_str(),
                  c["ratio_of_means"].get<double>(), 100.0 * c["rel_rmse"].get<double>(),
                  c["name"] == s["worst_cell"] ? " <- worst" : "");
    }
    std::printf("\n");
  }
  const auto& d = bake["difference_points"];
  std::printf("  A - B: %+.3f points of rel RMSE (%+.3f without lamps)\n", d["rel_rmse"].get<double>(),
              d["rel_rmse_nonemissive"].get<double>());
}

}  // namespace cpgi::cli
