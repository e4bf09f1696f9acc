// Is a lightmap a solution of its own radiosity equation? For each receiver texel, the light it should
// gather from every other texel's radiosity in the same lightmap, by exact point-to-texel form factors
// with visibility by rays (nothing shared with the engines but the ray scene), against what the lightmap
// holds there: per room, Σ a·B over Σ a·(E + ρ·H[B]). A converged bake whose transfers are right reads 1
// in every room up to its own discretisation, the same in a lit room as in one four doors away; a bias of
// the shots into the rooms behind doors reads as a ratio above the lit rooms' there. A reference passes
// it too (up to its noise), so the same check tells which of the two is off. Also per receiving room, the
// share of H from each source room. With --shoot ROOM, the same light of ROOM's surfaces shot patch by
// patch by the rays engine (radiosity/cpu/ray_shot.h, each shot scaled as the loop scales it, averaged over
// --draws eye draws) against the exact gather of it, per receiving room: which transfer is off. With
// --engine gl, the GL engine's shots instead (SolverParams' defaults; GATHER_REGIONS and
// GATHER_REGION_SIZE set --regions and --region-size, GATHER_STRONG makes every shot strong), each draw a
// fresh solve. With --shoot solve, a whole GL solve of SCENE (its lamps shot by the GL engine too,
// GATHER_UNSHOT its stop, 1e-4 by default) with every reflector shot's delivery at the receivers against
// the exact transfer of the residual it shot, per shooting and receiving room, then shot by shot.
//
//   cpgi_gather_check SCENE LIGHT_DIR --density D [--every N] [--rooms R3,R9]
//                     [--shoot ROOM|solve [--draws K] [--engine rays|gl]]
//
// LIGHT_DIR is a bake (one level: --solve-density 0, and --density D) or a reference at --density D;
// --every N takes every N-th valid texel of the chosen rooms as a receiver (default 4).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/image_io.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "radiosity/solve/solve.h"

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

// A solve's shots watched one by one (--solve): before each shot the residual and the radiosity, after it
// the radiosity again, handed to `watch` (shooter, emitting, residual, before, after).
using ShotWatch = std::function<void(int, bool, const std::vector<glm::vec3>&, const std::vector<glm::vec3>&,
                                     const std::vector<glm::vec3>&)>;

class WatchedBackend final : public cpgi::ShotBackend {
 public:
  WatchedBackend(std::unique_ptr<cpgi::ShotBackend> inner, const ShotWatch& watch)
      : inner_(std::move(inner)), watch_(watch) {}
  cpgi::EnergyTotals start() override { return inner_->start(); }
  cpgi::ShooterChoice next() override { return inner_->next(); }
  cpgi::ShotGathered shoot(const cpgi::ShooterChoice& c, bool strong, bool lamp) override {
    shooter_ = c.patch, emitting_ = c.emitting;
    residual_ = inner_->residual(), before_ = inner_->radiosity();
    return inner_->shoot(c, strong, lamp);
  }
  double deliver(float scale) override {
    const double d = inner_->deliver(scale);
    watch_(shooter_, emitting_, residual_, before_, inner_->radiosity());
    return d;
  }
  cpgi::TexelSums sums() const override { return inner_->sums(); }
  std::vector<glm::vec3> radiosity() override { return inner_->radiosity(); }
  std::vector<glm::vec3> residual() override { return inner_->residual(); }
  std::vector<double> patchUnshot() override { return inner_->patchUnshot(); }
  int shotEyes(int patch, bool strong) const override { return inner_->shotEyes(patch, strong); }
  void readBack(const cpgi::ReadBack& what, cpgi::SolveResult& result, cpgi::Context& ctx) override {
    inner_->readBack(what, result, ctx);
  }

 private:
  std::unique_ptr<cpgi::ShotBackend> inner_;
  const ShotWatch& watch_;
  int shooter_ = -1;
  bool emitting_ = false;
  std::vector<glm::vec3> residual_, before_;
};

class WatchedEngine final : public cpgi::ShotEngine {
 public:
  WatchedEngine(cpgi::ShotEngine& inner, const ShotWatch& watch) : inner_(inner), watch_(watch) {}
  std::string name() const override { return inner_.name(); }
  cpgi::EngineFeatures features() const override { return inner_.features(); }
  std::unique_ptr<cpgi::ShotBackend> backend(const cpgi::Scene& scene, const cpgi::LightmapAtlas& atlas,
                                             const cpgi::SolverParams& settings, const cpgi::ShotShape& shape,
                                             const cpgi::FirstShot& first, cpgi::Context& ctx,
                                             std::chrono::steady_clock::time_point deadline) override {
    return std::make_unique<WatchedBackend>(
        inner_.backend(scene, atlas, settings, shape, first, ctx, deadline), watch_);
  }
  std::unique_ptr<cpgi::ShotEngine> forThisThread() const override { return nullptr; }

