#include "radiosity/solve/auto_density.h"

#include <algorithm>
#include <chrono>

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
  pilotParams.density = params.pilotDensity;
  pilotParams.triangleDensity.clear();
  const LightmapAtlas pilot = buildAtlas(scene, quads, pilotParams, ctx);
  // The direct light alone: what bounces is smooth but for the contacts, found by rays below.
  const SolveResult lit = shootLampsRefined(scene, quads, pilot, pilotParams, RefinedLampParams{}, settings,
                                            engine, ctx, controls);
  std::vector<float> density = lightDensity(pilot, lit.incident, scene.triangles.size(), params.light);
  size_t contactTriangles = 0;
  if (params.contacts) {
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
  if (data)
    *data = {pilot.validTexels(),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
             contactTriangles};
  return density;
}

}  // namespace cpgi
