// `cpgi view DIR [--camera NAME | --eye X,Y,Z --look X,Y,Z] [--view-size WxH] [-o OUT]`: pictures of an
// existing bake (or reference) without solving again. The scene, its cells and the lightmap's atlas
// coordinates come from DIR/preview.glb (TEXCOORD_1; baked.glb in a folder from before it), the radiosity
// from DIR/lightmap.exr; the pictures are rendered and exposed as the bake's own view-*.png
// (radiosity/lightmap/views.h) and written to OUT (default DIR/views), all or nothing.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/scene_io.h"
#include "radiosity/bake/lightmap_report.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/views.h"

namespace cpgi::cli {
namespace {

namespace fs = std::filesystem;

struct ViewOptions {
  std::string dir;
  std::string camera;  ///< one camera by name (the scene's, or a default one: a cell's name, "overview")
  std::string eye, look;
  std::string output;  ///< default DIR/views
  ViewParams views;
  bool quiet = false;
};

/// What a bake folder holds that a picture needs: the scene with its cells, the atlas rebuilt from the
/// glb's lightmap coordinates and lightmap.exr's texel areas, and the radiosity per texel.
struct BakedLightmap {
  LoadedScene loaded;
  LightmapAtlas atlas;
  std::vector<glm::vec3> radiosity;
};

fs::path requireFile(const fs::path& dir, const std::string& name) {
  const fs::path path = dir / name;
  if (!fs::is_regular_file(path))
    throw InputError(dir.string(), "no " + name + " (not the output folder of cpgi bake or cpgi reference)");
  return path;
}

BakedLightmap readBake(const std::string& dirName) {
  const fs::path dir(dirName);
  if (!fs::is_directory(dir)) throw InputError(dirName, "no such folder (give the output folder of a bake)");
  const fs::path reportPath = requireFile(dir, "report.json");
  const fs::path glb = requireFile(dir, previewGlb(dir).filename().string());
  const fs::path exr = requireFile(dir, "lightmap.exr");
  {
    std::ifstream in(reportPath);
    const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
    if (report.is_discarded() || !report.is_object() || !report.contains("method"))
      throw InputError(reportPath.string(), "is not the report of a bake or a reference (no \"method\")");
  }
  BakedLightmap b;
  b.loaded = loadScene(glb.string());
  if (b.loaded.lightmapUVs.size() != b.loaded.scene.triangles.size())
    throw InputError(glb.string(), "has no lightmap coordinates (TEXCOORD_1) on every triangle");
  std::vector<ExrChannel> extra;
  ImageRGB image = readExr(exr.string(), &extra);
  const auto area =
      std::find_if(extra.begin(), extra.end(), [](const ExrChannel& c) { return c.name == "area"; });
  if (area == extra.end() || area->values.size() != image.pixels.size())
    throw InputError(exr.string(), "no per-texel \"area\" channel (not written by cpgi bake or reference)");
  LightmapAtlas& atlas = b.atlas;
  atlas.width = image.width;
  atlas.height = image.height;
  atlas.triangleUV = b.loaded.lightmapUVs;
  atlas.area = area->values;
  atlas.patch.resize(atlas.area.size());
  // Only "is this texel on a surface" matters to the exposure rule; which patch does not.
  for (size_t i = 0; i < atlas.area.size(); ++i) atlas.patch[i] = atlas.area[i] > 0.0f ? 0 : -1;
  b.radiosity = std::move(image.pixels);
  return b;
}

Camera cameraAt(const ViewOptions& o) {
  Camera cam;
  cam.name = "eye";
  cam.position = parsePoint(o.eye, "--eye");
  const glm::vec3 look = parsePoint(o.look, "--look");
  const glm::vec3 forward = look - cam.position;
  if (!(glm::length(forward) > 1e-6f)) throw InputError("--look", "must differ from --eye");
  cam.forward = glm::normalize(forward);
  glm::vec3 up = glm::vec3(0, 1, 0) - cam.forward * cam.forward.y;
  cam.up = glm::length(up) > 1e-4f ? glm::normalize(up) : glm::vec3(0, 0, -1);
  cam.yfov = glm::radians(65.0f);
  cam.aspect = o.views.height > 0 ? float(o.views.width) / float(o.views.height) : 4.0f / 3.0f;
  return cam;
}

std::vector<Camera> chooseCameras(const ViewOptions& o, const RayScene& rays, const BakedLightmap& b) {
  if (!o.eye.empty()) return {cameraAt(o)};
  std::vector<Camera> cameras = viewCameras(rays, b.loaded.scene, b.loaded.cells);
  if (o.camera.empty()) return cameras;
  for (const Camera& c : cameras)
    if (c.name == o.camera) return {c};
  std::string known;
  for (const Camera& c : cameras) known += (known.empty() ? "" : ", ") + c.name;
  throw InputError("--camera", "no camera named " + o.camera + " in " + o.dir + " (known: " + known + ")");
}

int runView(const ViewOptions& o) {
  Context ctx;
  ctx.setProgress(stderrProgress(o.quiet));
  const BakedLightmap b = readBake(o.dir);
  const RayScene rays(b.loaded.scene);
  const std::vector<Camera> cameras = chooseCameras(o, rays, b);
  const std::string output = o.output.empty() ? (fs::path(o.dir) / "views").string() : o.output;
  OutputDir out(output);
  const std::vector<std::string> names =
      renderCameraViews(rays, b.loaded.scene, cameras, b.atlas, b.radiosity, out, ctx, o.views).written;
  out.commit();
  if (!o.quiet) {
    for (const std::string& n : names)
      std::cout << (fs::path(output) / ("view-" + n + ".png")).string() << "\n";
    for (const std::string& w : ctx.warnings()) std::cerr << "warning: " << w << "\n";
  }
  return 0;
}

}  // namespace

void addViewCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* sub = app.add_subcommand(
      "view",
      "Render views of an existing bake or reference (its preview.glb and lightmap.exr) without baking");
  sub->add_option("dir", o->dir, "Output folder of cpgi bake or cpgi reference")->required();
  const OptionGroup output(*sub, "Output");
  auto* camera =
      sub->add_option("--camera", o->camera,
                      "Only this camera: one of the scene's, or of the default ones (a cell's name, "
                      "or overview) when the scene has none");
  auto* eye = sub->add_option("--eye", o->eye, "A camera at X,Y,Z (metres) instead; needs --look");
  auto* look = sub->add_option("--look", o->look, "The point X,Y,Z the --eye camera looks at");
  eye->needs(look);
  look->needs(eye);
  camera->excludes(eye);
  camera->excludes(look);
  sub->add_option("-o,--output", o->output, "Folder for view-NAME.png/.exr (default DIR/views)");
  addViewOptions(*sub, o->views);
  sub->add_flag("-q,--quiet", o->quiet, "No progress or list of pictures");
  sub->callback([&selected, o] { selected = [o] { return runView(*o); }; });
}

}  // namespace cpgi::cli
