// compare-light's seams (radiosity/metrics/portal_seams.h): the step across every portal of the scene on
// the floor, in A and in the reference B, on B's atlas rebuilt from the scene.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/scene_io.h"

namespace cpgi::cli {

/// "portal_seams": per portal of `scenePath`'s hand-made cells {name, measured, texels_a, texels_b, step,
/// step_reference, excess (step − step_reference), noise, noise_reference, seam (|excess| above the larger
/// noise)}, measured on B's atlas (rebuilt from the scene with the options `bDir`/report.json records)
/// with `a` read on it and `weight` (B's texels that count: area, 0 for lamps and untraced texels).
/// Null with `why` set when the seams cannot be measured: no scene, a scene without portals, an atlas
/// that cannot be rebuilt.
nlohmann::json portalSeamsJson(const std::string& scenePath, const std::string& bDir,
                               const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                               const std::vector<float>& weight, const std::vector<float>& bArea, int width,
                               int height, std::string& why, const LoadOptions& load = {});

/// The seams' lines of compare-light's text output.
void printPortalSeams(const nlohmann::json& seams);

}  // namespace cpgi::cli
