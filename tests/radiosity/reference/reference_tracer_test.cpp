#include "radiosity/reference/reference_tracer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "core/quads.h"
#include "radiosity/metrics/form_factors.h"
#include "tests/radiosity/reference/path_test_scenes.h"

namespace cpgi {
namespace {

using namespace cpgi::testing;
using namespace cpgi::pathtest;

/// |estimate − exact| within `sigmas` standard errors (plus a float-rounding floor), per channel.
void expectWithinError(const glm::vec3& estimate, const glm::vec3& error, const glm::vec3& exact,
                       float sigmas, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(estimate[c], exact[c], sigmas * error[c] + 1e-5f * std::abs(exact[c]))
        << what << " channel " << c << " (standard error " << error[c] << ")";
}

TEST(ReferenceTracer, WhiteFurnaceConvergesToEOverOneMinusRho) {
  // A closed box, every face with the same albedo and emission: B = E / (1 − ρ) per channel.
  const glm::vec3 albedo(0.2f, 0.5f, 0.8f), emission(1.0f, 2.0f, 0.5f);
  Scene scene;
  const uint32_t m = addMaterial(scene, albedo, emission);
  const auto faces = boxFaces(2.0f, {m, m, m, m, m, m});
  addFaces(scene, faces);
  const auto points = facePoints(scene, faces, 3);

  Context ctx;
  ReferenceParams params;
  params.spp = 4096;
  const ReferenceResult r = traceReference(scene, points, params, ctx);
  const glm::vec3 exact = emission / (1.0f - albedo);
  for (size_t i = 0; i < points.size(); ++i) {
    expectWithinError(r.radiosity[i], r.standardError[i], exact, 5.0f, "point " + std::to_string(i));
    EXPECT_LT(r.standardError[i].z / exact.z, 0.03f);  // the test would prove little with a huge error
    EXPECT_GT(r.standardError[i].z, 0.0f);
  }
  EXPECT_GT(r.rays, points.size() * params.spp);
}

/// An a × a emitter centred above the origin at height h, facing down; nothing else in the scene.
Scene emitterScene(float a, float h, glm::vec3 emission) {
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.0f), emission);
  addRect(scene, {-a / 2, -a / 2, h}, {0, a, 0}, {a, 0, 0}, m);
  return scene;
}

std::vector<glm::dvec3> emitterPolygon(float a, float h) {
  return {{-a / 2, -a / 2, h}, {-a / 2, a / 2, h}, {a / 2, a / 2, h}, {a / 2, -a / 2, h}};
}

TEST(ReferenceTracer, DirectLightMatchesLambertFormFactor) {
  const glm::vec3 emission(10.0f, 5.0f, 2.0f), albedo(0.5f, 0.7f, 0.9f);
  struct Case {
    float a, h;
    glm::vec3 position, normal;
  };
  const std::vector<Case> cases = {
      {1.0f, 1.0f, {0, 0, 0}, {0, 0, 1}},                                        // centred, far
      {1.0f, 1.0f, {0.8f, -0.3f, 0.2f}, glm::normalize(glm::vec3(0.6f, 0, 1))},  // off-axis, tilted
      {1.0f,
       0.5f,
       {0.0f, 0.1f, 0.3f},
       glm::normalize(glm::vec3(1, 0.2f, 0))},  // emitter partly behind the plane
      {2.0f,
       0.05f,
       {0.1f, 0.2f, 0},
       {0, 0, 1}},  // large and close: BSDF hits dominate, MIS must not double count
  };
  for (const Case& c : cases) {
    const Scene scene = emitterScene(c.a, c.h, emission);
    const std::vector<SamplePoint> points = {{c.position, c.normal, albedo, glm::vec3(0.0f)}};
    Context ctx;
    ReferenceParams params;
    params.spp = 4096;
    const ReferenceResult r = traceReference(scene, points, params, ctx);
    const double f =
        pointToPolygonFormFactor(glm::dvec3(c.position), glm::dvec3(c.normal), emitterPolygon(c.a, c.h));
    const glm::vec3 exact = albedo * emission * float(f);
    expectWithinError(r.radiosity[0], r.standardError[0], exact, 5.0f, "h " + std::to_string(c.h));
    EXPECT_LT(r.standardError[0].x, 0.02f * exact.x)
        << "h " << c.h << " B " << r.radiosity[0].x << " exact " << exact.x;
  }
}

