#include "radiosity/solve/auto_density.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "radiosity/lightmap/atlas_size.h"
#include "radiosity/lightmap/contact_density.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/solve/refined_lamp_shot.h"

namespace cpgi {

std::vector<float> chooseAutoDensity(const Scene& scene, const QuadSet& quads, const AtlasParams& atlasParams,
                                     const AutoDensityParams& params, const SolverParams& settings,
                                     ShotEngine& engine, Context& ctx, const SolveControls& controls,
                                     AutoDensityData* data) {
  const auto start = std::chrono::steady_clock::now();
  AtlasParams pilotParams = atlasParams;
  pilotParams.texelsPerQuad = 0;
  pilotParams.density = pilotDensity(scene, params);
  pilotParams.triangleDensity.clear();
  // The area's estimate misses the charts' borders and the texels a thin chart touches (OpenArena's
  // aggressor: 768 k valid texels where its 4 578 m² at 7.4 a metre make 250 k), so the built atlas is
  // fitted to the budget too.
  const LightmapAtlas pilot =
      fitTexelBudget(scene, quads, pilotParams,
                     params.maxTexels > 0 ? size_t(kPilotTexelShare * double(params.maxTexels)) : 0, ctx);
  // The direct light alone: what bounces is smooth but for the contacts, found by rays below. On the GL
  // engine through its item buffers, coarse and then refined where the light varies, whatever lampRays
  // says: the pilot only places texels, and shadow rays at every pilot texel cost more than it does.
  SolverParams pilotSettings = settings;
  pilotSettings.lampRays = 0;
  const SolveResult lit = shootLampsRefined(scene, quads, pilot, pilotParams, RefinedLampParams{},
                                            pilotSettings, engine, ctx, controls);
  std::vector<float> density = lightDensity(pilot, lit.incident, scene.triangles.size(), params.light);
  size_t contactTriangles = 0;
  // Past the deadline the contacts' rays (every texel of the pilot) are left out: the light's density stands.
  if (params.contacts && std::chrono::steady_clock::now() < controls.deadline) {
    // A contact's edge in the bounced light is sharp (a lamp 1 cm under a ceiling: 200 texels a metre
    // by the gap), but weaker than a lamp's shadow: asked of the whole 4 × 4 m ceiling of seed1's lamp
    // rooms, the light's 40 a metre were 88 % of the output's texels. params.maxContactDensity caps it.
    std::vector<float> most(density.size(), 0.0f);
    for (size_t t = 0; t < density.size(); ++t)
      if (density[t] > 0.0f) most[t] = std::min(params.light.maxDensity, params.maxContactDensity);
    const std::vector<float> contact = contactDensity(scene, RayScene(scene), params.light.minDensity, most);
    for (size_t t = 0; t < density.size(); ++t)
      if (contact[t] > density[t] && density[t] > 0.0f) {
        density[t] = contact[t];
        ++contactTriangles;
      }
  }
  evenOverSurfaces(scene, density);
  // A triangle the pilot charted no texel of (zero area: a face cut at a contact can leave one, which
  // every atlas leaves out) still needs a density the output's atlas accepts.
  for (float& d : density)
    if (!(d > 0.0f)) d = params.light.minDensity;
  if (data)
    *data = {pilot.validTexels(), pilotParams.density,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
             contactTriangles};
  return density;
}

float pilotDensity(const Scene& scene, const AutoDensityParams& params) {
  if (params.maxTexels == 0) return params.pilotDensity;
  double area = 0.0;
  for (const Triangle& t : scene.triangles) area += t.area();
  if (!(area > 0.0)) return params.pilotDensity;
  const double budget = double(params.maxTexels) * kPilotTexelShare;
  return float(std::min(double(params.pilotDensity), std::sqrt(budget / area)));
}

double texelsByArea(const Scene& scene, const std::vector<float>& density, float uniform) {
  double texels = 0.0;
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    const double d = density.empty() ? uniform : density[t];
    texels += double(scene.triangles[t].area()) * d * d;
  }
  return texels;
}

LightmapAtlas fitTexelBudget(const Scene& scene, const QuadSet& quads, AtlasParams& params, size_t maxTexels,
                             Context& ctx, TexelBudget* budget,
                             std::chrono::steady_clock::time_point deadline) {
  TexelBudget b;
  auto scaled = [&](double factor) {
    if (params.triangleDensity.empty()) params.density *= float(factor);
    for (float& d : params.triangleDensity) d *= float(factor);
    b.scale *= float(factor);
  };
  const double byArea = texelsByArea(scene, params.triangleDensity, params.density);
  b.asked = size_t(byArea);
  const bool fitted = maxTexels > 0 && params.texelsPerQuad == 0;
  // From the area first: an atlas of the densities asked may be too large to build (a house's 2.96 M).
  if (fitted && byArea > double(maxTexels)) scaled(std::sqrt(double(maxTexels) / byArea));
  // Then by the charts (measureAtlas): their borders, rounding and grids at their quads' largest density
  // add texels the area does not count (oa_dm2: 9.0 M valid texels where the area said 1.09 M). Filled at
  // each scale tried, that first layout's 19.5 M texels and their gutters made a map's peak (2.4-4.9 GB
  // for a bake that then solved in 1.2 GB); measured, the atlas is filled once, at the scale that fits.
  if (fitted) {
    size_t valid = measureAtlas(scene, quads, params).validTexels;
    if (b.scale == 1.0f) b.asked = valid;
    for (int tries = 0; valid > maxTexels && tries < 4; ++tries) {
      scaled(0.98 * std::sqrt(double(maxTexels) / double(valid)));
      valid = measureAtlas(scene, quads, params).validTexels;
    }
  }
  // Each layout's warnings (a chart capped at its most texels) are the last one's alone, said once.
  Context layout;
  LightmapAtlas atlas = buildAtlas(scene, quads, params, layout, {}, deadline);
  if (!fitted && b.scale == 1.0f) b.asked = atlas.validTexels();
  // A line the bake's context holds already (the same triangles left out by an earlier layout) is not
  // said twice.
  for (const std::string& w : layout.warnings())
    if (std::find(ctx.warnings().begin(), ctx.warnings().end(), w) == ctx.warnings().end()) ctx.warn(w);
  if (b.scale < 1.0f) {
    char line[240];
    std::snprintf(line, sizeof line,
                  "atlas: the light asked for about %zu texels, over the budget of %zu (--max-texels): every "
                  "surface's texels per metre scaled by %.2f, %zu texels",
                  b.asked, maxTexels, b.scale, atlas.validTexels());
    b.note = line;
  }
  if (budget) *budget = b;
  return atlas;
}

}  // namespace cpgi
