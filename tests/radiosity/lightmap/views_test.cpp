#include "radiosity/lightmap/views.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/quads.h"
#include "radiosity/lightmap/ray_scene.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using namespace cpgi::testing;
constexpr float kPi = std::numbers::pi_v<float>;

struct FloorFixture {
  Scene scene;
  LightmapAtlas atlas;
  std::vector<glm::vec3> lightmap;

  /// A 2 m × 2 m floor at z = 0 facing +z, 8 × 8 texels, lit with radiance L(x, y) = 1 + 0.5x + 0.25y (so
  /// B = π·L at texel centres); a linear function survives bilinear interpolation exactly.
  FloorFixture() {
    addRect(scene, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}, addMaterial(scene, glm::vec3(0.5f)));
    AtlasParams params;
    params.texelsPerQuad = 8;
    Context ctx;
    atlas = buildAtlas(scene, findQuads(scene), params, ctx);
    lightmap.assign(atlas.texelCount(), glm::vec3(0.0f));
    for (size_t i = 0; i < atlas.texelCount(); ++i)
      if (atlas.patch[i] >= 0) lightmap[i] = kPi * radiance(atlas.position[i]);
    dilate(atlas, lightmap);
  }
  static glm::vec3 radiance(glm::vec3 p) {
    return glm::vec3(1.0f + 0.5f * p.x + 0.25f * p.y, 2.0f, 0.1f * p.x);
  }
};

Camera downCamera(glm::vec3 eye) {
  Camera cam;
  cam.name = "down";
  cam.position = eye;
  cam.forward = {0, 0, -1};
  cam.up = {0, 1, 0};
  cam.yfov = glm::radians(70.0f);
  cam.aspect = 1.0f;
  return cam;
}

TEST(Views, RadianceIsBilinearLightmapOverPi) {
  FloorFixture f;
  const RayScene rays(f.scene);
  const Camera cam = downCamera({0.9f, 1.2f, 2.0f});
  ViewParams params;
  params.width = 64;
  params.supersample = 1;
  const ImageRGB image = renderView(rays, f.scene, f.atlas, f.lightmap, cam, params);
  ASSERT_EQ(image.height, 64);
  const float tanHalf = std::tan(0.5f * cam.yfov);
  int inside = 0, outside = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      // The same pixel ray, intersected with z = 0 by hand.
      const float px = (x + 0.5f) / image.width, py = (y + 0.5f) / image.height;
      const glm::vec3 dir = glm::normalize(glm::vec3((2 * px - 1) * tanHalf, (1 - 2 * py) * tanHalf, -1.0f));
      const glm::vec3 p = cam.position + dir * (cam.position.z / -dir.z);
      const glm::vec3& got = image.at(x, y);
      if (p.x < 0 || p.x > 2 || p.y < 0 || p.y > 2) {
        EXPECT_EQ(got, glm::vec3(0.0f));
        ++outside;
      } else if (p.x > 0.126f && p.x < 1.874f && p.y > 0.126f && p.y < 1.874f) {  // between texel centres
        const glm::vec3 expected = FloorFixture::radiance(p);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 2e-4f) << x << "," << y;
        ++inside;
      }
    }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 100);
}

// A camera exported with an aspect ratio of 0.001 asked for a 640 x 640 000 picture (5 GB); the height
// is kept within kMaxViewEdge and the width follows it, the aspect ratio kept where the width allows.
TEST(Views, SizesStayWithinTheEdgesKeepingTheAspectWherePossible) {
  Camera cam = downCamera({1.0f, 1.0f, 2.0f});
  ViewParams params;  // 640 wide
  cam.aspect = 4.0f / 3.0f;
  ViewSize v = viewSize(cam, params);
  EXPECT_EQ(v.width, 640);
  EXPECT_EQ(v.height, 480);
  EXPECT_FALSE(v.clamped);
  cam.aspect = 0.1f;  // 640 x 6400: the height to 8192 at most, the aspect kept
  v = viewSize(cam, params);
  EXPECT_EQ(v.width, 640);
  EXPECT_EQ(v.height, 6400);
  EXPECT_FALSE(v.clamped);
  cam.aspect = 0.01f;
  v = viewSize(cam, params);
  EXPECT_EQ(v.height, kMaxViewEdge);
  EXPECT_EQ(v.width, 82);
  EXPECT_TRUE(v.clamped);
  cam.aspect = 0.001f;  // the width cannot follow below the smallest edge
  v = viewSize(cam, params);
  EXPECT_EQ(v.height, kMaxViewEdge);
  EXPECT_EQ(v.width, kMinViewEdge);
  EXPECT_TRUE(v.clamped);
  cam.aspect = 1000.0f;
  v = viewSize(cam, params);
  EXPECT_EQ(v.height, kMinViewEdge);
  EXPECT_EQ(v.width, kMaxViewEdge);
  EXPECT_TRUE(v.clamped);
  params.height = 100000;  // a height given is clamped alike
  v = viewSize(cam, params);
  EXPECT_EQ(v.height, kMaxViewEdge);
  EXPECT_TRUE(v.clamped);
}

