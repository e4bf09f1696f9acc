#include "radiosity/lightmap/atlas.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "radiosity/lightmap/atlas_size.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;
using testing::addTriangle;

// A 4 m × 3 m × 2.5 m room (6 quads), a thin 4 m × 0.1 m ledge, and two loose triangles.
Scene mixedScene() {
  Scene s;
  const uint32_t wall = addMaterial(s, glm::vec3(0.7f));
  const uint32_t lamp = addMaterial(s, glm::vec3(0.0f), glm::vec3(100.0f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 2.5f), wall);
  addRect(s, glm::vec3(0.0f, 1.0f, 1.0f), glm::vec3(4.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.1f, 0.0f), wall, 1);
  addTriangle(s, glm::vec3(1.0f, 1.0f, 2.49f), glm::vec3(1.5f, 1.0f, 2.49f), glm::vec3(1.2f, 1.7f, 2.49f),
              lamp, 2);
  addTriangle(s, glm::vec3(2.0f, 0.5f, 0.3f), glm::vec3(2.0f, 0.9f, 0.3f), glm::vec3(2.0f, 0.5f, 1.1f), wall,
              3);
  return s;
}

LightmapAtlas build(const Scene& s, const AtlasParams& params, const std::vector<uint32_t>& subset = {}) {
  Context ctx;
  return buildAtlas(s, findQuads(s), params, ctx, subset);
}

// Distance from q to the plane of a triangle and whether q projects inside it (barycentric, with slack).
bool onTriangle(const Triangle& t, glm::vec3 q, float tol = 1e-4f) {
  const glm::vec3 n = t.geometricNormal();
  if (std::abs(glm::dot(q - t.p[0], n)) > tol) return false;
  for (int k = 0; k < 3; ++k) {
    const glm::vec3 e = t.p[(k + 1) % 3] - t.p[k];
    if (glm::dot(glm::cross(e, q - t.p[k]), n) < -tol) return false;
  }
  return true;
}

TEST(Atlas, AreasSumToPatchAreasAndTotalSurface) {
  const Scene s = mixedScene();
  for (AtlasParams params : {AtlasParams{.texelsPerQuad = 8}, AtlasParams{}}) {
    const LightmapAtlas a = build(s, params);
    ASSERT_EQ(a.patches.size(), 9u);  // 7 quads + 2 loose triangles
    std::vector<double> sum(a.patches.size(), 0.0);
    for (size_t t = 0; t < a.texelCount(); ++t) {
      if (a.patch[t] < 0) {
        EXPECT_EQ(a.area[t], 0.0f);
        continue;
      }
      sum[a.patch[t]] += a.area[t];
    }
    double total = 0.0;
    for (size_t p = 0; p < a.patches.size(); ++p) {
      EXPECT_NEAR(sum[p], a.patches[p].area, 1e-4 * a.patches[p].area) << "patch " << p;
      total += sum[p];
    }
    double sceneArea = 0.0;
    for (const Triangle& t : s.triangles) sceneArea += t.area();
    EXPECT_NEAR(total, sceneArea, 1e-4 * sceneArea);
  }
}

TEST(Atlas, TexelPositionsLieOnTheirPatch) {
  const Scene s = mixedScene();
  const LightmapAtlas a = build(s, AtlasParams{.texelsPerQuad = 5});
  for (size_t t = 0; t < a.texelCount(); ++t) {
    const int p = a.patch[t];
    if (p < 0) continue;
    const Patch& patch = a.patches[p];
    bool on = false;
    for (int32_t tri : patch.triangles)
      if (tri >= 0) on = on || onTriangle(s.triangles[tri], a.position[t]);
    EXPECT_TRUE(on) << "texel " << t << " of patch " << p;
    const int i = int(t % a.width) - patch.x, j = int(t / a.width) - patch.y;
    const glm::vec3 centre = patch.origin + (i + 0.5f) * patch.texelU + (j + 0.5f) * patch.texelV;
    EXPECT_NEAR(glm::length(centre - a.position[t]), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a.normal[t]), 1.0f, 1e-5f);
    EXPECT_EQ(a.albedo[t], s.materials[patch.material].albedo);
    EXPECT_EQ(a.emission[t], s.materials[patch.material].emission);
  }
}

