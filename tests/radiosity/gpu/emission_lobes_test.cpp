// Directional emission lobes (radiosity/solve/emission_lobes.h): ∫ f cos θ dω = π by quadrature for every
// kind of lobe, the fit of known arrivals (diffuse → Lambertian, a beam → a lobe around it, a mixture →
// its share), and on the GPU an emitter aimed at one of two walls of a black box: that wall gets more than
// under a Lambertian, the total caught stays the emitted power.
#include "radiosity/solve/emission_lobes.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/quads.h"
#include "radiosity/cpu/ray_shot_engine.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

constexpr double kPi = std::numbers::pi;

// Σ f(ω) cos θ over the hemisphere around n, and the first moment of that emission, by the midpoint rule
// in (θ, φ) on a grid fine enough for lobes of 0.02 rad (800 steps: 0.002 rad).
struct Emission {
  double total = 0.0;
  glm::dvec3 mean{0.0};  ///< ∫ ω f cos θ dω / ∫ f cos θ dω
};
Emission integrate(const glm::vec4& lobe, const glm::vec3& n, int steps = 800, float blur2 = 0.0f) {
  const glm::vec3 t = glm::normalize(std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                                          : glm::cross(n, glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(n, t);
  Emission e;
  const double dt = 0.5 * kPi / steps, dp = 2.0 * kPi / (4 * steps);
  for (int i = 0; i < steps; ++i) {
    const double th = (i + 0.5) * dt;
    for (int j = 0; j < 4 * steps; ++j) {
      const double ph = (j + 0.5) * dp;
      const glm::vec3 w = float(std::sin(th) * std::cos(ph)) * t + float(std::sin(th) * std::sin(ph)) * b +
                          float(std::cos(th)) * n;
      const double f = emissionLobeFactor(lobe, n, w, blur2) * std::cos(th) * std::sin(th) * dt * dp;
      e.total += f;
      e.mean += f * glm::dvec3(w);
    }
  }
  e.mean /= e.total;
  return e;
}

glm::vec3 tilted(const glm::vec3& n, const glm::vec3& t, double degrees) {
  const double a = degrees * kPi / 180.0;
  return glm::normalize(float(std::cos(a)) * n + float(std::sin(a)) * t);
}

glm::vec4 momentsOfBeam(const glm::vec3& omega, const glm::vec3& n, float weight) {
  return arrivalMoment(omega, n, weight);
}

// Cosine-weighted directions around n (a Lambertian's arrivals), as moments.
glm::vec4 momentsOfDiffuse(const glm::vec3& n, float weight, int samples = 20000) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const glm::vec3 t(1, 0, 0), b = glm::cross(n, t);
  glm::vec4 sum(0.0f);
  for (int i = 0; i < samples; ++i) {
    const float r = std::sqrt(u01(rng)), ph = float(2.0 * kPi) * u01(rng);
    const glm::vec3 w =
        r * std::cos(ph) * t + r * std::sin(ph) * b + std::sqrt(std::max(0.0f, 1 - r * r)) * n;
    sum += arrivalMoment(w, n, weight / samples);
  }
  return sum;
}

const glm::vec3 kN(0, 0, 1), kT(1, 0, 0);

TEST(EmissionLobes, LambertianIsZero) {
  EXPECT_FLOAT_EQ(emissionLobeFactor(glm::vec4(0.0f), kN, tilted(kN, kT, 40)), 1.0f);
  EXPECT_EQ(emissionLobeFactor(glm::vec4(0.0f), kN, -kN), 0.0f);  // nothing behind the surface
  EXPECT_NEAR(integrate(glm::vec4(0.0f), kN, 400).total, kPi, 1e-5);
}

TEST(EmissionLobes, EveryLobeIntegratesToPi) {
  // Beams at 0°, 35°, 70° and 85°, narrow to wide, and half-diffuse mixtures; a tilted normal too.
  const glm::vec3 n2 = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  struct Case {
    glm::vec3 n;
    glm::vec4 moments;
    float width;
  };
  const std::vector<Case> cases = {
      {kN, momentsOfBeam(kN, kN, 1.0f), 0.02f},
      {kN, momentsOfBeam(tilted(kN, kT, 35), kN, 1.0f), 0.05f},
      {kN, momentsOfBeam(tilted(kN, kT, 70), kN, 1.0f), 0.1f},
      {kN, momentsOfBeam(tilted(kN, kT, 85), kN, 1.0f), 0.05f},
      {kN, momentsOfBeam(tilted(kN, kT, 35), kN, 1.0f) + momentsOfDiffuse(kN, 1.0f), 0.05f},
      {kN, momentsOfBeam(tilted(kN, kT, 20), kN, 1.0f) + momentsOfBeam(tilted(kN, -kT, 50), kN, 1.0f), 0.05f},
      {n2, momentsOfBeam(tilted(n2, glm::normalize(glm::cross(n2, kT)), 60), n2, 2.0f), 0.05f},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const glm::vec4 lobe = fitEmissionLobe(cases[i].moments, cases[i].n, cases[i].width);
    EXPECT_GT(glm::dot(glm::vec3(lobe), cases[i].n), 0.3f) << "case " << i;  // really directional
    EXPECT_NEAR(integrate(lobe, cases[i].n).total, kPi, 1e-3 * kPi) << "case " << i;
    // Widened as the solver does for a large receiver texel: still π.
    EXPECT_NEAR(integrate(lobe, cases[i].n, 500, 0.05f).total, kPi, 1e-3 * kPi) << "case " << i;
  }
}

TEST(EmissionLobes, DiffuseArrivalsFitALambertian) {
  const glm::vec4 lobe = fitEmissionLobe(momentsOfDiffuse(kN, 3.0f), kN, 0.05f);
  const float a = glm::dot(glm::vec3(lobe), kN);
  EXPECT_LT(a, 0.03f);
  for (double deg : {0.0, 30.0, 60.0, 80.0})
    EXPECT_NEAR(emissionLobeFactor(lobe, kN, tilted(kN, kT, deg)), 1.0f, 0.05f);
}

TEST(EmissionLobes, ABeamKeepsItsDirection) {
  for (double deg : {0.0, 30.0, 60.0}) {
    const glm::vec3 beam = tilted(kN, kT, deg);
    const glm::vec4 lobe = fitEmissionLobe(momentsOfBeam(beam, kN, 1.0f), kN, 0.03f);
    EXPECT_NEAR(glm::dot(glm::vec3(lobe), kN), 1.0f, 1e-5f) << deg;  // all of it in the lobe
    const Emission e = integrate(lobe, kN);
    // The emission's mean direction is the beam's (within 1°), and it peaks there: 3° off the beam is
    // far weaker, a Lambertian's directions get next to nothing.
    EXPECT_GT(glm::dot(glm::normalize(e.mean), glm::dvec3(beam)), std::cos(kPi / 180.0)) << deg;
    const float peak = emissionLobeFactor(lobe, kN, beam);
    EXPECT_GT(peak, 100.0f) << deg;
    EXPECT_LT(emissionLobeFactor(lobe, kN, tilted(kN, kT, deg + 8.0)), 0.05f * peak) << deg;
    EXPECT_LT(emissionLobeFactor(lobe, kN, tilted(kN, -kT, 45.0)), 1e-3f) << deg;
  }
}

TEST(EmissionLobes, HalfBeamHalfDiffuseSplitsInTwo) {
  const glm::vec3 beam = tilted(kN, kT, 40);
  const glm::vec4 lobe =
      fitEmissionLobe(momentsOfBeam(beam, kN, 1.0f) + momentsOfDiffuse(kN, 1.0f), kN, 0.05f);
  EXPECT_NEAR(glm::dot(glm::vec3(lobe), kN), 0.5f, 0.03f);
  // Away from the beam the emission is the diffuse half.
  EXPECT_NEAR(emissionLobeFactor(lobe, kN, tilted(kN, -kT, 40)), 0.5f, 0.03f);
  // The moments of what it emits are the moments it was fitted to (the lobe is that narrow).
  const Emission e = integrate(lobe, kN);
  const glm::vec4 m = momentsOfBeam(beam, kN, 1.0f) + momentsOfDiffuse(kN, 1.0f);
  const glm::vec3 meanU = glm::vec3(m) / m.w - glm::dot(glm::vec3(m) / m.w, kN) * kN;
  const glm::dvec3 emittedU = e.mean - glm::dot(e.mean, glm::dvec3(kN)) * glm::dvec3(kN);
  EXPECT_NEAR(emittedU.x, meanU.x, 0.01);
  EXPECT_NEAR(emittedU.y, meanU.y, 0.01);
}

TEST(EmissionLobes, ZeroMomentsAreLambertian) {
  EXPECT_EQ(fitEmissionLobe(glm::vec4(0.0f), kN, 0.05f), glm::vec4(0.0f));
}

// A 0.2 m emitter on the floor of a closed black 2 m box, its lobe aimed 45° at the +x wall: that wall gets
// more than from a Lambertian emitter, the −x wall less, and the total caught by all walls is the emitted
// power as much as it is for the Lambertian one.
void aimedEmitterInABox(ShotEngine& engine) {
  Scene scene;
  const uint32_t black = testing::addMaterial(scene, glm::vec3(0.0f));
  const uint32_t lamp = testing::addMaterial(scene, glm::vec3(0.0f), glm::vec3(100.0f));
  testing::addClosedBox(scene, glm::vec3(-1, 0, -1), glm::vec3(1, 2, 1), black);
  testing::addRect(scene, glm::vec3(-0.1f, 0.001f, -0.1f), glm::vec3(0, 0, 0.2f), glm::vec3(0.2f, 0, 0),
                   lamp);
  Context ctx;
  AtlasParams ap;
  ap.texelsPerQuad = 32;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), ap, ctx);
  SolverParams sp;
  sp.itemBuffer = 256;
  const glm::vec3 up(0, 1, 0), aim = glm::normalize(glm::vec3(1, 1, 0));
  std::vector<glm::vec4> lobes(atlas.texelCount(), glm::vec4(0.0f));
  for (size_t i = 0; i < lobes.size(); ++i)
    if (atlas.patch[i] >= 0 && atlas.emission[i] != glm::vec3(0.0f))
      lobes[i] = fitEmissionLobe(arrivalMoment(aim, up, 1.0f), up, 0.15f);
  const std::vector<glm::vec4> lambertian(lobes.size(), glm::vec4(0.0f));
  const SolveResult lambert =
      solveProgressive(scene, atlas, sp, engine, ctx, SolveControls{},
                       ShotShape{.directionalEmission = true, .emissionLobes = lambertian});
  const SolveResult aimed = solveProgressive(scene, atlas, sp, engine, ctx, SolveControls{},
                                             ShotShape{.directionalEmission = true, .emissionLobes = lobes});
  ASSERT_EQ(aimed.shots, 1);
  auto wall = [&](const SolveResult& r, glm::vec3 normal) {
    double sum = 0.0;
    for (size_t i = 0; i < atlas.texelCount(); ++i)
      if (atlas.patch[i] >= 0 && glm::dot(atlas.normal[i], normal) > 0.99f)
        sum += double(r.arrivals[i].w) * atlas.area[i];  // arrivals.w: irradiance, R + G + B
    return sum;                                          // W caught
  };
  const double emitted = aimed.energy.emitted;
  const double px = wall(aimed, {-1, 0, 0}), mx = wall(aimed, {1, 0, 0});
  const double lpx = wall(lambert, {-1, 0, 0}), lmx = wall(lambert, {1, 0, 0});
  EXPECT_GT(px, 2.0 * lpx);
  EXPECT_LT(mx, 0.1 * lmx);
  EXPECT_NEAR(lpx, lmx, 1e-3 * emitted);  // the Lambertian is symmetric
  // Energy: what the walls caught against what left the lamp (measured: +1.1e-3, the Lambertian +0.4e-3),
  // directional against Lambertian (+0.6e-3).
  EXPECT_NEAR(aimed.energy.received, emitted, 2e-3 * emitted);
  EXPECT_NEAR(aimed.energy.received, lambert.energy.received, 1e-3 * emitted);
  // The arrival moments hold the same power as the irradiance.
  double arrived = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0) arrived += double(aimed.arrivals[i].w) * atlas.area[i];
  EXPECT_NEAR(arrived, aimed.energy.received, 1e-4 * emitted);
}