TEST(ReferenceTracer, SeveralEmittersAddUp) {
  // Three lamps of different colours: one near above, one far and tilted, one facing away from the
  // point (contributes nothing). Direct light only: B = ρ Σ_k E_k F_k.
  Scene scene;
  const glm::vec3 e1(10.0f, 1.0f, 1.0f), e2(1.0f, 30.0f, 1.0f), e3(1.0f, 1.0f, 50.0f);
  addRect(scene, {-0.3f, -0.3f, 1.0f}, {0, 0.6f, 0}, {0.6f, 0, 0}, addMaterial(scene, glm::vec3(0.0f), e1));
  addRect(scene, {3.0f, -1.0f, 0.5f}, {0, 0, 2.0f}, {0, 2.0f, 0}, addMaterial(scene, glm::vec3(0.0f), e2));
  addRect(scene, {-1.0f, -1.0f, 2.0f}, {2.0f, 0, 0}, {0, 2.0f, 0}, addMaterial(scene, glm::vec3(0.0f), e3));
  const glm::vec3 albedo(0.6f);
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f));
  const std::vector<SamplePoint> points = {{{0, 0, 0}, n, albedo, glm::vec3(0.0f)}};
  Context ctx;
  ReferenceParams params;
  params.spp = 8192;
  const ReferenceResult r = traceReference(scene, points, params, ctx);
  const glm::dvec3 nd(n);
  const double f1 = pointToPolygonFormFactor(
      glm::dvec3(0), nd, {{{-0.3, -0.3, 1.0}, {-0.3, 0.3, 1.0}, {0.3, 0.3, 1.0}, {0.3, -0.3, 1.0}}});
  const double f2 = pointToPolygonFormFactor(
      glm::dvec3(0), nd, {{{3.0, -1.0, 0.5}, {3.0, -1.0, 2.5}, {3.0, 1.0, 2.5}, {3.0, 1.0, 0.5}}});
  const glm::vec3 exact = albedo * (e1 * float(f1) + e2 * float(f2));
  expectWithinError(r.radiosity[0], r.standardError[0], exact, 5.0f, "three lamps");
  for (int c = 0; c < 3; ++c) EXPECT_LT(r.standardError[0][c], 0.02f * exact[c]);
}

TEST(ReferenceTracer, ManyEmittersFallBackToPowerSelection) {
  // A 1 m² lamp cut into 12 × 12 quads (288 triangles, more than the per-vertex selection handles).
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.0f), glm::vec3(8.0f));
  const int cells = 12;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      addRect(scene, {-0.5f + float(i) / cells, -0.5f + float(j) / cells, 0.8f}, {0, 1.0f / cells, 0},
              {1.0f / cells, 0, 0}, m);
  const std::vector<SamplePoint> points = {{{0.2f, 0.1f, 0}, {0, 0, 1}, glm::vec3(0.5f), glm::vec3(0.0f)}};
  Context ctx;
  ReferenceParams params;
  params.spp = 4096;
  const ReferenceResult r = traceReference(scene, points, params, ctx);
  const double f =
      pointToPolygonFormFactor(glm::dvec3(0.2, 0.1, 0), glm::dvec3(0, 0, 1), emitterPolygon(1.0f, 0.8f));
  expectWithinError(r.radiosity[0], r.standardError[0], glm::vec3(0.5f * 8.0f * float(f)), 5.0f,
                    "split lamp");
  EXPECT_LT(r.standardError[0].x, 0.02f * 4.0f * float(f));
}

TEST(ReferenceTracer, ShadowAndBackFaceAreExactlyDark) {
  Scene scene = emitterScene(1.0f, 1.0f, glm::vec3(10.0f));
  const uint32_t black = addMaterial(scene, glm::vec3(0.0f));
  addRect(scene, {-1.0f, -1.0f, 0.5f}, {2.0f, 0, 0}, {0, 2.0f, 0}, black);  // a blocker facing the point
  const std::vector<SamplePoint> points = {
      {{0, 0, 0}, {0, 0, 1}, glm::vec3(0.8f), glm::vec3(0.0f)},   // under the blocker
      {{0, 0, 2}, {0, 0, -1}, glm::vec3(0.8f), glm::vec3(0.0f)},  // above the emitter's back
  };
  Context ctx;
  ReferenceParams params;
  params.spp = 64;
  const ReferenceResult r = traceReference(scene, points, params, ctx);
  EXPECT_EQ(r.radiosity[0], glm::vec3(0.0f));
  EXPECT_EQ(r.radiosity[1], glm::vec3(0.0f));
}