TEST(Atlas, QuadTexelCentresFollowTheDocumentedLayout) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, glm::vec3(1.0f, 2.0f, 3.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), m);
  const LightmapAtlas a = build(s, AtlasParams{.density = 4.0f, .padding = 2});
  ASSERT_EQ(a.patches.size(), 1u);
  const Patch& p = a.patches[0];
  const Quad q = findQuads(s).quads[0];
  // findQuads picks which edge is u; the chart follows it: 2 m → 8 texels, 1 m → 4.
  EXPECT_EQ(p.w, q.width() > 1.5f ? 8 : 4);
  EXPECT_EQ(p.h, q.height() > 1.5f ? 8 : 4);
  EXPECT_GE(p.x, 2);
  EXPECT_GE(p.y, 2);
  for (int j = 0; j < p.h; ++j)
    for (int i = 0; i < p.w; ++i) {
      const size_t t = size_t(p.y + j) * a.width + p.x + i;
      const glm::vec3 expect = q.corners[0] + (i + 0.5f) / p.w * (q.corners[1] - q.corners[0]) +
                               (j + 0.5f) / p.h * (q.corners[3] - q.corners[0]);
      EXPECT_NEAR(glm::length(a.position[t] - expect), 0.0f, 1e-5f);
      EXPECT_FLOAT_EQ(a.area[t], 2.0f / 32.0f);
    }
  EXPECT_EQ(a.validTexels(), 32u);
}

TEST(Atlas, FixedModeGivesEveryQuadNByN) {
  const Scene s = mixedScene();
  const LightmapAtlas a = build(s, AtlasParams{.texelsPerQuad = 16});
  for (const Patch& p : a.patches) {
    EXPECT_EQ(p.w, 16);
    EXPECT_EQ(p.h, 16);
  }
  // Loose triangles keep s(s−1)/2 of their s² texels.
  size_t valid = 0;
  for (const Patch& p : a.patches) valid += p.quad >= 0 ? 256 : 16 * 15 / 2;
  EXPECT_EQ(a.validTexels(), valid);
}

TEST(Atlas, DensityModeClampsToLimits) {
  const Scene s = mixedScene();
  const AtlasParams params{.density = 10.0f, .minTexels = 3, .maxTexels = 32};
  const LightmapAtlas a = build(s, params);
  const QuadSet quads = findQuads(s);
  for (const Patch& p : a.patches) {
    EXPECT_GE(p.w, 3);
    EXPECT_LE(p.w, 32);
    EXPECT_GE(p.h, 3);
    EXPECT_LE(p.h, 32);
    if (p.quad < 0) continue;
    const Quad& q = quads.quads[p.quad];
    EXPECT_EQ(p.w, std::clamp(int(std::lround(q.width() * 10.0f)), 3, 32));
    EXPECT_EQ(p.h, std::clamp(int(std::lround(q.height() * 10.0f)), 3, 32));
  }
  // The ledge is 4 m × 0.1 m: 32 (clamped from 40) along, 3 (raised from 1) across.
  bool sawLedge = false;
  for (const Patch& p : a.patches)
    if (p.quad >= 0 && std::abs(p.area - 0.4f) < 1e-4f) {
      sawLedge = true;
      EXPECT_EQ(std::max(p.w, p.h), 32);
      EXPECT_EQ(std::min(p.w, p.h), 3);
    }
  EXPECT_TRUE(sawLedge);
}

