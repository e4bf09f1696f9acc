// The binned portals' arrival rays traced once and kept for every later round (cell_round.h,
// ArrivalHitCache): a send's bins from the texels its rays met in a round of other light are the bins of a
// fresh trace, float for float, for the light the cell's reflectors shot and for a portal texel that
// re-emits by its own bins. A cache kept by the wrong link or texel, or one holding the first round's
// light rather than the texels met, would differ.
#include "radiosity/cells/cell_round.h"

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/cells/cell_atlases.h"
#include "scenes/stability_scenes.h"

namespace cpgi {
namespace {

// A solve's result for cell `s` whose light differs from texel to texel and from round to round.
SolveResult roundLight(const CellState& s, int round) {
  SolveResult r;
  const size_t n = s.atlas.texelCount();
  r.radiosity.assign(n, glm::vec3(0.0f));
  r.residual.assign(n, glm::vec3(0.0f));
  r.incident.resize(n);
  for (size_t t = 0; t < n; ++t)
    r.incident[t] =
        glm::vec3(float(1 + (7 * t + 3 * size_t(round)) % 5), float(1 + (3 * t + size_t(round)) % 4),
                  0.5f + float((t + 5 * size_t(round)) % 3));
  return r;
}

// Cell `c`'s portal texels where light arrives emit by bins leaning towards one side (a neighbour's light
// re-emitted), so the rays that meet them read those bins in their own direction.
void emitThroughPortalsByBins(CellState& s, int c, const std::vector<PortalLink>& links) {
  for (const PortalLink& link : links) {
    if (link.to != c) continue;
    for (const auto& [tt, ft] : link.texels) {
      ArrivalBins bins;
      for (int b = 0; b < kArrivalBins; ++b)
        bins[size_t(b)] = glm::vec3(float(1 + b % kBinGrid), 1.0f, float(1 + b / kBinGrid));
      s.pendingBins[tt] = bins;
      s.atlas.emission[size_t(tt)] = glm::vec3(2.0f, 1.0f, 0.5f);
    }
  }
}

TEST(ArrivalHits, KeptFromARoundOfOtherLightGiveTheBinsOfAFreshTrace) {
  const SeedScene scene = makeBuiltinScene("office-small");
  Context ctx;
  CellSolveParams params;
  params.atlas.texelsPerQuad = 6;
  const LightmapAtlas global = buildAtlas(scene.scene, findQuads(scene.scene), params.atlas, ctx);
  const std::vector<int> cellOf = scene.cells.cellOfTriangle(scene.scene.triangles.size());
  std::vector<CellState> cells =
      buildMappedCellAtlases(scene.scene, scene.cells, params, cellOf, global, ctx);
  const std::vector<PortalLink> links = linkPortals(scene.cells, cells);
  for (size_t c = 0; c < cells.size(); ++c) emitThroughPortalsByBins(cells[c], int(c), links);
  constexpr int kRays = 400;  // over kArrivalBins: as many rays through each bin
  ArrivalHitCache hits(links.size());
  size_t compared = 0, changed = 0;
  for (size_t c = 0; c < cells.size(); ++c) {
    const CellRound first = cellRoundOf(c, cells[c], roundLight(cells[c], 1), links, cells, kRays, &hits);
    const SolveResult second = roundLight(cells[c], 2);
    const CellRound kept = cellRoundOf(c, cells[c], second, links, cells, kRays, &hits);
    const CellRound fresh = cellRoundOf(c, cells[c], second, links, cells, kRays);
    ASSERT_EQ(kept.sends.size(), fresh.sends.size());
    for (size_t i = 0; i < fresh.sends.size(); ++i) {
      ASSERT_EQ(kept.sends[i].bins.size(), fresh.sends[i].bins.size());
      for (size_t k = 0; k < fresh.sends[i].bins.size(); ++k) {
        EXPECT_EQ(kept.sends[i].bins[k], fresh.sends[i].bins[k])
            << "cell " << c << " send " << i << " texel " << k;
        changed += first.sends[i].bins[k] != fresh.sends[i].bins[k];
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 20u);
  EXPECT_GT(changed, compared / 2);  // the second round's light is not the first's
  for (size_t l = 0; l < links.size(); ++l) {
    ASSERT_EQ(hits[l].size(), links[l].texels.size()) << "link " << l;
    for (const std::vector<int32_t>& h : hits[l]) EXPECT_EQ(h.size(), size_t(kRays));
  }
}

}  // namespace
}  // namespace cpgi
