// Binned directional emission (radiosity/solve/emission_bins.h): bins normalised by their projected solid
// angle make ∫ f cos θ dω = π for any weights, in each channel; a square above a point gives, by rays, its
// closed-form irradiance, all of it in the bins its directions fall in; an emitter whose colour depends on
// the direction lights a wall with the colour each part of it gets.
#include "radiosity/solve/emission_bins.h"

#include <cmath>
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
using namespace testing;

constexpr double kPi = std::numbers::pi;

// (1/π) ∫ f cos θ dω per channel by cosine-weighted sampling: 1 for a normalised emission.
glm::dvec3 meanFactor(const ArrivalBins& bins, const glm::vec3& n, int samples) {
  const BinFrame frame = binFrame(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  glm::dvec3 sum(0.0);
  for (int k = 0; k < samples; ++k) {
    const float r = std::sqrt(U(rng)), phi = float(2.0 * kPi) * U(rng);
    const glm::vec3 w = r * std::cos(phi) * frame.t1 + r * std::sin(phi) * frame.t2 +
                        std::sqrt(std::max(0.0f, 1.0f - r * r)) * frame.n;
    sum += glm::dvec3(binnedEmissionFactor(bins, frame, glm::normalize(w)));
  }
  return sum / double(samples);
}

void expectEachChannel(const glm::dvec3& v, double expected, double tolerance) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], expected, tolerance) << "channel " << c;
}

TEST(EmissionBins, AnyWeightsKeepTheExitance) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  for (const glm::vec3 n :
       {glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f))}) {
    ArrivalBins bins{};
    for (glm::vec3& b : bins)  // spiky, with empty bins, each channel its own way; no blue at all
      b = glm::vec3(U(rng) < 0.3f ? 10.0f * U(rng) : 0.0f, U(rng) < 0.5f ? U(rng) : 0.0f, 0.0f);
    expectEachChannel(meanFactor(bins, n, 400000), 1.0, 0.01);
    EXPECT_EQ(binnedEmissionFactor(bins, binFrame(n), n).b, 1.0f);  // a channel without weights: Lambertian
    expectEachChannel(meanFactor(ArrivalBins{}, n, 1000), 1.0, 1e-9);
    EXPECT_EQ(binnedEmissionFactor(bins, binFrame(n), -n), glm::vec3(0.0f));  // nothing behind the surface
  }
}

TEST(EmissionBins, AnEmitterNormalisedOnceReadsAsTheBinsThemselves) {
  // portalArrivalBins reads a binned portal texel along every ray that meets it through a BinnedEmitter:
  // the same floats as normalising the bins at each reading, whatever the bins, normal and direction.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (int texel = 0; texel < 20; ++texel) {
    ArrivalBins bins{};
    for (glm::vec3& b : bins)  // negative bins count as zero; one texel in four without any blue
      b = glm::vec3(U(rng) > 0.0f ? 5.0f * U(rng) : 0.0f, U(rng), texel % 4 == 0 ? 0.0f : U(rng) + 1.0f);
    const glm::vec3 n = glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));
    const BinnedEmitter emitter = binnedEmitter(bins, n);
    for (int k = 0; k < 200; ++k) {
      const glm::vec3 omega = glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));  // behind it too
      EXPECT_EQ(binnedEmissionFactor(emitter, omega), binnedEmissionFactor(bins, binFrame(n), omega));
    }
  }
}

