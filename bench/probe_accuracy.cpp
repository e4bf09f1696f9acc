// Light probes against the reference path tracer (issue 48 item 5): at every probe of a default bake,
// the irradiance its L2 SH gives a surface facing each of the six axes, against `cpgi reference`'s tracer
// at the same point and normal (a white point, ρ = 1: its B is the irradiance). Per probe, the error is
// the RMS over the six normals of (E_probe − E_ref), over the mean of the six E_ref; listed per room with
// the share of probes within 5 %. Beside it, the same for the probes' own gather summed straight over
// each normal's hemisphere (no SH): what the L2 truncation costs, apart from the gather and the bake.
//
// Usage: cpgi_probe_accuracy [seed1|seed2|seed3] [SPP of the reference]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "radiosity/bake/bake.h"
#include "radiosity/bake/light_probes.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "radiosity/reference/reference_tracer.h"
#include "scenes/seed_scenes.h"

using namespace cpgi;

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "seed1";
  const int spp = argc > 2 ? std::stoi(argv[2]) : 4096;
  const int level = name == "seed3" ? 3 : name == "seed2" ? 2 : 1;
  const SeedScene seed = makeSeedScene(level);
  Context ctx;
  const BakeResult r = bake(seed.scene, seed.cells, BakeSettings{}, ctx);
  const LightProbes probes = gatherLightProbes(seed.scene, seed.cells, r.atlas, r.radiosity, {}, ctx);
  std::printf("%s: %zu probes, gathered in %.2f s (%.2f M rays)\n", name.c_str(), probes.probes.size(),
              probes.seconds, double(probes.rays) * 1e-6);

  const std::array<glm::vec3, 6> axes = {glm::vec3(1, 0, 0),  glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                         glm::vec3(0, -1, 0), glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1)};
  std::vector<SamplePoint> points;
  for (const LightProbe& p : probes.probes)
    for (const glm::vec3& n : axes) points.push_back({p.position, n, glm::vec3(1.0f), glm::vec3(0.0f)});
  ReferenceParams params;
  params.spp = spp;
  params.texelMean = false;
  const ReferenceResult ref = traceReference(seed.scene, points, params, ctx);

  const RayScene rays(seed.scene);
  const BakedRadiance baked(seed.scene, rays, r.atlas, r.radiosity);
  std::map<std::string, std::vector<double>> errors, unprojected;  // per room
  double noise = 0.0, worst = 0.0;
  std::vector<ArrivalSample> samples;
  for (size_t i = 0; i < probes.probes.size(); ++i) {
    const LightProbe& p = probes.probes[i];
    baked.gather(p.position, glm::vec3(0.0f), uint64_t(i), ProbeParams{}.gather, samples);
    double err2 = 0.0, mean = 0.0, se2 = 0.0, direct2 = 0.0;
    for (size_t d = 0; d < 6; ++d) {
      const glm::vec3 want = ref.radiosity[6 * i + d], got = shIrradiance(p.sh, axes[d]);
      glm::vec3 direct(0.0f);
      for (const ArrivalSample& a : samples) direct += a.light * std::max(0.0f, glm::dot(axes[d], a.towards));
      direct2 += glm::dot(direct - want, direct - want) / 3.0;
      err2 += glm::dot(got - want, got - want) / 3.0;
      mean += (want.r + want.g + want.b) / 3.0;
      se2 += glm::dot(ref.standardError[6 * i + d], ref.standardError[6 * i + d]) / 3.0;
    }
    mean /= 6.0;
    const double e = std::sqrt(err2 / 6.0) / mean;
    noise = std::max(noise, std::sqrt(se2 / 6.0) / mean);
    worst = std::max(worst, e);
    const std::string room = p.cell >= 0 ? seed.cells.cells[size_t(p.cell)].name : std::string("-");
    errors[room].push_back(e);
    unprojected[room].push_back(std::sqrt(direct2 / 6.0) / mean);
  }
  for (auto* table : {&errors, &unprojected})
    for (auto& [room, list] : *table) {
      std::sort(list.begin(), list.end());
      const size_t within =
          size_t(std::count_if(list.begin(), list.end(), [](double e) { return e <= 0.05; }));
      std::printf("%s room %s: %zu probes, error median %.4f, 90th %.4f, worst %.4f; within 5 %%: %zu\n",
                  table == &errors ? "L2 SH" : "no SH", room.c_str(), list.size(), list[list.size() / 2],
                  list[std::min(list.size() - 1, list.size() * 9 / 10)], list.back(), within);
    }
  std::printf("worst probe %.4f; the reference's noise (standard error, worst probe) %.4f at %d spp\n", worst,
              noise, ref.spp);
  return 0;
}