TEST(Views, AThinCamerasPictureIsClampedAndNamedInOneWarning) {
  FloorFixture f;
  const RayScene rays(f.scene);
  Camera thin = downCamera({0.9f, 1.2f, 2.0f});
  thin.name = "needle";
  thin.aspect = 0.001f;
  const Camera cameras[] = {downCamera({0.9f, 1.2f, 2.0f}), thin};
  ViewParams params;
  params.width = 64;
  params.supersample = 1;
  test::TempDir dir;
  Context ctx;
  OutputDir out(dir.path() / "views");
  const RenderedViews views =
      renderCameraViews(rays, f.scene, cameras, f.atlas, f.lightmap, out, ctx, params);
  out.commit();
  EXPECT_EQ(views.written, (std::vector<std::string>{"down", "needle"}));
  EXPECT_TRUE(views.skipped.empty());
  const ImageRGB needle = readExr(dir / "views/view-needle.exr");
  EXPECT_EQ(needle.width, kMinViewEdge);
  EXPECT_EQ(needle.height, kMaxViewEdge);
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_NE(ctx.warnings()[0].find("needle (aspect ratio 0.001"), std::string::npos) << ctx.warnings()[0];
  EXPECT_EQ(ctx.warnings()[0].find("down"), std::string::npos) << ctx.warnings()[0];
}

// Past the deadline no view is rendered: each camera is said skipped, in one warning, and no file written.
TEST(Views, PastTheDeadlineTheViewsAreSkipped) {
  FloorFixture f;
  const RayScene rays(f.scene);
  const Camera cameras[] = {downCamera({0.9f, 1.2f, 2.0f}), downCamera({1.0f, 1.0f, 3.0f})};
  test::TempDir dir;
  Context ctx;
  OutputDir out(dir.path() / "views");
  const RenderedViews views = renderCameraViews(rays, f.scene, cameras, f.atlas, f.lightmap, out, ctx, {},
                                                std::chrono::steady_clock::now());
  out.commit();
  EXPECT_TRUE(views.written.empty());
  EXPECT_EQ(views.skipped, (std::vector<std::string>{"down", "down"}));
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_EQ(ctx.warnings()[0].rfind("views: the time limit came before 2 of 2 views", 0), 0u);
  for (const auto& e : std::filesystem::directory_iterator(dir.path() / "views")) {  // cpgi's own list only
    EXPECT_NE(e.path().filename().string().rfind("view-", 0), 0u) << e.path();
  }
}

TEST(Views, BackFacesAreBlack) {
  FloorFixture f;
  const RayScene rays(f.scene);
  Camera cam = downCamera({1.0f, 1.0f, -2.0f});
  cam.forward = {0, 0, 1};
  ViewParams params;
  params.width = 32;
  const ImageRGB image = renderView(rays, f.scene, f.atlas, f.lightmap, cam, params);
  for (const glm::vec3& p : image.pixels) EXPECT_EQ(p, glm::vec3(0.0f));
}

TEST(Views, ExposureFromAreaWeightedPercentile) {
  FloorFixture f;
  std::vector<glm::vec3> lightmap(f.atlas.texelCount(), glm::vec3(0.0f));
  // Valid texels (all the same area) get radiance 1..64 in the max channel, in scrambled order.
  std::vector<size_t> valid;
  for (size_t i = 0; i < f.atlas.texelCount(); ++i)
    if (f.atlas.patch[i] >= 0) valid.push_back(i);
  ASSERT_EQ(valid.size(), 64u);
  for (size_t k = 0; k < valid.size(); ++k)
    lightmap[valid[(k * 37) % 64]] = kPi * glm::vec3(0.0f, float(k + 1), 0.5f);
  // 90% of 64 texels = 57.6 → the 58th smallest radiance, 58.
  EXPECT_NEAR(viewExposure(f.atlas, lightmap), 0.8f / 58.0f, 1e-6f);
  EXPECT_EQ(viewExposure(f.atlas, std::vector<glm::vec3>(f.atlas.texelCount(), glm::vec3(0.0f))), 1.0f);
}

TEST(Views, DefaultCamerasOnePerCellInsideIt) {
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
  addClosedBox(scene, {0, 0, 0}, {4, 3, 4}, m);
  addClosedBox(scene, {5, 0, 0}, {9, 3, 6}, m);
  CellGraph cells;
  cells.cells.resize(2);
  cells.cells[0].name = "A";
  cells.cells[1].name = "B";
  for (uint32_t t = 0; t < 12; ++t) cells.cells[0].triangles.push_back(t);
  for (uint32_t t = 12; t < 24; ++t) cells.cells[1].triangles.push_back(t);
  const RayScene rays(scene);
  const std::vector<Camera> cameras = defaultCameras(rays, scene, cells);
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0].name, "A");
  EXPECT_EQ(cameras[1].name, "B");
  const glm::vec3 lo[2] = {{0, 0, 0}, {5, 0, 0}}, hi[2] = {{4, 3, 4}, {9, 3, 6}};
  for (int c = 0; c < 2; ++c) {
    const glm::vec3 eye = cameras[c].position;
    EXPECT_TRUE(glm::all(glm::greaterThan(eye, lo[c])) && glm::all(glm::lessThan(eye, hi[c]))) << c;
    EXPECT_NEAR(eye.y, 1.6f, 1e-5f);
    EXPECT_NEAR(glm::length(cameras[c].forward), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(cameras[c].forward, cameras[c].up), 0.0f, 1e-5f);
    // Looking into the room: the ray along the view axis hits a wall of the same cell from inside.
    const RayScene::Hit hit = rays.intersect(eye, cameras[c].forward);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit.triangle / 12, c);
  }

  const std::vector<Camera> overview = defaultCameras(rays, scene, CellGraph{});
  ASSERT_EQ(overview.size(), 1u);
  EXPECT_EQ(overview[0].name, "overview");
  EXPECT_NEAR(glm::abs(overview[0].forward.x), 0.989f, 0.01f);  // the longest horizontal axis is x
}

}  // namespace
}  // namespace cpgi