TEST(EmissionBins, BinsHoldTheirProjectedSolidAngle) {
  // Cosine-weighted directions fall into each bin in proportion to its share of the projected disk; the
  // rings are of equal angle, so a rim bin holds far less than one at the pole.
  const BinFrame frame = binFrame(glm::vec3(0, 1, 0));
  std::vector<int> count(kArrivalBins, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const int samples = 400000;
  for (int k = 0; k < samples; ++k) {
    const float r = std::sqrt(U(rng)), phi = float(2.0 * kPi) * U(rng);
    const glm::vec3 w = r * std::cos(phi) * frame.t1 + r * std::sin(phi) * frame.t2 +
                        std::sqrt(std::max(0.0f, 1.0f - r * r)) * frame.n;
    ++count[size_t(arrivalBin(frame, glm::normalize(w)))];
  }
  double shares = 0.0;
  for (int b = 0; b < kArrivalBins; ++b) {
    const double expected = samples * binProjectedArea(b);
    EXPECT_NEAR(count[size_t(b)], expected, 4.0 * std::sqrt(expected) + 2.0) << "bin " << b;
    shares += binProjectedArea(b);
  }
  EXPECT_NEAR(shares, 1.0, 1e-9);
  const int centre = (kBinGrid / 2) * kBinGrid + kBinGrid / 2;
  EXPECT_GT(binProjectedArea(centre), 5.0 * binProjectedArea(0));  // a corner of the rim
}

TEST(EmissionBins, EachBinsDirectionsFallInIt) {
  // binDirection is binSquarePoint's inverse: a point of a cell gives a direction of that cell's bin, in
  // rings of equal angle (the middle of the square's right edge half-way out: 45° off the normal).
  const BinFrame frame = binFrame(glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0.02f, 0.98f);
  for (int b = 0; b < kArrivalBins; ++b) {
    const glm::vec2 s(float(b % kBinGrid) + U(rng), float(b / kBinGrid) + U(rng));
    const glm::vec3 w = binDirection(frame, s);
    EXPECT_GT(glm::dot(w, frame.n), 0.0f);
    EXPECT_EQ(arrivalBin(frame, w), b);
    const glm::vec2 back = binSquarePoint(frame, w);
    EXPECT_NEAR(back.x, s.x, 1e-3f);
    EXPECT_NEAR(back.y, s.y, 1e-3f);
  }
  const glm::vec3 halfway = binDirection(frame, glm::vec2(0.75f, 0.5f) * float(kBinGrid));
  EXPECT_NEAR(glm::dot(halfway, frame.n), std::cos(kPi / 4.0), 1e-5);
}

TEST(EmissionBins, RaysGiveASquaresIrradianceInItsDirections) {
  // A 1 m square 1 m above a small patch at the origin, sending 1 W/m² everywhere: the point-to-square
  // form factor (2/π)(2 · 0.5/√1.25 · atan(0.5/√1.25)) = 0.2394; every direction from it lies within
  // sin θ ≤ 1/√3 (θ ≤ 35.3°), inside the concentric map's square of half-width 0.39.
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
  addRect(scene, {-0.5f, -0.5f, 1.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, m);  // faces −z
  Context ctx;
  AtlasParams params;
  params.density = 8.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), params, ctx);
  const RayScene rays(scene);
  const float side = 0.01f;
  const ArrivalBins bins = traceArrivalBins(
      rays, atlas, {-0.5f * side, -0.5f * side, 0.0f}, {side, 0.0f, 0.0f}, {0.0f, side, 0.0f},
      {0.0f, 0.0f, 1.0f}, 160000, 5, [](size_t, const glm::vec3&) { return glm::vec3(1.0f, 0.5f, 0.0f); });
  glm::dvec3 total(0.0), outer(0.0);
  for (int b = 0; b < kArrivalBins; ++b) {
    total += glm::dvec3(bins[size_t(b)]);
    // Cells wholly past 0.4 of the square's half-width: beyond 36° of the normal.
    const int i = b % kBinGrid, j = b / kBinGrid;
    if (std::min({i, j, kBinGrid - 1 - i, kBinGrid - 1 - j}) < int(0.3f * float(kBinGrid)))
      outer += glm::dvec3(bins[size_t(b)]);
  }
  const double expected = 2.0 / kPi * (2.0 * 0.5 / std::sqrt(1.25) * std::atan(0.5 / std::sqrt(1.25)));
  EXPECT_NEAR(total.r, expected, 0.015 * expected);  // 3σ of 160k rays
  EXPECT_NEAR(total.g, 0.5 * expected, 0.015 * expected);
  EXPECT_EQ(total.b, 0.0);
  EXPECT_EQ(outer, glm::dvec3(0.0));
  // The same light seen as one emitter of the far side: its f is 0 outside those rings, and it still
  // keeps the exitance; blue, which no ray brought, is Lambertian.
  const BinFrame far = binFrame({0.0f, 0.0f, -1.0f});
  EXPECT_EQ(binnedEmissionFactor(bins, far, glm::normalize(glm::vec3(1.0f, 0.0f, -0.2f))),
            glm::vec3(0, 0, 1));
  EXPECT_GT(binnedEmissionFactor(bins, far, glm::vec3(0.0f, 0.0f, -1.0f)).r, 1.5f);
  expectEachChannel(meanFactor(bins, far.n, 400000), 1.0, 0.01);
}

