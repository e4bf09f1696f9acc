// How well each portal emission model passes light through one portal, with everything else exact: the
// light arriving at the portal is B's radiosity from a bake (a converged global bake: right to ~1 %),
// looked up where rays from the portal into the source cell hit; the destination cell's texels then
// receive from the portal (a) through it, as the truth: the ray from the texel through a portal point
// continues into the source cell and takes the radiance it meets, and (b) from the portal re-emitting its
// irradiance per portal texel as a Lambertian, as the moment-fitted lobe of radiosity/solve/emission_lobes.h,
// or as a histogram of arrival directions in radiosity/solve/emission_bins.h's bins — and the bins read
// between neighbouring texels' centres (bins-lerp: the bins alone; light-lerp: irradiance times bins), or
// per quarter of the texel with the texel's irradiance (bins/4): what a texel's light spread over its area
// without finer texels would give. Only the first pass through the portal; no interreflection in the
// destination. Prints, per destination surface orientation and per band of distance from the portal
// plane, the ratio of each model to the truth, and the per-texel RMSE relative to the destination's mean.
//
//   cpgi_portal_oracle SCENE BAKE_DIR PORTAL_NAME SOURCE_CELL [--density D] [--portal-texel M]
//                      [--arrival-rays N] [--portal-points K] [--lobe-width W] [--keep-contacts 1]
// --keep-contacts 1: the scene read with its faces whole, as a bake made before the contact cuts was.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <random>
#include <string>

#include <tbb/parallel_for.h>

#include "core/image_io.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/solve/emission_bins.h"
#include "radiosity/solve/emission_lobes.h"

