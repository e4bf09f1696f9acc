// What one reflector shot gathers at each receiving patch, against the same shot computed independently
// (Embree rays from every receiver texel to N² stratified points per shooter texel): where a shot's light
// goes missing, or goes where it should not. Nothing emits; the shooter's texels hold an unshot radiosity
// of 1 W/m², or with --lit X,Y,Z what a downward-facing point lamp there gives them (a wall lit by a
// ceiling lamp: bright in a band, dark at the top), or with --residual-from the radiosity a bake of the
// scene left there (its lightmap.exr, at the same density); the solver shoots once, and the figures are what
// its receive pass gathered before the shot was scaled to what its eyes saw covered (gl_shot_backend.cpp).
//
//   cpgi_shot_probe SCENE_NAME PATCH [--density D] [--points N] [--hemisphere] [--regions R]
//                   [--far-field F] [--lit X,Y,Z | --residual-from BAKE_DIR] [--draws N] [--texels P]
//
// The third figure per patch is the same shot by the CPU ray solver (radiosity/cpu/ray_shot.h), its
// eyes drawn by the same shot numbers, before its own scaling.
// --draws N: the same shot N times with the eyes of shots 1..N of a solve (SolveControls::
// firstShotNumber), each before its scaling, averaged: what a receiver gets on average over the eyes'
// draws (per draw the scale also averaged), against the rays. --texels P: also each texel of receiving
// patch P, as "T x y z gathered rays" lines.
//
// SCENE_NAME is a built-in scene (cpgi generate's names); PATCH an atlas patch index (-1 lists them).
// --regions sets both the ordinary and the strong shots' regions per edge.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/context.h"
#include "core/image_io.h"
#include "core/quads.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "scenes/stability_scenes.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// Unshot radiosity at y (normal n) as lit by a downward-facing point lamp at `lamp` (relative units), or 1.
struct Lighting {
  bool lit = false;
  glm::vec3 lamp{0.0f};
  float at(const glm::vec3& y, const glm::vec3& n) const {
    if (!lit) return 1.0f;
    const glm::vec3 d = lamp - y;
    const float r2 = glm::dot(d, d), r = std::sqrt(r2);
    return std::max(0.0f, glm::dot(n, d) / r) * std::max(0.0f, d.y / r) / r2;
  }
};