 private:
  cpgi::ShotEngine& inner_;
  const ShotWatch& watch_;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace cpgi;
  if (argc < 5 || std::strcmp(argv[3], "--density") != 0) {
    std::fprintf(stderr, "usage: %s SCENE LIGHT_DIR --density D [--every N] [--rooms R3,R9]\n", argv[0]);
    return 1;
  }
  int every = 4, draws = 8;
  std::string rooms, shoot, engine = "rays";
  for (int i = 5; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--every")) every = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--rooms")) rooms = "," + std::string(argv[i + 1]) + ",";
    if (!std::strcmp(argv[i], "--shoot")) shoot = argv[i + 1];
    if (!std::strcmp(argv[i], "--draws")) draws = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--engine")) engine = argv[i + 1];
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
    if (shoot == "solve") {
      // --shoot solve: a GL solve of the scene (its lamps shot by the GL engine too) with every reflector
      // shot's delivery at the receivers against the exact transfer of the residual it shot, per shooting
      // and receiving room.
      std::vector<std::vector<uint32_t>> patchTexels(atlas.patches.size());
      for (size_t t = 0; t < atlas.texelCount(); ++t)
        if (atlas.patch[t] >= 0) patchTexels[size_t(atlas.patch[t])].push_back(uint32_t(t));
      std::map<std::pair<size_t, size_t>, glm::dvec2> tally;  // (shooting, receiving room): exact, GL
      struct Shot {
        int number, patch;
        size_t room;
        double exact, gl, power;
      };
      std::vector<Shot> log;
      int number = 0;
      const ShotWatch watch = [&](int p, bool emitting, const std::vector<glm::vec3>& residual,
                                  const std::vector<glm::vec3>& before, const std::vector<glm::vec3>& after) {
        ++number;
        if (emitting) return;
        const std::vector<uint32_t>& texels = patchTexels[size_t(p)];
        double power = 0.0;
        for (uint32_t s : texels)
          power += double(residual[s].r + residual[s].g + residual[s].b) * atlas.area[s];
        std::vector<double> exactHere(receivers.size(), 0.0);
        tbb::parallel_for(size_t(0), receivers.size(), [&](size_t k) {
          const size_t t = receivers[k];
          if (atlas.patch[t] == p) return;
          glm::dvec3 h(0.0);
          for (uint32_t s : texels) h += fromTexel(atlas, rays, eps, t, s, residual[s]);
          h *= glm::dvec3(atlas.albedo[t]);
          exactHere[k] = h.r + h.g + h.b;
        });
        const size_t from = cellIndex(texels[0]);
        std::map<size_t, glm::dvec2> here;
        for (size_t k = 0; k < receivers.size(); ++k) {
          const size_t t = receivers[k];
          const glm::vec3 d = atlas.patch[t] == p ? glm::vec3(0.0f) : after[t] - before[t];
          here[cellIndex(t)] += double(atlas.area[t]) * glm::dvec2(exactHere[k], d.r + d.g + d.b);
        }
        for (const auto& [c, v] : here) {
          tally[{from, c}] += v;
          if (v.x > 0.0 || v.y > 0.0) log.push_back({number, p, c, v.x, v.y, power});
        }
      };
      const EglContext gl(ctx);
      GlShotEngine glEngine(gl);
      WatchedEngine watched(glEngine, watch);
      SolverParams settings;
      settings.unshotFraction = std::getenv("GATHER_UNSHOT") ? std::stod(std::getenv("GATHER_UNSHOT")) : 1e-4;
      if (const char* v = std::getenv("GATHER_REGIONS")) settings.maxRegions = std::atoi(v);
      if (const char* v = std::getenv("GATHER_REGION_SIZE")) settings.regionSize = std::stof(v);
      const SolveResult solved = solveProgressive(loaded.scene, atlas, settings, watched, ctx);
      std::printf("solve: %d shots, unshot %.3g\nfrom  to  exact  gl  ratio\n", solved.shots,
                  solved.unshotFraction);
      for (const auto& [k, v] : tally)
        if (v.x > 0.0 || v.y > 0.0)
          std::printf("%-5s %-5s %.5g %.5g %.4f\n", k.first < names.size() ? names[k.first].c_str() : "-",
                      k.second < names.size() ? names[k.second].c_str() : "-", v.x, v.y, v.y / v.x);
      for (const Shot& s : log)
        std::printf("shot %d patch %d %s -> %s %.3g W: %.4g/%.4g\n", s.number, s.patch,
                    nameOf((*cell)[patchTexels[size_t(s.patch)][0]]).c_str(),
                    s.room < names.size() ? names[s.room].c_str() : "-", s.power, s.gl, s.exact);
      return 0;
    }
    if (engine == "gl") {
      // The GL engine's shots of ROOM's patches one by one, each with the residual it holds when shot (the
      // lightmap's light, plus what the room's earlier shots sent it), against the exact transfer of that
      // residual per receiving room, each shot scaled as the loop scales it.
      LightmapAtlas dark = atlas;
      std::fill(dark.emission.begin(), dark.emission.end(), glm::vec3(0.0f));
      std::vector<std::vector<uint32_t>> patchTexels(atlas.patches.size());
      for (size_t t = 0; t < atlas.texelCount(); ++t)
        if (atlas.patch[t] >= 0) patchTexels[size_t(atlas.patch[t])].push_back(uint32_t(t));
      std::vector<glm::vec3> irradiance(atlas.texelCount(), glm::vec3(0.0f));
      std::vector<size_t> shooters;
      for (size_t p = 0; p < atlas.patches.size(); ++p) {
        if (patchTexels[p].empty() || nameOf((*cell)[patchTexels[p][0]]) != shoot) continue;
        shooters.push_back(p);
        for (uint32_t t : patchTexels[p])
          irradiance[t] = light.pixels[t] / glm::max(atlas.albedo[t], glm::vec3(1e-6f));
      }
      const EglContext gl(ctx);
      GlShotEngine glEngine(gl);
      SolverParams settings;
      if (const char* v = std::getenv("GATHER_REGIONS")) settings.maxRegions = std::atoi(v);
      if (const char* v = std::getenv("GATHER_REGION_SIZE")) settings.regionSize = std::stof(v);
      const ShotShape shape;
      const FirstShot first{irradiance, 0.0, {}};
      const bool strong = std::getenv("GATHER_STRONG") != nullptr;
      std::map<size_t, glm::dvec2> total;  // per receiving room: exact, GL
      double shotPower = 0.0, scaled = 0.0;
      // Each draw a fresh solve with the room's patches shot in an order turned by one, so that every
      // patch is shot with other eye draws (the engine draws them by its shot count).
      for (int d = 0; d < draws; ++d) {
        std::unique_ptr<ShotBackend> backend = glEngine.backend(
            loaded.scene, dark, settings, shape, first, ctx, std::chrono::steady_clock::time_point::max());
        backend->start();
        for (size_t i = 0; i < shooters.size(); ++i) {
          const size_t p = shooters[(i + size_t(d)) % shooters.size()];
          const std::vector<glm::vec3> residual = backend->residual(), before = backend->radiosity();
          double power = 0.0;
          for (uint32_t t : patchTexels[p])
            power += double(residual[t].r + residual[t].g + residual[t].b) * atlas.area[t];
          if (power <= 0.0) continue;
          const ShotGathered g = backend->shoot({int(p), power, false, true}, strong, false);
          const double target = g.open < 1e-3
                                    ? power * std::min(g.covered, 1.0)
                                    : std::min(g.gathered, power * std::min(g.covered + g.open, 1.0));
          const bool rescale =
              g.gathered > 0.0 && (g.gathered - target > 1e-5 * power || target - g.gathered > 2e-3 * power);
          const float scale = rescale ? float(target / g.gathered) : 1.0f;
          backend->deliver(scale);
          const std::vector<glm::vec3> after = backend->radiosity();
          std::vector<double> exactHere(receivers.size(), 0.0);
          tbb::parallel_for(size_t(0), receivers.size(), [&](size_t k) {
            const size_t t = receivers[k];
            if (atlas.patch[t] == int32_t(p)) return;
            glm::dvec3 h(0.0);
            for (uint32_t s : patchTexels[p]) h += fromTexel(atlas, rays, eps, t, s, residual[s]);
            h *= glm::dvec3(atlas.albedo[t]);
            exactHere[k] = h.r + h.g + h.b;
          });
          std::map<size_t, glm::dvec2> here;
          for (size_t k = 0; k < receivers.size(); ++k) {
            const size_t t = receivers[k];
            const glm::vec3 d = atlas.patch[t] == int32_t(p) ? glm::vec3(0.0f) : after[t] - before[t];
            here[cellIndex(t)] += double(atlas.area[t]) * glm::dvec2(exactHere[k], d.r + d.g + d.b);
          }
          const Patch& q = atlas.patches[p];
          std::printf(
              "patch %zu %s %dx%d n %+.0f %+.0f %+.0f at %.2f %.2f %.2f, %.3g W, gathered %.3f covered %.3f "
              "scale %.3f:",
              p, loaded.scene.nodePaths[loaded.scene.triangles[size_t(q.triangles[0])].node].c_str(), q.w,
              q.h, q.normal.x, q.normal.y, q.normal.z, q.origin.x, q.origin.y, q.origin.z, power,
              g.gathered / power, g.covered, scale);
          for (const auto& [c, v] : here)
            if (v.x > 0.0 || v.y > 0.0) {
              std::printf("  %s %.3g/%.3g=%.3f", c < names.size() ? names[c].c_str() : "-", v.y, v.x,
                          v.y / v.x);
              total[c] += v;
            }
          std::printf("\n");
          shotPower += power;
          scaled += scale * power;
        }
      }
      std::printf("%s shot by gl: %.5g W, scaled on average by %.4f\nroom  exact  gl  ratio\n", shoot.c_str(),
                  shotPower, shotPower > 0.0 ? scaled / shotPower : 0.0);
      for (const auto& [c, v] : total)
        std::printf("%-5s %.5g %.5g %.4f\n", c < names.size() ? names[c].c_str() : "-", v.x, v.y, v.y / v.x);
      return 0;
    }
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