// A 1 m² emitter whose lobes turn from its normal towards a wall at right angles to it, sharing an edge
// (a portal and the reveal of its door beside it): what the wall gets, texel by texel and in all, against
// the integral of the lobes' radiance over the emitter by the midpoint rule (a Lambertian emitter: 1.992
// against the analytic 2.000 W). Left out: the two columns along the edge, a lamp shot's near receivers,
// taken at 4×4 points over the texel a few millimetres from the emitter, which the midpoint rule does not
// resolve. Measured: the wall 1.011 / 1.016 of the integral, the worst texel 15.5 % / 18.4 % off (two and
// three texels from the edge, where the lobe is widened by the receiver texel's clamped footprint, and
// under the 70° lobes where pieces are taken whole across which the lobe changes). Widening by the
// shooter piece's extent and resolving pieces against radius / h instead brought this to 1.002 / 1.000
// and 3.9 % / 6.1 %, but darkened the reveals beside openings' A:B portals by 20–40 % at density 20
// (room B 4.4 % → 12.6 % per texel; bench/RESULTS.md): the bounds hold today's accuracy.

TEST(EmissionLobes, AimedEmitterOnGl) {
  Context ctx;
  EglContext gl(ctx);
  GlShotEngine engine(gl);
  aimedEmitterInABox(engine);
}

