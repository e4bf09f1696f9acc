#include "radiosity/cells/cell_first_shot.h"

#include <algorithm>

#include "radiosity/cells/first_shot_groups.h"

namespace cpgi {
namespace {

// Each cell's sum is within the lights' power, but texel centres over all cells may sum to a little more
// (+0.2 % for the point-light rooms at 4 texels/m): scaled back so that no light is made up.
float fitLandedToEmitted(CellFirstShot& shot) {
  const float scale = shot.landed > shot.emitted ? float(shot.emitted / shot.landed) : 1.0f;
  shot.landed = std::min(shot.landed, shot.emitted);
  return scale;
}

// Cell texel `t` receives irradiance `e`: ρ e is pending, (1 − ρ) e absorbed at once (W, R + G + B).
double receive(CellState& s, size_t t, const glm::vec3& e) {
  s.pending[t] += s.atlas.albedo[t] * e;
  const glm::dvec3 kept = (glm::dvec3(1.0) - glm::dvec3(s.atlas.albedo[t])) * glm::dvec3(e);
  return (kept.r + kept.g + kept.b) * s.atlas.area[t];
}

// Per texel of a written cell: the mean irradiance of the global texels over it (a cell texel may sit
// under several where the cells cut a chart apart); `emission` receives those texels' exitance.
std::vector<glm::vec3> irradianceOfWrittenCell(const CellState& s, const LightmapAtlas& global,
                                               const std::vector<glm::vec3>& incident,
                                               std::vector<glm::vec3>& emission) {
  std::vector<glm::vec3> e(s.pending.size(), glm::vec3(0.0f));
  std::vector<int> count(s.pending.size(), 0);
  for (const auto& [g, t] : s.toGlobal) {
    e[size_t(t)] += incident[size_t(g)];
    ++count[size_t(t)];
    emission[size_t(g)] = global.emission[size_t(g)];
  }
  for (size_t t = 0; t < e.size(); ++t)
    if (count[t] > 0) e[t] /= float(count[t]);
  return e;
}

// Per texel of a boundary cell (a coarser atlas): the irradiance of the global texel at the same point.
std::vector<glm::vec3> irradianceOfBoundaryCell(const CellState& s, const LightmapAtlas& global,
                                                const std::vector<int>& globalPatchOfTriangle,
                                                const std::vector<glm::vec3>& incident) {
  std::vector<glm::vec3> e(s.pending.size(), glm::vec3(0.0f));
  std::vector<int32_t> source;
  for (size_t q = 0; q < s.atlas.patches.size(); ++q) {
    const Patch& Q = s.atlas.patches[q];
    const size_t own = size_t(Q.triangles[0]);
    if (own >= s.cs.ownTriangles) continue;  // a portal patch
    const int gp = globalPatchOfTriangle[size_t(s.cs.globalTriangle[own])];
    if (gp < 0) continue;
    mapPatchTexels(global, gp, s.atlas, int(q), source);
    for (int j = 0; j < Q.h; ++j)
      for (int i = 0; i < Q.w; ++i) {
        const size_t t = size_t(Q.y + j) * s.atlas.width + Q.x + i;
        if (s.atlas.patch[t] == int(q) && source[t] >= 0) e[t] = incident[size_t(source[t])];
      }
  }
  return e;
}

}  // namespace

CellFirstShot shootEmittersIntoCells(const Scene& scene, const LightmapAtlas& global,
                                     const std::vector<int>& cellOfTriangle, const SolverParams& settings,
                                     std::vector<CellState>& cells, CellWorkers& workers, Context& ctx) {
  const LightmapAtlas receivers = firstShotReceivers(global, cellOfTriangle);
  const std::vector<FirstShotGroup> groups = firstShotGroups(scene, receivers, cellOfTriangle);
  std::vector<FirstShotContribution> parts(groups.size());
  {
    auto t = ctx.time("cells: first shot");
    workers.run(groups.size(), ctx, [&](size_t g, ShotEngine& engine, Context& taskCtx) {
      parts[g] = shootFirstShotGroup(scene, receivers, groups, g, settings, engine, taskCtx);
    });
  }
  return landFirstShot(scene, global, sumFirstShot(parts, global.texelCount()), cells);
}

CellFirstShot landFirstShot(const Scene& scene, const LightmapAtlas& global, const FirstShotSum& sum,
                            std::vector<CellState>& cells) {
  CellFirstShot shot;
  shot.absorbed.assign(cells.size(), 0.0);
  shot.emitted = sum.emitted;
  shot.emission.assign(global.texelCount(), glm::vec3(0.0f));
  std::vector<int> globalPatchOfTriangle(scene.triangles.size(), -1);
  for (size_t gp = 0; gp < global.patches.size(); ++gp)
    for (int32_t t : global.patches[gp].triangles) globalPatchOfTriangle[size_t(t)] = int(gp);
  std::vector<std::vector<glm::vec3>> irradiance(cells.size());
  for (size_t c = 0; c < cells.size(); ++c) {
    CellState& s = cells[c];
    std::vector<glm::vec3>& e = irradiance[c];
    e = s.boundary ? irradianceOfBoundaryCell(s, global, globalPatchOfTriangle, sum.incident)
                   : irradianceOfWrittenCell(s, global, sum.incident, shot.emission);
    std::fill(s.pending.begin(), s.pending.end(), glm::vec3(0.0f));  // its emitters have shot
    const std::vector<char> portal = portalPatchFlags(s);
    for (size_t t = 0; t < e.size(); ++t) {
      if (s.atlas.patch[t] < 0 || portal[size_t(s.atlas.patch[t])]) {
        e[t] = glm::vec3(0.0f);
        continue;
      }
      shot.landed += (double(e[t].r) + e[t].g + e[t].b) * s.atlas.area[t];
    }
  }
  const float scale = fitLandedToEmitted(shot);
  for (size_t c = 0; c < cells.size(); ++c)
    for (size_t t = 0; t < irradiance[c].size(); ++t)
      if (cells[c].atlas.patch[t] >= 0) shot.absorbed[c] += receive(cells[c], t, irradiance[c][t] * scale);
  return shot;
}

void addFirstShotBookkeeping(const CellFirstShot& shot, SolveResult& result) {
  for (size_t g = 0; g < shot.emission.size(); ++g) result.radiosity[g] += shot.emission[g];
  if (shot.emitted <= 0.0) return;
  std::vector<CellEnergy>& cells = result.perCell->cells;
  size_t most = 0;
  for (size_t c = 0; c < cells.size(); ++c) {
    cells[c].emitted += shot.absorbed[c];
    cells[c].absorbed += shot.absorbed[c];
    result.energy.emitted += shot.absorbed[c];
    if (cells[c].emitted > cells[most].emitted) most = c;
  }
  const double escaped = std::max(shot.emitted - shot.landed, 0.0);
  cells[most].emitted += escaped;
  cells[most].escaped += escaped;
  result.energy.emitted += escaped;
  result.energy.shot += shot.landed + escaped;
  result.energy.received += shot.landed;
}

}  // namespace cpgi
