// Light probes against the reference path tracer (issue 48 item 5): at every probe of a default bake,
// the irradiance its SH gives a surface facing each of the six axes and eight diagonals (±1, ±1, ±1)/√3,
// against `cpgi reference`'s tracer at the same point and normal (a white point, ρ = 1: its B is the
// irradiance). Per probe, the error is the RMS over the fourteen normals of (E_probe − E_ref), over the
// mean of the fourteen E_ref; listed per room with the share of probes within 5 %, for each way of
// reading the probe, to tell the causes apart:
//  - "L2": the nine coefficients engines read;
//  - "L2+L4": with band 4 (LightProbe::sh4);
//  - "no SH": the probe's own gather summed straight over each normal's hemisphere (the gather, apart from
//    any truncation);
//  - "L2+L4 x4" and "no SH x4": the same from a gather of four times the rays and emitter samples (the
//    gather's noise);
// and the reference's noise (standard error) per probe beside them, and the probes' distance to the
// nearest surface (near a wall the light changes fastest).
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

  std::vector<glm::vec3> normals = {glm::vec3(1, 0, 0),  glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                    glm::vec3(0, -1, 0), glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1)};
  for (int k = 0; k < 8; ++k)
    normals.push_back(glm::normalize(glm::vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  const size_t nn = normals.size();
  std::vector<SamplePoint> points;
  for (const LightProbe& p : probes.probes)
    for (const glm::vec3& n : normals) points.push_back({p.position, n, glm::vec3(1.0f), glm::vec3(0.0f)});
  ReferenceParams params;
  params.spp = spp;
  params.texelMean = false;
  const ReferenceResult ref = traceReference(seed.scene, points, params, ctx);

  const RayScene rays(seed.scene);
  const BakedRadiance baked(seed.scene, rays, r.atlas, r.radiosity);
  const char* names[] = {"L2", "L2+L4", "no SH", "L2+L4 x4", "no SH x4", "ref noise"};
  constexpr size_t kWays = 6;
  std::map<std::string, std::array<std::vector<double>, kWays>> errors;  // per room, per way
  std::map<std::string, std::vector<std::pair<double, double>>>
      byDistance;  // per room: (distance, L2+L4 error)
  GatherParams dense = ProbeParams{}.gather;
  dense.rays *= 4, dense.emitterSamples *= 4;
  std::vector<ArrivalSample> samples, denseSamples;
  for (size_t i = 0; i < probes.probes.size(); ++i) {
    const LightProbe& p = probes.probes[i];
    baked.gather(p.position, glm::vec3(0.0f), uint64_t(i), ProbeParams{}.gather, samples);
    baked.gather(p.position, glm::vec3(0.0f), uint64_t(i) + 1000003u, dense, denseSamples);
    std::array<glm::vec3, 9> sh{}, sh4{};
    for (const ArrivalSample& a : denseSamples) {
      const std::array<float, 9> y = shBasis(a.towards), y4 = shBasisBand4(a.towards);
      for (size_t k = 0; k < 9; ++k) sh[k] += a.light * y[k], sh4[k] += a.light * y4[k];
    }
    std::array<double, kWays> err2{};
    double mean = 0.0;
    for (size_t d = 0; d < nn; ++d) {
      const glm::vec3 n = normals[d], want = ref.radiosity[nn * i + d];
      glm::vec3 direct(0.0f), denseDirect(0.0f);
      for (const ArrivalSample& a : samples) direct += a.light * std::max(0.0f, glm::dot(n, a.towards));
      for (const ArrivalSample& a : denseSamples)
        denseDirect += a.light * std::max(0.0f, glm::dot(n, a.towards));
      const glm::vec3 got[kWays - 1] = {shIrradiance(p.sh, n),
                                        shIrradiance(p.sh, n) + shIrradianceBand4(p.sh4, n), direct,
                                        shIrradiance(sh, n) + shIrradianceBand4(sh4, n), denseDirect};
      for (size_t w = 0; w + 1 < kWays; ++w) err2[w] += glm::dot(got[w] - want, got[w] - want) / 3.0;
      err2[kWays - 1] += glm::dot(ref.standardError[nn * i + d], ref.standardError[nn * i + d]) / 3.0;
      mean += (want.r + want.g + want.b) / 3.0;
    }
    mean /= double(nn);
    const std::string room = p.cell >= 0 ? seed.cells.cells[size_t(p.cell)].name : std::string("-");
    for (size_t w = 0; w < kWays; ++w) errors[room][w].push_back(std::sqrt(err2[w] / double(nn)) / mean);
    float nearest = 1e30f;
    for (const glm::vec3& n : normals)
      if (const RayScene::Hit hit = rays.intersect(p.position, n); hit) nearest = std::min(nearest, hit.t);
    byDistance[room].push_back({nearest, std::sqrt(err2[1] / double(nn)) / mean});
  }
  for (size_t w = 0; w < kWays; ++w)
    for (auto& [room, lists] : errors) {
      std::vector<double>& list = lists[w];
      std::sort(list.begin(), list.end());
      const size_t within =
          size_t(std::count_if(list.begin(), list.end(), [](double e) { return e <= 0.05; }));
      std::printf("%-9s room %s: %zu probes, error median %.4f, 90th %.4f, worst %.4f; within 5 %%: %zu\n",
                  names[w], room.c_str(), list.size(), list[list.size() / 2],
                  list[std::min(list.size() - 1, list.size() * 9 / 10)], list.back(), within);
    }
  for (auto& [room, list] : byDistance) {
    std::sort(list.begin(), list.end());
    std::printf("room %s, L2+L4 error by distance to the nearest surface (of 14 directions):", room.c_str());
    for (const auto& [d, e] : list) std::printf(" %.2f:%.3f", d, e);
    std::printf("\n");
  }
  std::printf("reference %d spp\n", ref.spp);
  return 0;
}
