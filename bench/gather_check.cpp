// Is a lightmap a solution of its own radiosity equation? For each receiver texel, the light it should
// gather from every other texel's radiosity in the same lightmap, by exact point-to-texel form factors
// with visibility by rays (nothing shared with the engines but the ray scene), against what the lightmap
// holds there: per room, Σ a·B over Σ a·(E + ρ·H[B]). A converged bake whose transfers are right reads 1
// in every room up to its own discretisation, the same in a lit room as in one four doors away; a bias of
// the shots into the rooms behind doors reads as a ratio above the lit rooms' there. A reference passes
// it too (up to its noise), so the same check tells which of the two is off. Also per receiving room, the
// share of H from each source room. With --shoot ROOM, the same light of ROOM's surfaces shot patch by
// patch by the rays engine (radiosity/cpu/ray_shot.h, each shot scaled as the loop scales it, averaged over
// --draws eye draws) against the exact gather of it, per receiving room: which transfer is off.
//
//   cpgi_gather_check SCENE LIGHT_DIR --density D [--every N] [--rooms R3,R9] [--shoot ROOM [--draws K]]
//
// LIGHT_DIR is a bake (one level: --solve-density 0, and --density D) or a reference at --density D;
// --every N takes every N-th valid texel of the chosen rooms as a receiver (default 4).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/image_io.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

const std::vector<float>* channel(const std::vector<cpgi::ExrChannel>& channels, const std::string& name) {
  for (const cpgi::ExrChannel& c : channels)
    if (c.name == name) return &c.values;
  return nullptr;
}