TEST(Atlas, ChartsArePaddedApartAndInsideTheAtlas) {
  const Scene s = mixedScene();
  const AtlasParams params{.texelsPerQuad = 6, .padding = 2};
  const LightmapAtlas a = build(s, params);
  for (size_t i = 0; i < a.patches.size(); ++i) {
    const Patch& p = a.patches[i];
    EXPECT_GE(p.x, params.padding);
    EXPECT_GE(p.y, params.padding);
    EXPECT_LE(p.x + p.w + params.padding, a.width);
    EXPECT_LE(p.y + p.h + params.padding, a.height);
    for (size_t j = i + 1; j < a.patches.size(); ++j) {
      const Patch& o = a.patches[j];
      const bool apart = p.x + p.w + 2 * params.padding <= o.x || o.x + o.w + 2 * params.padding <= p.x ||
                         p.y + p.h + 2 * params.padding <= o.y || o.y + o.h + 2 * params.padding <= p.y;
      EXPECT_TRUE(apart) << "charts " << i << " and " << j;
    }
  }
}

TEST(Atlas, TriangleUVsMapCornersIntoTheirChart) {
  const Scene s = mixedScene();
  const LightmapAtlas a = build(s, AtlasParams{.texelsPerQuad = 8});
  ASSERT_EQ(a.triangleUV.size(), s.triangles.size());
  for (size_t pi = 0; pi < a.patches.size(); ++pi) {
    const Patch& p = a.patches[pi];
    for (int32_t tri : p.triangles) {
      if (tri < 0) continue;
      const auto& uv = a.triangleUV[tri];
      for (int k = 0; k < 3; ++k) {
        const float x = uv[k].x * a.width, y = uv[k].y * a.height;
        EXPECT_GE(x, p.x - 1e-3f);
        EXPECT_LE(x, p.x + p.w + 1e-3f);
        EXPECT_GE(y, p.y - 1e-3f);
        EXPECT_LE(y, p.y + p.h + 1e-3f);
      }
      // Interpolating the corners' UVs at the centroid lands on a texel of this patch whose sample
      // point is near the centroid (within one texel diagonal).
      const glm::vec2 c = (uv[0] + uv[1] + uv[2]) / 3.0f;
      const int tx = int(c.x * a.width), ty = int(c.y * a.height);
      const size_t t = size_t(ty) * a.width + tx;
      ASSERT_EQ(a.patch[t], int(pi));
      const Triangle& T = s.triangles[tri];
      float edge = 0.0f;
      for (int k = 0; k < 3; ++k) edge = std::max(edge, glm::length(T.p[k] - T.p[(k + 1) % 3]));
      EXPECT_LT(glm::length(a.position[t] - T.centroid()), edge / 8.0f * 1.5f);
    }
  }
}

TEST(Atlas, SubsetKeepsOnlyItsTrianglesAndSplitsHalfQuads) {
  const Scene s = mixedScene();
  // Triangles 0,1 form the floor quad; take 0, 1 and 2 (half of the ceiling quad).
  const LightmapAtlas a = build(s, AtlasParams{.texelsPerQuad = 4}, {2, 1, 0});
  ASSERT_EQ(a.patches.size(), 2u);
  EXPECT_GE(a.patches[0].quad, 0);
  EXPECT_EQ(a.patches[1].quad, -1);
  EXPECT_EQ(a.patches[1].triangles[0], 2);
  for (size_t t = 3; t < s.triangles.size(); ++t)
    for (const glm::vec2& uv : a.triangleUV[t]) EXPECT_EQ(uv, glm::vec2(0.0f));
}

TEST(Atlas, Deterministic) {
  const Scene s = mixedScene();
  const LightmapAtlas a = build(s, AtlasParams{}), b = build(s, AtlasParams{});
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_EQ(a.patch, b.patch);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.triangleUV, b.triangleUV);
}

TEST(Atlas, TooLargeNamesTheOption) {
  const Scene s = mixedScene();
  try {
    build(s, AtlasParams{.texelsPerQuad = 512, .maxSize = 1024});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "texels per quad");
  }
}