namespace {

using namespace cpgi;
constexpr float kPi = std::numbers::pi_v<float>;

glm::vec3 radiosityAt(const LightmapAtlas& atlas, const ImageRGB& bake, const Scene& scene,
                      const RayScene::Hit& hit) {
  const auto& uv = atlas.triangleUV[size_t(hit.triangle)];
  const glm::vec2 p = (1.0f - hit.u - hit.v) * uv[0] + hit.u * uv[1] + hit.v * uv[2];
  const int i = std::clamp(int(p.x * float(atlas.width)), 0, atlas.width - 1);
  const int j = std::clamp(int(p.y * float(atlas.height)), 0, atlas.height - 1);
  (void)scene;
  return bake.pixels[size_t(j) * size_t(atlas.width) + size_t(i)];
}

struct PortalTexel {
  glm::vec3 centre;
  glm::vec3 irradiance{0.0f};  ///< from the source side, RGB
  glm::vec4 moments{0.0f};
  glm::vec4 lobe{0.0f};
  ArrivalBins bins{};                        ///< irradiance per arrival bin
  std::array<ArrivalBins, 4> quarterBins{};  ///< the same per quarter of the texel (u, v halves)
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s SCENE BAKE_DIR PORTAL_NAME SOURCE_CELL [options]\n", argv[0]);
    return 1;
  }
  float density = 10.0f, portalTexel = 0.1f, lobeWidth = 0.2f;
  int arrivalRays = 4096, portalPoints = 4;
  LoadOptions load;
  for (int a = 5; a + 1 < argc; a += 2) {
    const std::string o = argv[a];
    const float v = std::stof(argv[a + 1]);
    if (o == "--density")
      density = v;
    else if (o == "--portal-texel")
      portalTexel = v;
    else if (o == "--arrival-rays")
      arrivalRays = int(v);
    else if (o == "--portal-points")
      portalPoints = int(v);
    else if (o == "--lobe-width")
      lobeWidth = v;
    else if (o == "--keep-contacts")
      load.cutContacts = v == 0.0f;
    else {
      std::fprintf(stderr, "unknown option %s\n", o.c_str());
      return 1;
    }
  }
  try {
    const LoadedScene loaded = loadScene(argv[1], load);
    const Scene& scene = loaded.scene;
    const CellGraph& cells = loaded.cells;
    AtlasParams params;
    params.density = density;
    Context ctx;
    const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), params, ctx);
    const ImageRGB bake = readExr(std::string(argv[2]) + "/lightmap.exr");
    if (bake.width != atlas.width || bake.height != atlas.height) throw std::runtime_error("atlas mismatch");
    const RayScene rays(scene);
    const PortalQuad* portal = nullptr;
    for (const PortalQuad& p : cells.portals)
      if (p.name == argv[3]) portal = &p;
    if (!portal) throw std::runtime_error("no such portal");
    const int source = cells.findCell(argv[4]);
    if (source != portal->cellA && source != portal->cellB) throw std::runtime_error("source not on portal");
    const int dest = source == portal->cellA ? portal->cellB : portal->cellA;
    const glm::vec3 nOut = source == portal->cellA ? portal->normal : -portal->normal;  // into dest

    // Portal texels.
    const glm::vec3 o = portal->corners[0], e1 = portal->corners[1] - o, e2 = portal->corners[3] - o;
    const int n1 = std::max(1, int(std::round(glm::length(e1) / portalTexel)));
    const int n2 = std::max(1, int(std::round(glm::length(e2) / portalTexel)));
    const float texelArea = portal->area / float(n1 * n2);
    const BinFrame bins = binFrame(nOut);
    std::vector<PortalTexel> texels(size_t(n1 * n2));
    const float eps = 1e-4f * rays.diagonal();
    tbb::parallel_for(0, n1 * n2, [&](int k) {
      PortalTexel& pt = texels[size_t(k)];
      const int i = k % n1, j = k / n1;
      pt.centre = o + (float(i) + 0.5f) / float(n1) * e1 + (float(j) + 0.5f) / float(n2) * e2;
      std::mt19937 rng(1234u + unsigned(k));
      std::uniform_real_distribution<float> U(0.0f, 1.0f);
      for (int s = 0; s < arrivalRays; ++s) {
        const float ru = U(rng), rv = U(rng);
        const glm::vec3 y = o + (float(i) + ru) / float(n1) * e1 + (float(j) + rv) / float(n2) * e2;
        // Cosine-weighted direction into the source side (−nOut), stratified-ish by random.
        const float r = std::sqrt(U(rng)), phi = 2.0f * kPi * U(rng);
        const glm::vec3 inward = -nOut;
        const glm::vec3 d = glm::normalize(r * std::cos(phi) * bins.t1 + r * std::sin(phi) * bins.t2 +
                                           std::sqrt(std::max(0.0f, 1.0f - r * r)) * inward);
        const RayScene::Hit hit = rays.intersect(y - eps * inward * 0.0f, d, eps);
        if (!hit) continue;
        const glm::vec3 b = radiosityAt(atlas, bake, scene, hit);
        // cosine-weighted: E = π/N Σ L = (1/N) Σ B.
        pt.irradiance += b / float(arrivalRays);
        const float w = (b.r + b.g + b.b) / float(arrivalRays);
        const glm::vec3 omega = -d;  // the light travels into dest
        pt.moments += arrivalMoment(omega, nOut, w);
        pt.bins[size_t(arrivalBin(bins, omega))] += b / float(arrivalRays);
        pt.quarterBins[size_t((ru < 0.5f ? 0 : 1) + (rv < 0.5f ? 0 : 2))][size_t(arrivalBin(bins, omega))] +=
            b / float(arrivalRays);
      }
      pt.lobe = fitEmissionLobe(pt.moments, nOut, lobeWidth);
    });

    // Destination texels.
    const std::vector<int> cellOf = cells.cellOfTriangle(scene.triangles.size());
    std::vector<size_t> receivers;
    for (size_t t = 0; t < atlas.texelCount(); ++t) {
      if (atlas.patch[t] < 0 || !(atlas.area[t] > 0.0f)) continue;
      const Patch& p = atlas.patches[size_t(atlas.patch[t])];
      if (cellOf[size_t(p.triangles.front())] != dest) continue;
      receivers.push_back(t);
    }
    constexpr int kModels = 8;  // truth, lambert, lobe, lobe+blur, bins, bins between texels (2), quarters
    std::vector<std::array<double, kModels>> got(receivers.size());
    tbb::parallel_for(size_t(0), receivers.size(), [&](size_t q) {
      const size_t t = receivers[q];
      const glm::vec3 x = atlas.position[t], n = atlas.normal[t];
      std::array<double, kModels> sum{};
      std::mt19937 rng(777u + unsigned(q));
      std::uniform_real_distribution<float> U(0.0f, 1.0f);
      for (int k = 0; k < n1 * n2; ++k) {
        const PortalTexel& pt = texels[size_t(k)];
        const int i = k % n1, j = k / n1;
        const int side = std::max(1, int(std::sqrt(double(portalPoints))));
        for (int s = 0; s < portalPoints; ++s) {
          // Stratified over the texel (side × side cells), the same points for the truth and every model.
          const float su = (float(s % side) + U(rng)) / float(side),
                      sv = (float((s / side) % side) + U(rng)) / float(side);
          const glm::vec3 y = o + (float(i) + su) / float(n1) * e1 + (float(j) + sv) / float(n2) * e2;
          const glm::vec3 v = y - x;
          const float r2 = glm::dot(v, v), r = std::sqrt(r2);
          const glm::vec3 d = v / r;
          const float cx = glm::dot(n, d), cy = -glm::dot(nOut, d);  // at the portal, leaving into dest
          if (cx <= 0.0f || cy <= 0.0f) continue;
          if (rays.occluded(x + eps * n, d, 0.0f, r - eps)) continue;
          const float g = cx * cy / (kPi * r2) * texelArea / float(portalPoints);  // × exitance·f
          const RayScene::Hit hit = rays.intersect(y, d, eps);
          if (hit) {
            const glm::vec3 b = radiosityAt(atlas, bake, scene, hit);
            sum[0] += (b.r + b.g + b.b) * g;  // radiance B/π along the ray, × cx cy dA / r²
          }
          const glm::vec3 omega = -d;
          const float m = pt.irradiance.r + pt.irradiance.g + pt.irradiance.b;
          sum[1] += m * g;
          sum[2] += m * g * emissionLobeFactor(pt.lobe, nOut, omega);
          const float cs = std::max(cy, 0.1f);
          const float blur = std::min(atlas.area[t] * cx / (12.0f * r2 * cs * cs * cs), 0.1f);
          sum[3] += m * g * emissionLobeFactor(pt.lobe, nOut, omega, blur);
          sum[4] += g * glm::dot(pt.irradiance, binnedEmissionFactor(pt.bins, bins, omega));
          // Between the texels' centres, bilinearly, held at the portal's edges: the bins alone (the
          // texel's own irradiance), or the light (irradiance times bins).
          const float gx = std::clamp(float(i) + su - 0.5f, 0.0f, float(n1 - 1)),
                      gy = std::clamp(float(j) + sv - 0.5f, 0.0f, float(n2 - 1));
          const int i0 = std::min(int(gx), n1 - 1), j0 = std::min(int(gy), n2 - 1);
          const int i1 = std::min(i0 + 1, n1 - 1), j1 = std::min(j0 + 1, n2 - 1);
          const float fx = gx - float(i0), fy = gy - float(j0);
          const int at[4] = {j0 * n1 + i0, j0 * n1 + i1, j1 * n1 + i0, j1 * n1 + i1};
          const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
          glm::vec3 f(0.0f), light(0.0f);
          for (int q = 0; q < 4; ++q) {
            const PortalTexel& nb = texels[size_t(at[q])];
            const glm::vec3 fq = binnedEmissionFactor(nb.bins, bins, omega);
            f += w[q] * fq, light += w[q] * nb.irradiance * fq;
          }
          sum[5] += g * glm::dot(pt.irradiance, f);
          sum[6] += g * (light.r + light.g + light.b);
          // The texel's irradiance, in the directions of the quarter of it the point is in.
          const ArrivalBins& quarter = pt.quarterBins[size_t((su < 0.5f ? 0 : 1) + (sv < 0.5f ? 0 : 2))];
          sum[7] += g * glm::dot(pt.irradiance, binnedEmissionFactor(quarter, bins, omega));
        }
      }
      got[q] = sum;
    });

    // Report: by surface orientation, and by distance bands from the portal plane.
    const char* names[kModels] = {"truth", "lambert",   "lobe",       "lobe+blur",
                                  "bins",  "bins-lerp", "light-lerp", "bins/4"};
    std::map<std::string, std::array<double, kModels>> byGroup;
    std::array<double, kModels> total{}, sq{};
    double area = 0.0;
    for (size_t q = 0; q < receivers.size(); ++q) {
      const size_t t = receivers[q];
      const glm::vec3 n = atlas.normal[t];
      const float dist = std::abs(glm::dot(atlas.position[t] - portal->corners[0], nOut));
      std::string orient = std::abs(n.x) > 0.9f   ? (n.x > 0 ? "+x" : "-x")
                           : std::abs(n.y) > 0.9f ? (n.y > 0 ? "+y" : "-y")
                                                  : (n.z > 0 ? "+z" : "-z");
      char band[64];
      std::snprintf(band, sizeof band, "%s d%.1f", orient.c_str(), std::floor(dist / 0.5f) * 0.5f);
      const double a = atlas.area[t];
      for (int m = 0; m < kModels; ++m) {
        byGroup[orient][size_t(m)] += got[q][size_t(m)] * a;
        byGroup[band][size_t(m)] += got[q][size_t(m)] * a;
        total[size_t(m)] += got[q][size_t(m)] * a;
      }
      area += a;
    }
    const double mean = total[0] / area;
    // The same past half a metre from the portal's plane: the texels beside the opening see it at contact,
    // where a few sub-points' 1/r² dominate every model's error alike.
    std::array<double, kModels> sqFar{}, totalFar{};
    double areaFar = 0.0;
    for (size_t q = 0; q < receivers.size(); ++q) {
      const size_t t = receivers[q];
      const bool far = std::abs(glm::dot(atlas.position[t] - portal->corners[0], nOut)) >= 0.5f;
      if (far) areaFar += atlas.area[t], totalFar[0] += got[q][0] * atlas.area[t];
      for (int m = 1; m < kModels; ++m) {
        const double d = got[q][size_t(m)] - got[q][0];
        sq[size_t(m)] += d * d * atlas.area[t];
        if (far) sqFar[size_t(m)] += d * d * atlas.area[t];
      }
    }
    std::printf("portal %s: %dx%d texels of %.3f m², %zu receivers; %d bins\n", portal->name.c_str(), n1, n2,
                texelArea, receivers.size(), kArrivalBins);
    glm::dvec3 through(0.0);
    for (const PortalTexel& pt : texels) through += glm::dvec3(pt.irradiance) * double(texelArea);
    std::printf("power through it from %s: %.6g W (R %.6g G %.6g B %.6g)\n", argv[4],
                through.r + through.g + through.b, through.r, through.g, through.b);
    std::printf("%-12s", "group");
    for (int m = 1; m < kModels; ++m) std::printf(" %10s", names[m]);
    std::printf("  (ratio to truth)\n");
    for (const auto& [g, s] : byGroup) {
      std::printf("%-12s", g.c_str());
      for (int m = 1; m < kModels; ++m) std::printf(" %10.3f", s[size_t(m)] / s[0]);
      std::printf("   share %.3f\n", s[0] / total[0]);
    }
    std::printf("%-12s", "all");
    for (int m = 1; m < kModels; ++m) std::printf(" %10.3f", total[size_t(m)] / total[0]);
    std::printf("\n%-12s", "rmse/mean");
    for (int m = 1; m < kModels; ++m) std::printf(" %9.1f%%", 100.0 * std::sqrt(sq[size_t(m)] / area) / mean);
    std::printf("\n%-12s", "rmse ≥ 0.5 m");
    for (int m = 1; m < kModels; ++m)
      std::printf(" %9.1f%%", 100.0 * std::sqrt(sqFar[size_t(m)] / areaFar) / (totalFar[0] / areaFar));
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