// Irradiance at receiver texel t from source texel s of radiosity `b`: m × m points over s (m by distance,
// disk form factors near contact), each with its own visibility ray.
glm::dvec3 fromTexel(const cpgi::LightmapAtlas& atlas, const cpgi::RayScene& rays, float eps, size_t t,
                     size_t s, const glm::vec3& b) {
  const cpgi::Patch& sp = atlas.patches[size_t(atlas.patch[s])];
  const glm::vec3 x = atlas.position[t], n = atlas.normal[t], ns = sp.normal;
  const glm::vec3 d = atlas.position[s] - x;
  const float size = std::max(glm::length(sp.texelU + sp.texelV), glm::length(sp.texelU - sp.texelV));
  // Whole texel behind the receiver's plane, or the receiver behind the texel's: nothing.
  if (glm::dot(n, d) < -size || glm::dot(ns, -d) < -size) return glm::dvec3(0.0);
  const float r = glm::length(d);
  const int m = r < 2.0f * size ? 8 : r < 6.0f * size ? 3 : 1;
  const float a = atlas.area[s] / float(m * m);
  double sum = 0.0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const glm::vec3 y =
          atlas.position[s] + ((i + 0.5f) / m - 0.5f) * sp.texelU + ((j + 0.5f) / m - 0.5f) * sp.texelV;
      const glm::vec3 v = y - x;
      const float r2 = glm::dot(v, v), ci = glm::dot(n, v), cs = -glm::dot(ns, v);
      if (ci <= 0.0f || cs <= 0.0f || r2 <= 0.0f) continue;
      const glm::vec3 from = x + n * eps, to = y + ns * eps;
      const float length = glm::distance(from, to);
      if (length <= 2.0f * eps || rays.occluded(from, (to - from) / length, 0.0f, length - eps)) continue;
      sum += double(a) * ci * cs / (r2 * (kPi * r2 + a));
    }
  return sum * glm::dvec3(b);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cpgi;
  if (argc < 5 || std::strcmp(argv[3], "--density") != 0) {
    std::fprintf(stderr, "usage: %s SCENE LIGHT_DIR --density D [--every N] [--rooms R3,R9]\n", argv[0]);
    return 1;
  }
  int every = 4, draws = 8;
  std::string rooms, shoot;
  for (int i = 5; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--every")) every = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--rooms")) rooms = "," + std::string(argv[i + 1]) + ",";
    if (!std::strcmp(argv[i], "--shoot")) shoot = argv[i + 1];
    if (!std::strcmp(argv[i], "--draws")) draws = std::max(1, std::atoi(argv[i + 1]));
  }
  try {
    const LoadedScene loaded = loadScene(argv[1]);
    AtlasParams params;
    params.density = std::stof(argv[4]);
    Context ctx;
    const LightmapAtlas atlas = buildAtlas(loaded.scene, findQuads(loaded.scene), params, ctx);
    std::vector<ExrChannel> channels;
    const ImageRGB light = readExr(std::string(argv[2]) + "/lightmap.exr", &channels);
    const std::vector<float>* cell = channel(channels, "cell");
    const std::vector<float>* area = channel(channels, "area");
    if (light.width != atlas.width || light.height != atlas.height || !cell || !area) {
      std::fprintf(stderr, "the lightmap is not of this atlas (%dx%d) or has no cell channel\n", atlas.width,
                   atlas.height);
      return 1;
    }
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (std::abs((*area)[t] - atlas.area[t]) > 1e-4f * std::max(atlas.area[t], 1e-9f)) {
        std::fprintf(stderr, "texel %zu: area %g in the lightmap, %g in this atlas\n", t, (*area)[t],
                     atlas.area[t]);
        return 1;
      }
    std::vector<std::string> names;
    for (const Cell& c : loaded.cells.cells) names.push_back(c.name);
    auto nameOf = [&](float c) { return c >= 0.0f && size_t(c) < names.size() ? names[size_t(c)] : "-"; };
    if (rooms == ",patches,") {  // --rooms patches: each patch's room (by its texels' majority) and node
      for (size_t p = 0; p < atlas.patches.size(); ++p) {
        std::map<std::string, size_t> count;
        for (size_t t = 0; t < atlas.texelCount(); ++t)
          if (atlas.patch[t] == int32_t(p)) ++count[nameOf((*cell)[t])];
        std::string best = "-";
        size_t most = 0;
        for (const auto& [n, c] : count)
          if (c > most) best = n, most = c;
        std::printf("PATCH %zu %s %s\n", p, best.c_str(),
                    loaded.scene.nodePaths[loaded.scene.triangles[size_t(atlas.patches[p].triangles[0])].node]
                        .c_str());
      }
      return 0;
    }
    std::vector<size_t> sources, receivers;
    size_t rank = 0;
    for (size_t t = 0; t < atlas.texelCount(); ++t) {
      if (atlas.patch[t] < 0) continue;
      if (light.pixels[t] != glm::vec3(0.0f)) sources.push_back(t);
      const bool chosen = rooms.empty() || rooms.find("," + nameOf((*cell)[t]) + ",") != std::string::npos;
      if (chosen && glm::length(atlas.emission[t]) == 0.0f && rank++ % size_t(every) == 0)
        receivers.push_back(t);
    }
    const RayScene rays(loaded.scene);
    const float eps = 1e-4f * rays.diagonal();
    const size_t cells = names.size() + 1;  // the last: no cell
    auto cellIndex = [&](size_t t) {
      const float c = (*cell)[t];
      return c >= 0.0f && size_t(c) < names.size() ? size_t(c) : names.size();
    };
    // Per receiver, H split by source cell (R + G + B).
    std::vector<std::vector<glm::dvec3>> gathered(receivers.size(), std::vector<glm::dvec3>(cells));
    tbb::parallel_for(size_t(0), receivers.size(), [&](size_t k) {
      const size_t t = receivers[k];
      for (size_t s : sources)
        if (atlas.patch[s] != atlas.patch[t])
          gathered[k][cellIndex(s)] += fromTexel(atlas, rays, eps, t, s, light.pixels[s]);
    });
    struct Room {
      double b = 0.0, expected = 0.0;
      std::vector<double> from;
    };
    std::map<size_t, Room> perRoom;
    for (size_t k = 0; k < receivers.size(); ++k) {
      const size_t t = receivers[k];
      Room& r = perRoom[cellIndex(t)];
      if (r.from.empty()) r.from.assign(cells, 0.0);
      glm::dvec3 h(0.0);
      for (size_t c = 0; c < cells; ++c) {
        h += gathered[k][c];
        const glm::dvec3 hc = glm::dvec3(atlas.albedo[t]) * gathered[k][c];
        r.from[c] += atlas.area[t] * (hc.r + hc.g + hc.b);
      }
      const glm::dvec3 expected = glm::dvec3(atlas.emission[t]) + glm::dvec3(atlas.albedo[t]) * h;
      const glm::dvec3 b(light.pixels[t]);
      r.b += atlas.area[t] * (b.r + b.g + b.b);
      r.expected += atlas.area[t] * (expected.r + expected.g + expected.b);
    }
    std::printf("room  receivers-light  gathered  ratio  (share of the gathered from each room)\n");
    for (const auto& [c, r] : perRoom) {
      std::printf("%-5s %.5g %.5g %.4f ", c < names.size() ? names[c].c_str() : "-", r.b, r.expected,
                  r.b / r.expected);
      for (size_t s = 0; s < cells; ++s)
        if (r.from[s] > 1e-3 * r.expected)
          std::printf(" %s:%.3f", s < names.size() ? names[s].c_str() : "-", r.from[s] / r.expected);
      std::printf("\n");
    }
    if (shoot.empty()) return 0;
    // The rays engine's shots of ROOM's patches, each with the bake's radiosity there as its unshot light.
    std::vector<double> byRays(atlas.texelCount(), 0.0);
    const RayShotScene shots(loaded.scene, atlas, rays);
    const std::vector<ShooterLayout> layouts = layoutShooters(loaded.scene, atlas, {1.0f, 2});
    std::vector<glm::vec3> residual(atlas.texelCount(), glm::vec3(0.0f));
    double shotPower = 0.0, scaled = 0.0;
    for (size_t p = 0; p < atlas.patches.size(); ++p) {
      const std::vector<uint32_t>& texels = shots.patchTexels[p];
      if (texels.empty() || nameOf((*cell)[texels[0]]) != shoot) continue;
      double power = 0.0;
      for (uint32_t t : texels) {
        residual[t] = light.pixels[t];
        power += double(residual[t].r + residual[t].g + residual[t].b) * atlas.area[t];
      }
      std::vector<double> patchRays(atlas.texelCount(), 0.0);
      if (power > 0.0)
        for (int d = 0; d < draws; ++d) {
          const RayShotGain g = shootByRays(shots, int(p), layouts[p], residual, uint32_t(d + 1), {});
          // progressive_loop.cpp's shotScale, the loop's rule for what a shot delivers.
          const double target = g.open < 1e-3
                                    ? power * std::min(g.covered, 1.0)
                                    : std::min(g.gathered, power * std::min(g.covered + g.open, 1.0));
          const bool rescale =
              g.gathered > 0.0 && (g.gathered - target > 1e-5 * power || target - g.gathered > 2e-3 * power);
          const double scale = rescale ? target / g.gathered : 1.0;
          scaled += scale * power / draws;
          for (size_t k = 0; k < shots.texels.size(); ++k) {
            const glm::vec3 h = g.irradiance[k] * atlas.albedo[shots.texels[k]];
            patchRays[shots.texels[k]] += scale * double(h.r + h.g + h.b) / draws;
          }
        }
      // This patch's exact light at the receivers, per receiving room, beside the rays'.
      std::vector<double> exactHere(receivers.size(), 0.0);
      tbb::parallel_for(size_t(0), receivers.size(), [&](size_t k) {
        const size_t t = receivers[k];
        if (atlas.patch[t] == int32_t(p)) return;
        glm::dvec3 h(0.0);
        for (uint32_t s : texels) h += fromTexel(atlas, rays, eps, t, s, light.pixels[s]);
        h *= glm::dvec3(atlas.albedo[t]);
        exactHere[k] = h.r + h.g + h.b;
      });
      std::map<size_t, glm::dvec2> here;
      for (size_t k = 0; k < receivers.size(); ++k)
        here[cellIndex(receivers[k])] +=
            double(atlas.area[receivers[k]]) * glm::dvec2(exactHere[k], patchRays[receivers[k]]);
      const Patch& q = atlas.patches[p];
      std::printf("patch %zu %s n %+.0f %+.0f %+.0f at %.2f %.2f %.2f, %.3g W:", p,
                  loaded.scene.nodePaths[loaded.scene.triangles[size_t(q.triangles[0])].node].c_str(),
                  q.normal.x, q.normal.y, q.normal.z, q.origin.x, q.origin.y, q.origin.z, power);
      for (const auto& [c, v] : here)
        if (v.x > 0.0 || v.y > 0.0)
          std::printf("  %s %.3g/%.3g=%.3f", c < names.size() ? names[c].c_str() : "-", v.y, v.x, v.y / v.x);
      std::printf("\n");
      for (size_t t = 0; t < atlas.texelCount(); ++t) byRays[t] += patchRays[t];
      shotPower += power;
      for (uint32_t t : texels) residual[t] = glm::vec3(0.0f);
    }
    std::printf("%s shot by rays: %.5g W, scaled on average by %.4f\nroom  exact  rays  ratio\n",
                shoot.c_str(), shotPower, shotPower > 0.0 ? scaled / shotPower : 0.0);
    const size_t source = size_t(std::find(names.begin(), names.end(), shoot) - names.begin());
    std::map<size_t, double> raysPerRoom;
    for (size_t t : receivers) raysPerRoom[cellIndex(t)] += atlas.area[t] * byRays[t];
    for (const auto& [c, r] : perRoom)
      if (source < cells && (r.from[source] > 0.0 || raysPerRoom[c] > 0.0))
        std::printf("%-5s %.5g %.5g %.4f\n", c < names.size() ? names[c].c_str() : "-", r.from[source],
                    raysPerRoom[c], raysPerRoom[c] / r.from[source]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