TEST(Atlas, DilateCopiesNearestValidTexel) {
  const Scene s = mixedScene();
  const LightmapAtlas a = build(s, AtlasParams{.texelsPerQuad = 4, .padding = 1});
  std::vector<glm::vec3> v(a.texelCount(), glm::vec3(-1.0f));
  for (size_t t = 0; t < v.size(); ++t)
    if (a.patch[t] >= 0) v[t] = glm::vec3(float(a.patch[t]), float(t), 1.0f);
  dilate(a, v, 2);
  for (size_t pi = 0; pi < a.patches.size(); ++pi) {
    const Patch& p = a.patches[pi];
    if (p.quad < 0) continue;
    // The gutter texel left of chart row j copies texel (0, j); the corner copies (0, 0).
    for (int j = 0; j < p.h; ++j) {
      const size_t g = size_t(p.y + j) * a.width + p.x - 1;
      EXPECT_EQ(v[g], v[g + 1]);
    }
    const size_t corner = size_t(p.y - 1) * a.width + p.x - 1;
    EXPECT_EQ(v[corner], v[corner + a.width + 1]);
  }
  for (size_t t = 0; t < v.size(); ++t) {
    if (a.patch[t] < 0) continue;
    EXPECT_EQ(v[t].y, float(t));
  }
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// A density the chart cap cannot give (issue 15, defect 8: --density 1e9 was clamped silently) is said,
// once; a density the charts can hold says nothing.
TEST(Atlas, DensityBeyondTheChartCapIsSaid) {
  Scene s;
  addRect(s, glm::vec3(0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f),
          testing::addMaterial(s, glm::vec3(0.5f)), 0);
  for (const float density : {10.0f, 1e9f}) {
    AtlasParams params;
    params.density = density;
    Context ctx;
    const LightmapAtlas atlas = buildAtlas(s, findQuads(s), params, ctx);
    if (density < 100.0f) {
      EXPECT_TRUE(ctx.warnings().empty());
      continue;
    }
    ASSERT_EQ(ctx.warnings().size(), 1u);
    EXPECT_NE(ctx.warnings()[0].find("atlas: --density 1e+09 asks for"), std::string::npos)
        << ctx.warnings()[0];
    EXPECT_NE(ctx.warnings()[0].find("capped at 256 texels per edge"), std::string::npos)
        << ctx.warnings()[0];
    EXPECT_LE(atlas.width, 2 * (256 + 2));
  }
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

// A bake builds its atlas several times on one context (density pilot, solve, output): a zero-area
// triangle left out is said once, not once per layout.
TEST(Atlas, AZeroAreaTriangleLeftOutIsSaidOncePerContext) {
  Scene s = mixedScene();
  testing::addZeroAreaTriangle(s);
  const QuadSet quads = findQuads(s);
  Context ctx;
  for (int layout = 0; layout < 3; ++layout) buildAtlas(s, quads, AtlasParams{}, ctx);
  int said = 0;
  for (const std::string& w : ctx.warnings())
    said += w.find("zero-area triangle(s) left out") != std::string::npos;
  EXPECT_EQ(said, 1);
}

// measureAtlas is the atlas buildAtlas makes, without its texels: the same size and valid texels, on quads,
// merged grids and loose triangles (a zero-area one left out), at an even density and per triangle.
TEST(Atlas, MeasuredIsTheSizeOfTheAtlasBuilt) {
  Scene s = mixedScene();
  testing::addZeroAreaTriangle(s);
  const QuadSet quads = findQuads(s);
  AtlasParams even;
  even.density = 7.0f;
  AtlasParams perTriangle;
  for (size_t t = 0; t < s.triangles.size(); ++t) perTriangle.triangleDensity.push_back(float(3 + t % 11));
  for (const AtlasParams& params : {AtlasParams{}, even, perTriangle}) {
    Context ctx;
    const LightmapAtlas built = buildAtlas(s, quads, params, ctx);
    const AtlasSize measured = measureAtlas(s, quads, params);
    EXPECT_EQ(measured.width, built.width);
    EXPECT_EQ(measured.height, built.height);
    EXPECT_EQ(measured.validTexels, built.validTexels());
  }
}

}  // namespace
}  // namespace cpgi
