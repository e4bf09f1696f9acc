#include "radiosity/bake/lightmap_report.h"

#include <filesystem>
#include <system_error>

namespace cpgi {

namespace {

std::string absoluteScenePath(const std::string& scene) {
  std::error_code error;
  const std::filesystem::path path = std::filesystem::absolute(scene, error);
  return error ? scene : path.lexically_normal().string();
}

}  // namespace

nlohmann::json lightmapReport(const LightmapRun& run, const Context& ctx) {
  const LightmapAtlas& atlas = *run.atlas;
  nlohmann::json timings = nlohmann::json::object();
  for (const Context::Timing& t : ctx.timings()) timings[t.stage] = timings.value(t.stage, 0.0) + t.seconds;
  return {{"method", run.method},
          {"scene", run.scene},
          // The scene as a path from anywhere: compare-light rebuilds an atlas from it.
          {"scene_file", absoluteScenePath(run.scene)},
          {"seconds", run.seconds},
          {"solve_seconds", run.solveSeconds},
          {"texels", atlas.validTexels()},
          {"shots", run.shots},
          {"unshot_fraction", run.unshotFraction},
          {"cells", run.cells},
          {"portals", run.portals},
          {"atlas",
           {{"width", atlas.width},
            {"height", atlas.height},
            {"patches", atlas.patches.size()},
            {"texels_per_quad", run.atlasParams.texelsPerQuad},
            {"density", run.atlasParams.texelsPerQuad > 0 ? 0.0f : run.atlasParams.density}}},
          {"triangles", run.triangles},
          {"quads", run.quads},
          {"timings", timings},
          {"views", run.views},
          {"cell_names", run.cellNames},
          {"warnings", ctx.warnings()}};
}

nlohmann::json energyReport(const EnergyTotals& e) {
  return {{"emitted_w", e.emitted},   {"shot_w", e.shot},
          {"received_w", e.received}, {"absorbed_w", e.absorbed},
          {"unshot_w", e.unshot},     {"escaped_w", e.escaped()},
          {"created_w", e.created},   {"worst_shot_gain", e.worstShotGain}};
}

void writeReport(OutputDir& out, const nlohmann::json& report) {
  writeFileAtomically(out.file("report.json"), report.dump(2) + "\n");
}

nlohmann::json skyReport(const Scene& scene) {
  const Sky& sky = scene.sky;
  nlohmann::json sun = nullptr;
  for (const PunctualLight& l : scene.lights)
    if (l.kind == PunctualLight::Kind::Directional && l.name == "sun") {
      const glm::vec3 towards = -l.direction;
      sun = {{"towards", {towards.x, towards.y, towards.z}}, {"irradiance_w_m2", l.intensity.g}};
    }
  if (!sky.lights() && sun.is_null()) return nullptr;
  return {{"kind", skyKindName(sky.kind)},
          {"zenith_radiance_w_m2_sr", sky.zenithRadiance},
          {"horizontal_irradiance_w_m2", horizontalIrradiance(sky.kind, sky.zenithRadiance)},
          {"ground_radiance_w_m2_sr", sky.groundRadiance},
          {"gather_rays", sky.gatherRays},
          {"sun", sun}};
}

}  // namespace cpgi