// Bins of cosine-weighted directions around n weighted by w(ω) per channel.
ArrivalBins binsOf(const glm::vec3& n, const std::function<glm::vec3(const glm::vec3&)>& w,
                   int samples = 200000) {
  const BinFrame frame = binFrame(n);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  ArrivalBins bins{};
  for (int k = 0; k < samples; ++k) {
    const float r = std::sqrt(U(rng)), phi = float(2.0 * kPi) * U(rng);
    const glm::vec3 d = glm::normalize(r * std::cos(phi) * frame.t1 + r * std::sin(phi) * frame.t2 +
                                       std::sqrt(std::max(0.0f, 1.0f - r * r)) * frame.n);
    bins[size_t(arrivalBin(frame, d))] += w(d);
  }
  return bins;
}

// A 1 m² emitter whose bins send most of its light towards a wall at right angles to it, sharing an edge
// (a portal and the reveal beside it), some of it towards one side, its red and blue each their own way:
// what the wall gets in each channel, texel by texel and in all, against the integral of the bins'
// radiance over the emitter by the midpoint rule; and in a closed black box, what the walls catch is what
// left it.
void binnedEmitterLightsAsIntegrated(ShotEngine& engine, double wallTolerance, double worstTexel) {
  const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  // Per emitter row y: the light leans towards −z more the higher the row, and towards +y a little.
  auto binsAt = [&](float y) {
    return binsOf(X, [&](const glm::vec3& d) {
      const float towardsWall = std::pow(std::max(0.0f, -d.z), 2.0f) * (1.0f + 4.0f * y);
      const float sideways = std::max(0.0f, d.y), away = std::max(0.0f, d.z);
      return glm::vec3(0.2f + towardsWall + 0.5f * sideways, 0.2f + towardsWall,
                       0.1f + 2.0f * away + sideways);
    });
  };
  Scene scene;
  const uint32_t black = testing::addMaterial(scene, glm::vec3(0.0f));
  const uint32_t lamp = testing::addMaterial(scene, glm::vec3(0.0f), glm::vec3(10.0f));
  testing::addRect(scene, glm::vec3(0.0f), Y, Z, lamp);   // x = 0, normal +x
  testing::addRect(scene, glm::vec3(0.0f), X, Y, black);  // z = 0, normal +z
  Context ctx;
  const int perQuad = 16;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.texelsPerQuad = perQuad}, ctx);
  const float texel = 1.0f / float(perQuad);
  std::vector<ArrivalBins> rowBins(static_cast<size_t>(perQuad));
  for (int i = 0; i < perQuad; ++i) rowBins[size_t(i)] = binsAt((float(i) + 0.5f) * texel);
  std::vector<glm::vec4> lobes(atlas.texelCount(), glm::vec4(0.0f));
  std::vector<float> bins;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && atlas.emission[i] != glm::vec3(0.0f)) {
      const int row = std::clamp(int(atlas.position[i].y / texel), 0, perQuad - 1);
      lobes[i] = binnedLobe(int(bins.size() / kBinSlotFloats));
      const EmissionBinSlot f = normalisedEmissionBins(rowBins[size_t(row)]);
      bins.insert(bins.end(), f.begin(), f.end());
    }
  SolverParams sp;
  sp.itemBuffer = 512;
  const SolveResult r =
      solveProgressive(scene, atlas, sp, engine, ctx, SolveControls{.readTransfer = true},
                       ShotShape{.directionalEmission = true, .emissionLobes = lobes, .emissionBins = bins});
  ASSERT_EQ(r.shots, 1);
  const BinFrame frame = binFrame(X);
  const int n = 160;
  auto irradiance = [&](const glm::vec3& x) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < n; ++i) {
      const ArrivalBins& b = rowBins[size_t(std::min(int((i + 0.5f) / n / texel), perQuad - 1))];
      for (int j = 0; j < n; ++j) {
        const glm::vec3 s(0.0f, (i + 0.5f) / n, (j + 0.5f) / n), v = x - s;
        const float d2 = glm::dot(v, v);
        const glm::vec3 w = v / std::sqrt(d2);
        if (w.x > 0.0f && w.z < 0.0f)
          sum += 10.0 * glm::dvec3(binnedEmissionFactor(b, frame, w)) / kPi * double(w.x * -w.z / d2);
      }
    }
    return sum / double(n * n);
  };
  glm::dvec3 gpu(0.0), cpu(0.0), worst(0.0);
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0 || atlas.normal[t].z < 0.99f) continue;
    const glm::vec3 c = atlas.position[t];
    if (c.x < 2.0f * texel) continue;  // a lamp shot's near receivers, as in EmissionLobes
    const glm::dvec3 e = irradiance(c), g = glm::dvec3(r.incident[t]);
    gpu += g * double(atlas.area[t]);
    cpu += e * double(atlas.area[t]);
    for (int k = 0; k < 3; ++k)
      if (e[k] > 0.2) worst[k] = std::max(worst[k], std::abs(g[k] / e[k] - 1.0));
  }
  std::printf("%s binned: wall R %.4f G %.4f B %.4f of the integral, worst texel %.3f %.3f %.3f off\n",
              engine.name().c_str(), gpu.r / cpu.r, gpu.g / cpu.g, gpu.b / cpu.b, worst.r, worst.g, worst.b);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(gpu[k] / cpu[k], 1.0, wallTolerance) << "channel " << k;
    EXPECT_LT(worst[k], worstTexel) << "channel " << k;
  }
  // The colour goes where its bins send it: the wall gets the blue that leans away from it only a little.
  EXPECT_LT(cpu.b / cpu.r, 0.5);

  // Closed black box: the light caught is the light emitted, as for a Lambertian.
  Scene box;
  const uint32_t boxBlack = testing::addMaterial(box, glm::vec3(0.0f));
  const uint32_t boxLamp = testing::addMaterial(box, glm::vec3(0.0f), glm::vec3(100.0f));
  testing::addClosedBox(box, glm::vec3(-1, 0, -1), glm::vec3(1, 2, 1), boxBlack);
  testing::addRect(box, glm::vec3(-0.1f, 0.001f, -0.1f), glm::vec3(0, 0, 0.2f), glm::vec3(0.2f, 0, 0),
                   boxLamp);
  const LightmapAtlas boxAtlas = buildAtlas(box, findQuads(box), AtlasParams{.texelsPerQuad = 32}, ctx);
  const EmissionBinSlot aimed = normalisedEmissionBins(
      binsOf(Y, [](const glm::vec3& d) { return glm::vec3(d.x > 0.3f ? 1.0f : 0.0f); }));
  std::vector<glm::vec4> boxLobes(boxAtlas.texelCount(), glm::vec4(0.0f));
  for (size_t i = 0; i < boxAtlas.texelCount(); ++i)
    if (boxAtlas.patch[i] >= 0 && boxAtlas.emission[i] != glm::vec3(0.0f)) boxLobes[i] = binnedLobe(0);
  sp.itemBuffer = 256;
  const SolveResult caught = solveProgressive(box, boxAtlas, sp, engine, ctx, SolveControls{},
                                              ShotShape{.directionalEmission = true,
                                                        .emissionLobes = boxLobes,
                                                        .emissionBins = std::span<const float>(aimed)});
  auto wall = [&](glm::vec3 normal) {
    double sum = 0.0;
    for (size_t i = 0; i < boxAtlas.texelCount(); ++i)
      if (boxAtlas.patch[i] >= 0 && glm::dot(boxAtlas.normal[i], normal) > 0.99f)
        sum += double(caught.arrivals[i].w) * boxAtlas.area[i];
    return sum;
  };
  EXPECT_NEAR(caught.energy.received, caught.energy.emitted, 3e-3 * caught.energy.emitted);
  EXPECT_LT(wall({1, 0, 0}), 1e-3 * caught.energy.emitted);  // the wall at −x faces away from the light
  EXPECT_GT(wall({-1, 0, 0}), 0.3 * caught.energy.emitted);
}

TEST(EmissionBins, BinnedEmitterLightsAsIntegratedOnGl) {
  Context ctx;
  EglContext gl(ctx);
  GlShotEngine engine(gl);
  binnedEmitterLightsAsIntegrated(engine, 0.02, 0.15);
}

TEST(EmissionBins, BinnedEmitterLightsAsIntegratedOnRays) {
  RayShotEngine engine;
  binnedEmitterLightsAsIntegrated(engine, 0.02, 0.15);
}

}  // namespace
}  // namespace cpgi
