#include "radiosity/cells/first_shot_groups.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <map>

#include "core/error.h"

namespace cpgi {

LightmapAtlas firstShotReceivers(const LightmapAtlas& global, const std::vector<int>& cellOfTriangle) {
  LightmapAtlas black = global;
  std::fill(black.albedo.begin(), black.albedo.end(), glm::vec3(0.0f));
  for (const Patch& P : global.patches)
    for (int j = 0; j < P.h; ++j)
      for (int i = 0; i < P.w; ++i) {
        if (cellOfTriangle[size_t(texelTriangle(P, i, j))] < 0)
          black.emission[size_t(P.y + j) * global.width + P.x + i] = glm::vec3(0.0f);
      }
  return black;
}

std::vector<FirstShotGroup> firstShotGroups(const Scene& scene, const LightmapAtlas& receivers,
                                            const std::vector<int>& cellOfTriangle) {
  std::map<int, std::vector<int>> patchesOfCell;
  for (size_t p = 0; p < receivers.patches.size(); ++p) {
    const Patch& P = receivers.patches[p];
    int cell = INT_MAX;
    for (int j = 0; j < P.h; ++j)
      for (int i = 0; i < P.w; ++i) {
        const size_t t = size_t(P.y + j) * receivers.width + P.x + i;
        if (receivers.patch[t] != int(p) || receivers.emission[t] == glm::vec3(0.0f)) continue;
        const int c = cellOfTriangle[size_t(texelTriangle(P, i, j))];
        if (c >= 0) cell = std::min(cell, c);
      }
    if (cell != INT_MAX) patchesOfCell[cell].push_back(int(p));
  }
  std::vector<FirstShotGroup> groups;
  if (!scene.lights.empty()) groups.push_back(FirstShotGroup{-1, {}});
  for (auto& [cell, patches] : patchesOfCell) groups.push_back(FirstShotGroup{cell, std::move(patches)});
  return groups;
}

FirstShotContribution shootFirstShotGroup(const Scene& scene, const LightmapAtlas& receivers,
                                          const std::vector<FirstShotGroup>& groups, size_t g,
                                          const SolverParams& settings, ShotEngine& engine, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  const FirstShotGroup& group = groups.at(g);
  // The group's emitters alone; the power of all of them for the strong-shot threshold.
  LightmapAtlas own = receivers;
  std::vector<char> ours(own.patches.size(), 0);
  for (int p : group.patches) ours[size_t(p)] = 1;
  double all = 0.0, mine = 0.0;
  for (size_t t = 0; t < own.texelCount(); ++t) {
    const int p = own.patch[t];
    const glm::dvec3 power = glm::dvec3(own.emission[t]) * double(own.area[t]);
    if (p >= 0) all += power.r + power.g + power.b;
    if (p >= 0 && ours[size_t(p)])
      mine += power.r + power.g + power.b;
    else
      own.emission[t] = glm::vec3(0.0f);
  }
  // Punctual lights shoot in their own group only (the solver shoots a scene's lights before any patch).
  Scene dark;
  const Scene* shooting = &scene;
  if (group.cell >= 0 && !scene.lights.empty()) {
    dark = scene;
    dark.lights.clear();
    shooting = &dark;
  }
  // Black receivers: the solve ends once every emitter patch has shot (nothing is reflected to shoot
  // again), and the irradiance it read is the direct light alone, whatever --max-shots.
  SolverParams first = settings;
  first.unshotFraction = 1e-12;
  first.maxShots = std::max(first.maxShots, int(group.patches.size()) + 1);
  // A shot is strong against the power of its solve: here the group's. Scaled to all emitters, the
  // group's shots are strong where they were when all shot in one solve (punctual lights left out of
  // `all`; a group under the fraction of all is capped at 1: its largest shot still counts as strong).
  if (mine > 0.0) first.strongShotFraction = std::min(1.0, settings.strongShotFraction * all / mine);
  const SolveResult direct =
      solveProgressive(*shooting, own, first, engine, ctx, SolveControls{.readTransfer = true});
  FirstShotContribution out;
  out.emitted = direct.energy.emitted;
  out.shots = direct.shots;
  for (size_t t = 0; t < direct.incident.size(); ++t)
    if (direct.incident[t] != glm::vec3(0.0f)) {
      out.texels.push_back(uint32_t(t));
      out.incident.push_back(direct.incident[t]);
    }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

FirstShotSum sumFirstShot(const std::vector<FirstShotContribution>& parts, size_t texels) {
  FirstShotSum sum;
  sum.incident.assign(texels, glm::vec3(0.0f));
  for (const FirstShotContribution& part : parts) {
    sum.emitted += part.emitted;
    for (size_t k = 0; k < part.texels.size(); ++k) {
      if (part.texels[k] >= texels) throw InputError("first shot", "a group's texel outside the atlas");
      sum.incident[part.texels[k]] += part.incident[k];
    }
  }
  return sum;
}

}  // namespace cpgi