TEST(EmissionLobes, AimedEmitterOnRays) {
  RayShotEngine engine;
  aimedEmitterInABox(engine);
}

void aimedEmitterLightsTheWallBesideIt(ShotEngine& engine, double wallTolerance, double worstTexel) {
  Scene scene;
  const uint32_t black = testing::addMaterial(scene, glm::vec3(0.0f));
  const uint32_t lamp = testing::addMaterial(scene, glm::vec3(0.0f), glm::vec3(10.0f));
  const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  testing::addRect(scene, glm::vec3(0.0f), Y, Z, lamp);   // x = 0, normal +x
  testing::addRect(scene, glm::vec3(0.0f), X, Y, black);  // z = 0, normal +z
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.texelsPerQuad = 16}, ctx);
  SolverParams sp;
  sp.itemBuffer = 512;
  const float texel = 1.0f / 16.0f;
  for (const float tilt : {45.0f, 70.0f}) {
    // At height y the lobe is aimed tilt·y towards the wall, with a third of the light 30° sideways.
    auto lobeAt = [&](float y) {
      return fitEmissionLobe(
          arrivalMoment(tilted(X, -Z, tilt * y), X, 1.0f) + arrivalMoment(tilted(X, Y, 30), X, 0.5f), X,
          0.05f);
    };
    std::vector<glm::vec4> lobes(atlas.texelCount(), glm::vec4(0.0f));
    for (size_t i = 0; i < atlas.texelCount(); ++i)
      if (atlas.patch[i] >= 0 && atlas.emission[i] != glm::vec3(0.0f)) lobes[i] = lobeAt(atlas.position[i].y);
    const SolveResult r = solveProgressive(scene, atlas, sp, engine, ctx, SolveControls{.readTransfer = true},
                                           ShotShape{.directionalEmission = true, .emissionLobes = lobes});
    ASSERT_EQ(r.shots, 1);
    // E(x) = ∫ M f(ω) / π cos θs cos θr / d² dA over the emitter (M = 10 per channel), each texel row of
    // the emitter with its own lobe as on the GPU.
    const int n = 160;
    std::vector<glm::vec4> rowLobe(n);
    for (int i = 0; i < n; ++i) rowLobe[i] = lobeAt((std::floor((i + 0.5f) / n / texel) + 0.5f) * texel);
    auto irradiance = [&](const glm::vec3& x) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const glm::vec3 s(0.0f, (i + 0.5f) / n, (j + 0.5f) / n), v = x - s;
          const float d2 = glm::dot(v, v);
          const glm::vec3 w = v / std::sqrt(d2);
          if (w.x > 0.0f && w.z < 0.0f)
            sum += 10.0 * emissionLobeFactor(rowLobe[i], X, w) / kPi * w.x * -w.z / d2;
        }
      return sum / (n * n);
    };
    double gpu = 0.0, cpu = 0.0, worst = 0.0;
    for (size_t t = 0; t < atlas.texelCount(); ++t) {
      if (atlas.patch[t] < 0 || atlas.normal[t].z < 0.99f) continue;
      const glm::vec3 c = atlas.position[t];
      if (c.x < 2.0f * texel) continue;  // near receivers, see above
      const double e = irradiance(c), g = r.incident[t].r;
      gpu += g * atlas.area[t];
      cpu += e * atlas.area[t];
      if (e > 0.2) worst = std::max(worst, std::abs(g / e - 1.0));
    }
    EXPECT_NEAR(gpu / cpu, 1.0, wallTolerance) << tilt;
    EXPECT_LT(worst, worstTexel) << tilt;
    std::printf("%s, tilt %.0f: wall %.4f of the integral, worst texel %.3f off\n", engine.name().c_str(),
                tilt, gpu / cpu, worst);
  }
}

