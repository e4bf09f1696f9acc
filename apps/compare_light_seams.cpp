#include "apps/compare_light_seams.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/compare_light_resample.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "radiosity/metrics/portal_seams.h"

namespace cpgi::cli {

namespace {

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json portalSeamsJson(const std::string& scenePath, const std::string& bDir,
                               const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                               const std::vector<float>& weight, const std::vector<float>& bArea, int width,
                               int height, std::string& why, const LoadOptions& load) {
  if (scenePath.empty()) {
    why = "no scene (give --scene)";
    return nullptr;
  }
  LightmapAtlas atlas;
  std::vector<SeamPortal> portals;
  try {
    const LoadedScene scene = loadScene(scenePath, load);
    for (const PortalQuad& p : scene.cells.portals) portals.push_back({p.name, p.corners});
    if (portals.empty()) {
      why = scenePath + " has no hand-made portals";
      return nullptr;
    }
    atlas = rebuildReferenceAtlas(scene.scene, scenePath, bDir, bArea, width, height);
  } catch (const InputError& e) {
    why = e.what();
    return nullptr;
  }
  const SeamTexels onA{atlas.position, atlas.normal, a, weight}, onB{atlas.position, atlas.normal, b, weight};
  const std::vector<PortalSeam> seamsA = measurePortalSeams(onA, portals),
                                seamsB = measurePortalSeams(onB, portals);
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < portals.size(); ++i) {
    const PortalSeam &s = seamsA[i], &r = seamsB[i];
    const bool measured = s.measured && r.measured;
    const double excess = s.step - r.step, tolerance = std::max(s.noise, r.noise);
    out.push_back({{"name", s.name},
                   {"measured", measured},
                   {"texels_a", s.texelsA},
                   {"texels_b", s.texelsB},
                   {"step", number(s.step)},
                   {"step_reference", number(r.step)},
                   {"excess", measured ? number(excess) : nlohmann::json(nullptr)},
                   {"noise", number(s.noise)},
                   {"noise_reference", number(r.noise)},
                   {"seam", measured && std::abs(excess) > tolerance}});
  }
  return out;
}

void printPortalSeams(const nlohmann::json& seams) {
  if (!seams.is_array() || seams.empty()) return;
  std::printf("portal seams (floor, one texel each side)  step   reference  excess     noise   ref. noise\n");
  for (const nlohmann::json& s : seams) {
    const std::string name = s["name"].get<std::string>();
    if (!s["measured"].get<bool>()) {
      std::printf("  %-38s no floor across it\n", name.c_str());
      continue;
    }
    std::printf("  %-38s %+7.2f%%  %+7.2f%%  %+7.2f%%  %6.2f%%  %6.2f%%%s\n", name.c_str(),
                100.0 * s["step"].get<double>(), 100.0 * s["step_reference"].get<double>(),
                100.0 * s["excess"].get<double>(), 100.0 * s["noise"].get<double>(),
                100.0 * s["noise_reference"].get<double>(), s["seam"].get<bool>() ? "  <- seam" : "");
  }
}

}  // namespace cpgi::cli