TEST(ReferenceTracer, NoLeakThroughCoincidentBackToBackWalls) {
  // Two closed boxes sharing the plane x = 1 with zero thickness between them: only A has a lamp, so
  // every point in B must stay exactly black however close its ray origins sit to the shared plane.
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(0.8f));
  const uint32_t lamp = addMaterial(scene, glm::vec3(0.8f), glm::vec3(50.0f));
  auto a = boxFaces(1.0f, {wall, lamp, wall, wall, wall, wall});
  auto b = boxFaces(1.0f, {wall, wall, wall, wall, wall, wall});
  for (Face& f : b) f.origin.x += 1.0f;
  addFaces(scene, a);
  addFaces(scene, b);
  Context ctx;
  ReferenceParams params;
  params.spp = 64;
  const auto inB = facePoints(scene, b, 8);
  const ReferenceResult dark = traceReference(scene, inB, params, ctx);
  for (size_t i = 0; i < inB.size(); ++i) EXPECT_EQ(dark.radiosity[i], glm::vec3(0.0f)) << i;
  const auto inA = facePoints(scene, a, 4);
  const ReferenceResult lit = traceReference(scene, inA, params, ctx);
  for (size_t i = 0; i < inA.size(); ++i) EXPECT_GT(lit.radiosity[i].x, 1.0f) << i;
}

TEST(ReferenceTracer, OwnEmissionPassesThroughWithoutNoise) {
  const Scene scene = emitterScene(1.0f, 1.0f, glm::vec3(10.0f));
  const std::vector<SamplePoint> points = {
      {{0, 0, 0}, {0, 0, 1}, glm::vec3(0.0f), glm::vec3(3.0f, 2.0f, 1.0f)}};
  Context ctx;
  const ReferenceResult r = traceReference(scene, points, {}, ctx);
  EXPECT_EQ(r.radiosity[0], glm::vec3(3.0f, 2.0f, 1.0f));
  EXPECT_EQ(r.standardError[0], glm::vec3(0.0f));
}

TEST(ReferenceTracer, ClosedBoxConservesEnergy) {
  // In an enclosure with uniform albedo every watt leaving a surface arrives at another, so
  // Σ A·B = Σ A·E / (1 − ρ) even though only the ceiling emits.
  const float rho = 0.6f, size = 1.5f;
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(rho));
  const uint32_t light = addMaterial(scene, glm::vec3(rho), glm::vec3(4.0f));
  const auto faces = boxFaces(size, {wall, light, wall, wall, wall, wall});
  addFaces(scene, faces);
  const int k = 8;
  const auto points = facePoints(scene, faces, k);
  Context ctx;
  ReferenceParams params;
  params.spp = 128;
  const ReferenceResult r = traceReference(scene, points, params, ctx);
  const float texelArea = size * size / (k * k);
  double power = 0.0;
  for (const glm::vec3& b : r.radiosity) power += texelArea * b.x;
  const double expected = size * size * 4.0 / (1.0 - rho);
  EXPECT_NEAR(power / expected, 1.0, 0.01);
  // The floor, facing the light, is brighter than the walls beside it.
  EXPECT_GT(r.radiosity[k * k / 2].x, r.radiosity[2 * k * k + k * k / 2].x);
}

TEST(ReferenceTracer, AgreesWithCollocationRadiosityInABox) {
  // An independent answer for interreflection with non-uniform light: point-collocation radiosity with
  // exact (Lambert) form factors from each patch centre to every other patch, solved by Jacobi
  // iteration. In a convex box nothing is occluded, so this is exact up to the piecewise-constant
  // discretisation (12 × 12 patches per face).
  const float size = 1.0f, rho = 0.6f;
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(rho));
  const uint32_t light = addMaterial(scene, glm::vec3(rho), glm::vec3(5.0f));
  const auto faces = boxFaces(size, {wall, light, wall, wall, wall, wall});
  addFaces(scene, faces);
  const int k = 12;
  const auto points = facePoints(scene, faces, k);
  const size_t count = points.size();
  std::vector<std::vector<glm::dvec3>> polygons;
  for (const Face& f : faces)
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        const glm::dvec3 o =
            glm::dvec3(f.origin) + double(i) / k * glm::dvec3(f.u) + double(j) / k * glm::dvec3(f.v);
        const glm::dvec3 du = glm::dvec3(f.u) / double(k), dv = glm::dvec3(f.v) / double(k);
        polygons.push_back({o, o + du, o + du + dv, o + dv});
      }
  std::vector<double> formFactors(count * count, 0.0);
  for (size_t a = 0; a < count; ++a)
    for (size_t b = 0; b < count; ++b)
      if (a / (k * k) != b / (k * k))  // coplanar patches do not see each other
        formFactors[a * count + b] = pointToPolygonFormFactor(glm::dvec3(points[a].position),
                                                              glm::dvec3(points[a].normal), polygons[b]);
  std::vector<double> radiosity(count), next(count);
  for (size_t a = 0; a < count; ++a) radiosity[a] = points[a].emission.x;
  for (int iteration = 0; iteration < 200; ++iteration) {
    for (size_t a = 0; a < count; ++a) {
      double gathered = 0.0;
      for (size_t b = 0; b < count; ++b) gathered += formFactors[a * count + b] * radiosity[b];
      next[a] = points[a].emission.x + rho * gathered;
    }
    radiosity.swap(next);
  }

  // Trace a handful of patch centres: floor centre and corner, a wall's middle and its top edge, the lamp.
  const std::vector<size_t> probes = {k * k / 2 + k / 2, 0, 2 * k * k + k * k / 2,
                                      2 * k * k + k * (k / 2) + k - 1, k * k + k * k / 2};
  std::vector<SamplePoint> probePoints;
  for (size_t p : probes) probePoints.push_back(points[p]);
  Context ctx;
  ReferenceParams params;
  params.spp = 8192;
  const ReferenceResult r = traceReference(scene, probePoints, params, ctx);
  for (size_t q = 0; q < probes.size(); ++q) {
    const double exact = radiosity[probes[q]];
    EXPECT_NEAR(r.radiosity[q].x, exact, 5.0 * r.standardError[q].x + 0.01 * exact) << "probe " << q;
    EXPECT_LT(r.standardError[q].x, 0.01 * exact);
  }
}