TEST(EmissionLobes, AimedEmitterLightsTheWallBesideItAsIntegratedOnGl) {
  Context ctx;
  EglContext gl(ctx);
  GlShotEngine engine(gl);
  aimedEmitterLightsTheWallBesideIt(engine, 0.025, 0.22);
}

TEST(EmissionLobes, AimedEmitterLightsTheWallBesideItAsIntegratedOnRays) {
  RayShotEngine engine;
  aimedEmitterLightsTheWallBesideIt(engine, 0.025, 0.22);
}

TEST(EmissionLobes, LobesNeedTheDirectionalSolver) {
  Scene scene;
  testing::addRect(scene, glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                   testing::addMaterial(scene, glm::vec3(0.5f), glm::vec3(1.0f)));
  Context ctx;
  EglContext gl(ctx);
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.texelsPerQuad = 4}, ctx);
  const SolverParams sp;
  const std::vector<glm::vec4> perTexel(atlas.texelCount()), tooFew(3);
  EXPECT_THROW(
      solveProgressive(scene, atlas, sp, gl, ctx, SolveControls{}, ShotShape{.emissionLobes = perTexel}),
      InputError);
  EXPECT_THROW(solveProgressive(scene, atlas, sp, gl, ctx, SolveControls{},
                                ShotShape{.directionalEmission = true, .emissionLobes = tooFew}),
               InputError);
}

}  // namespace
}  // namespace cpgi