// Irradiance at receiver texel t from the shooter's texels (unit radiosity), by `points`² stratified points
// per shooter texel, with visibility by rays.
double exactIrradiance(const cpgi::LightmapAtlas& atlas, const cpgi::RayScene& rays,
                       const std::vector<size_t>& shooter, const cpgi::Patch& sp,
                       const std::vector<float>& unshot, size_t t, int points) {
  const glm::vec3 x = atlas.position[t], n = atlas.normal[t];
  double sum = 0.0;
  for (size_t s : shooter) {
    const double a = atlas.area[s] / double(points * points);
    for (int j = 0; j < points; ++j)
      for (int i = 0; i < points; ++i) {
        const glm::vec3 y = atlas.position[s] + ((i + 0.5f) / points - 0.5f) * sp.texelU +
                            ((j + 0.5f) / points - 0.5f) * sp.texelV;
        glm::vec3 v = y - x;
        const float r2 = glm::dot(v, v);
        const float r = std::sqrt(r2);
        v /= r;
        const float ci = glm::dot(n, v), cs = -glm::dot(sp.normal, v);
        if (ci <= 0.0f || cs <= 0.0f) continue;
        // Both ends off their surfaces, and the ray between those: along v from x lifted by eps the
        // ray met the shooter's own plane short of y at grazing angles (seed1: B's ceiling seen from A's
        // floor through the door read 0.42 of the light there at its far end).
        const float eps = 1e-4f * rays.diagonal();
        const glm::vec3 from = x + n * eps, to = y + sp.normal * eps;
        const float length = glm::distance(from, to);
        if (length > eps && rays.occluded(from, (to - from) / length, 0.0f, length - eps)) continue;
        const float b = unshot[s];
        sum += b * a * ci * cs / (kPi * r2);
      }
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s SCENE_NAME PATCH [--density D] [--points N] [--hemisphere] [--regions R] "
                 "[--far-field F] [--lit X,Y,Z | --residual-from BAKE_DIR] [--draws N] [--texels P]\n",
                 argv[0]);
    return 1;
  }
  float density = 10.0f, farField = 2.0f;
  int points = 4, regions = 2, draws = 1, texelsOf = -1, rayEyes = 1;
  bool hemisphere = false, nearRays = true;
  Lighting light;
  std::string bakeDir;
  for (int i = 3; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--density") && i + 1 < argc)
      density = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--points") && i + 1 < argc)
      points = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--regions") && i + 1 < argc)
      regions = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--eye-gated"))
      nearRays = false;
    else if (!std::strcmp(argv[i], "--ray-eyes") && i + 1 < argc)
      rayEyes = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--texels") && i + 1 < argc)
      texelsOf = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--draws") && i + 1 < argc)
      draws = std::max(1, std::stoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--far-field") && i + 1 < argc)
      farField = std::stof(argv[++i]);
    else if (!std::strcmp(argv[i], "--lit") && i + 1 < argc) {
      light.lit = std::sscanf(argv[++i], "%f,%f,%f", &light.lamp.x, &light.lamp.y, &light.lamp.z) == 3;
      if (!light.lit) return std::fprintf(stderr, "--lit takes X,Y,Z\n"), 1;
    } else if (!std::strcmp(argv[i], "--residual-from") && i + 1 < argc)
      bakeDir = argv[++i];
    else if (!std::strcmp(argv[i], "--hemisphere"))
      hemisphere = true;
  }
  try {
    cpgi::Context ctx;
    cpgi::Scene scene = cpgi::makeBuiltinScene(argv[1]).scene;
    for (auto& m : scene.materials) m.emission = glm::vec3(0.0f);
    const cpgi::QuadSet quads = cpgi::findQuads(scene);
    cpgi::AtlasParams ap;
    ap.density = density;
    const cpgi::LightmapAtlas atlas = cpgi::buildAtlas(scene, quads, ap, ctx);
    const int shooterPatch = std::stoi(argv[2]);
    if (shooterPatch < 0 || size_t(shooterPatch) >= atlas.patches.size()) {
      for (size_t p = 0; p < atlas.patches.size(); ++p) {
        const auto& q = atlas.patches[p];
        std::printf("patch %zu: %s, normal %.2f %.2f %.2f, %.2f m², %dx%d texels\n", p,
                    scene.nodePaths[scene.triangles[q.triangles[0]].node].c_str(), q.normal.x, q.normal.y,
                    q.normal.z, q.area, q.w, q.h);
      }
      return 0;
    }
    const cpgi::Patch& sp = atlas.patches[size_t(shooterPatch)];
    std::vector<size_t> shooter;
    std::vector<float> unshot(atlas.texelCount(), 0.0f);
    std::vector<glm::vec3> fromBake;
    if (!bakeDir.empty()) {
      const cpgi::ImageRGB lightmap = cpgi::readExr(bakeDir + "/lightmap.exr");
      if (size_t(lightmap.width) * lightmap.height != atlas.texelCount())
        return std::fprintf(stderr, "%s: not this atlas\n", bakeDir.c_str()), 1;
      fromBake = lightmap.pixels;
    }
    std::vector<glm::vec3> prior(atlas.texelCount(), glm::vec3(0.0f));
    double power = 0.0;
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (atlas.patch[t] == shooterPatch) {
        shooter.push_back(t);
        const float b = fromBake.empty() ? light.at(atlas.position[t], atlas.normal[t])
                                         : (fromBake[t].x + fromBake[t].y + fromBake[t].z) / 3.0f;
        unshot[t] = b;
        prior[t] = glm::vec3(b) / glm::max(atlas.albedo[t], glm::vec3(1e-3f));
        power += 3.0 * b * atlas.area[t];
      }
    cpgi::EglContext gl(ctx);
    cpgi::SolverParams sp2;
    sp2.visibility = hemisphere ? cpgi::Visibility::Hemisphere : cpgi::Visibility::Hemicube;
    sp2.maxShots = 1;
    sp2.maxRegions = regions;
    sp2.strongShotFraction =
        1.0;  // an ordinary shot's layout (the shot is under its whole power by rounding only)
    sp2.strongShotRegions = regions;
    sp2.unshotFraction = 1e-6;
    sp2.farField = farField;
    cpgi::SolveControls controls;
    controls.readTransfer = true;
    cpgi::PriorShot ps;
    ps.irradiance = prior;
    ps.emitted = power;
    controls.priorShot = &ps;
    // Each draw's irradiance before its scaling, averaged over the draws; the scales averaged beside it.
    std::vector<glm::dvec3> gathered(atlas.texelCount(), glm::dvec3(0.0));
    double scale = 0.0;
    for (int d = 0; d < draws; ++d) {
      const cpgi::SolveResult r =
          cpgi::solveProgressive(scene, atlas, sp2, gl, ctx, controls, {.firstShotNumber = uint32_t(d)});
      const double s = r.shotScales.empty() ? 1.0 : double(r.shotScales[0]);
      scale += s / draws;
      for (size_t t = 0; t < atlas.texelCount(); ++t) gathered[t] += glm::dvec3(r.incident[t]) / (s * draws);
    }

    const cpgi::RayScene rays(scene);
    // The same shot by the CPU ray solver's shot (radiosity/cpu/ray_shot.h), averaged over the same draws.
    std::vector<double> byRays(atlas.texelCount(), 0.0);
    {
      const cpgi::RayShotScene shots(scene, atlas, rays);
      const auto layouts = cpgi::layoutShooters(scene, atlas, {sp2.regionSize, regions});
      std::vector<glm::vec3> residual(atlas.texelCount(), glm::vec3(0.0f));
      for (size_t t : shooter) residual[t] = glm::vec3(unshot[t]);
      for (int d = 0; d < draws; ++d) {
        const cpgi::RayShotGain g =
            cpgi::shootByRays(shots, shooterPatch, layouts[size_t(shooterPatch)], residual, uint32_t(d + 1),
                              {farField, 1024, rayEyes, nearRays});
        for (size_t k = 0; k < shots.texels.size(); ++k)
          byRays[shots.texels[k]] +=
              (g.irradiance[k].x + g.irradiance[k].y + g.irradiance[k].z) / 3.0 / draws;
      }
    }
    std::vector<double> exact(atlas.texelCount(), 0.0);
    tbb::parallel_for(size_t(0), atlas.texelCount(), [&](size_t t) {
      if (atlas.patch[t] >= 0 && atlas.patch[t] != shooterPatch)
        exact[t] = exactIrradiance(atlas, rays, shooter, sp, unshot, t, points);
    });
    // What the receive pass gathered, before the solver scaled the shot to its eyes' covered share.
    std::vector<double> bakeP(atlas.patches.size(), 0.0), exactP(atlas.patches.size(), 0.0),
        absP(atlas.patches.size(), 0.0), raysP(atlas.patches.size(), 0.0);
    double bakeAll = 0.0, exactAll = 0.0, raysAll = 0.0;
    for (size_t t = 0; t < atlas.texelCount(); ++t) {
      if (atlas.patch[t] < 0 || atlas.patch[t] == shooterPatch) continue;
      const glm::dvec3 in = gathered[t];
      const double b = (in.x + in.y + in.z) / 3.0 * atlas.area[t], e = exact[t] * atlas.area[t];
      bakeP[size_t(atlas.patch[t])] += b;
      exactP[size_t(atlas.patch[t])] += e;
      absP[size_t(atlas.patch[t])] += std::abs(b - e);
      raysP[size_t(atlas.patch[t])] += byRays[t] * atlas.area[t];
      raysAll += byRays[t] * atlas.area[t];
      bakeAll += b;
      exactAll += e;
    }
    if (texelsOf >= 0)  // --texels P: "T x y z gathered rays" per texel of receiving patch P
      for (size_t t = 0; t < atlas.texelCount(); ++t)
        if (atlas.patch[t] == texelsOf)
          std::printf("T %.3f %.3f %.3f %.6f %.6f\n", atlas.position[t].x, atlas.position[t].y,
                      atlas.position[t].z, (gathered[t].x + gathered[t].y + gathered[t].z) / 3.0, exact[t]);
    const double shot = power / 3.0;
    std::printf(
        "shot %.4f W (per channel); gathered %.4f (%.4f of it), by rays %.4f (%.4f); then scaled by %.4f "
        "(mean over %d draws); the ray solver's shot gathered %.4f (%.4f)\n",
        shot, bakeAll, bakeAll / shot, exactAll, exactAll / shot, scale, draws, raysAll, raysAll / shot);
    for (size_t p = 0; p < atlas.patches.size(); ++p) {
      if (exactP[p] < 1e-4 * shot && bakeP[p] < 1e-4 * shot) continue;
      const auto& q = atlas.patches[p];
      std::printf(
          "  %3zu %-22s n %+.0f %+.0f %+.0f  bake %.4f exact %.4f  ratio %.3f  |diff| %.4f  rays %.4f ratio "
          "%.3f\n",
          p, scene.nodePaths[scene.triangles[q.triangles[0]].node].c_str(), q.normal.x, q.normal.y,
          q.normal.z, bakeP[p], exactP[p], exactP[p] > 0 ? bakeP[p] / exactP[p] : 0.0, absP[p], raysP[p],
          exactP[p] > 0 ? raysP[p] / exactP[p] : 0.0);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