TEST(ReferenceTracer, DeterministicWhateverTheThreadCount) {
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(0.7f));
  const uint32_t light = addMaterial(scene, glm::vec3(0.7f), glm::vec3(4.0f));
  const auto faces = boxFaces(1.0f, {wall, light, wall, wall, wall, wall});
  addFaces(scene, faces);
  const auto points = facePoints(scene, faces, 6);
  ReferenceParams params;
  params.spp = 16;
  Context ctx;
  const ReferenceResult a = traceReference(scene, points, params, ctx);
  ReferenceResult b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = traceReference(scene, points, params, ctx);
  }
  EXPECT_EQ(a.radiosity, b.radiosity);
  EXPECT_EQ(a.standardError, b.standardError);
  params.seed += 1;
  const ReferenceResult c = traceReference(scene, points, params, ctx);
  EXPECT_NE(a.radiosity, c.radiosity);
}

TEST(ReferenceTracer, SampledTexelsGetTheFullTracesValues) {
  // Each texel draws from the stream of its rank among the valid texels, so tracing a sample must give
  // those texels exactly what tracing the whole atlas gives them, and leave the others at 0.
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(0.6f));
  const uint32_t light = addMaterial(scene, glm::vec3(0.6f), glm::vec3(3.0f));
  addFaces(scene, boxFaces(1.0f, {wall, light, wall, wall, wall, wall}));
  Context ctx;
  AtlasParams atlasParams;
  atlasParams.texelsPerQuad = 4;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), atlasParams, ctx);
  ASSERT_EQ(atlas.validTexels(), 6u * 16u);
  ReferenceParams params;
  params.spp = 16;
  const ReferenceResult full = traceReference(scene, atlas, params, ctx);
  const std::vector<size_t> ranks = {0, 5, 17, 40, 95};
  const ReferenceResult sparse = traceReference(scene, atlas, params, ctx, ranks);
  EXPECT_EQ(sparse.spp, full.spp);
  size_t rank = 0, traced = 0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    if (std::find(ranks.begin(), ranks.end(), rank++) != ranks.end()) {
      ++traced;
      EXPECT_EQ(sparse.radiosity[i], full.radiosity[i]) << "texel " << i;
      EXPECT_EQ(sparse.standardError[i], full.standardError[i]) << "texel " << i;
      EXPECT_GT(sparse.radiosity[i].x, 0.0f);
    } else {
      EXPECT_EQ(sparse.radiosity[i], glm::vec3(0.0f)) << "texel " << i;
    }
  }
  EXPECT_EQ(traced, ranks.size());
  const std::vector<size_t> beyond = {3, 96};
  EXPECT_THROW(traceReference(scene, atlas, params, ctx, beyond), std::invalid_argument);
}

TEST(ReferenceTracer, RejectsTooFewSamples) {
  const Scene scene = emitterScene(1.0f, 1.0f, glm::vec3(1.0f));
  const std::vector<SamplePoint> points = {{{0, 0, 0}, {0, 0, 1}, glm::vec3(0.5f), glm::vec3(0.0f)}};
  ReferenceParams params;
  params.spp = 1;
  Context ctx;
  EXPECT_THROW(traceReference(scene, points, params, ctx), InputError);
}

TEST(ReferenceTracer, RelativeStandardErrorIsAreaWeighted) {
  ReferenceResult r;
  r.radiosity = {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(5.0f)};
  r.standardError = {glm::vec3(0.1f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.2f), glm::vec3(1.0f)};
  const std::vector<float> area = {1.0f, 2.0f, 0.0f};  // the last is padding
  // noise = 1·0.01 + 2·0.04 = 0.09; signal = 1·1 + 2·4 = 9
  EXPECT_NEAR(relativeStandardError(r, area), 0.1, 1e-7);
}

}  // namespace
}  // namespace cpgi
