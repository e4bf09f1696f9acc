#include "decomposition/portal_merge.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace cpgi::decomp {
namespace {

// A piece in the frame of the piece it may join: that one's corner 0 as origin, its edges as (u, v),
// its normal as n.
struct Frame2 {
  glm::vec3 origin, u, v, n;
  explicit Frame2(const PortalQuad& q) : origin(q.corners[0]), n(q.normal) {
    u = glm::normalize(q.corners[1] - q.corners[0]);
    v = glm::normalize(q.corners[3] - q.corners[0]);
  }
  glm::vec2 at(const glm::vec3& p) const { return {glm::dot(p - origin, u), glm::dot(p - origin, v)}; }
  float off(const glm::vec3& p) const { return glm::dot(p - origin, n); }
};

struct Rect {
  glm::vec2 lo{1e30f}, hi{-1e30f};
  void extend(const glm::vec2& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  float area() const { return (hi.x - lo.x) * (hi.y - lo.y); }
};

// Tries to fold `piece` into `into` (whose own pieces cover `pieceArea` m²); on success `into` holds the
// rectangle round both, in its plane.
bool tryMerge(FittedPortal& into, float& pieceArea, const FittedPortal& piece, float h,
              const PortalMergeParams& params) {
  const PortalQuad& a = into.quad;
  const PortalQuad& b = piece.quad;
  if (glm::dot(a.normal, b.normal) < std::cos(glm::radians(params.maxAngleDegrees))) return false;
  const Frame2 fr(a);
  const float tol = params.maxGapVoxels * h;
  Rect ra, rb;
  for (const glm::vec3& p : a.corners) ra.extend(fr.at(p));
  for (const glm::vec3& p : b.corners) {
    if (std::abs(fr.off(p)) > tol) return false;
    rb.extend(fr.at(p));
  }
  const glm::vec2 gap = glm::max(ra.lo - rb.hi, rb.lo - ra.hi);
  if (gap.x > tol || gap.y > tol) return false;
  Rect both = ra;
  both.extend(rb.lo), both.extend(rb.hi);
  const float pieces = pieceArea + b.area;
  if (both.area() > params.maxFill * pieces) return false;
  const glm::vec3 o = fr.origin;
  into.quad.corners = {o + both.lo.x * fr.u + both.lo.y * fr.v, o + both.hi.x * fr.u + both.lo.y * fr.v,
                       o + both.hi.x * fr.u + both.hi.y * fr.v, o + both.lo.x * fr.u + both.hi.y * fr.v};
  const glm::vec3 n = a.normal;
  computePortalFrame(into.quad);
  into.quad.normal = n;
  into.halfWidth = std::max(into.halfWidth, piece.halfWidth);
  into.faces += piece.faces;
  into.depth = std::max(into.depth, piece.depth);
  pieceArea = pieces;
  return true;
}

// One pair's portals merged greedily, largest first, until no two merge; `accept` may refuse a merge by
// the pair's portals it would leave.
template <typename Accept>
std::vector<FittedPortal> mergePair(std::vector<FittedPortal> list, float h, const PortalMergeParams& params,
                                    Accept&& accept) {
  std::sort(list.begin(), list.end(),
            [](const FittedPortal& x, const FittedPortal& y) { return x.quad.area > y.quad.area; });
  std::vector<float> pieceArea;
  for (const FittedPortal& p : list) pieceArea.push_back(p.quad.area);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size();) {
        FittedPortal merged = list[i];
        float area = pieceArea[i];
        std::vector<FittedPortal> candidate;
        if (tryMerge(merged, area, list[j], h, params)) {
          candidate = list;
          candidate[i] = merged;
          candidate.erase(candidate.begin() + ptrdiff_t(j));
        }
        if (!candidate.empty() && accept(candidate)) {
          list = std::move(candidate);
          pieceArea[i] = area;
          pieceArea.erase(pieceArea.begin() + ptrdiff_t(j));
          changed = true;
        } else {
          ++j;
        }
      }
  }
  return list;
}


}  // namespace

MergedPortals mergePortalPieces(PortalSet& set, const GridFrame& frame, const PortalMergeParams& params,
                                Context& ctx) {
  auto timer = ctx.time("portal_merge");
  MergedPortals out;
  if (!(params.maxAngleDegrees > 0.0f)) return out;
  using Pair = std::pair<int, int>;
  std::map<Pair, std::vector<FittedPortal>> before, after;
  for (const FittedPortal& p : set.portals) before[{p.quad.cellA, p.quad.cellB}].push_back(p);
  for (const auto& [pair, list] : before)
    after[pair] = list.size() < 2
                      ? list
                      : mergePair(list, float(frame.voxel), params, [](const auto&) { return true; });
  // In the order the pairs first came, so that an unmerged set comes back as it was.
  auto assemble = [&]() {
    std::vector<FittedPortal> all;
    std::map<Pair, bool> done;
    for (const FittedPortal& p : set.portals) {
      const Pair pair{p.quad.cellA, p.quad.cellB};
      if (done[pair]) continue;
      done[pair] = true;
      all.insert(all.end(), after[pair].begin(), after[pair].end());
    }
    return all;
  };
  // A merged quad keeps its pieces' plane only within a voxel or two: a pair the merges leave leaking
  // is merged again one piece at a time, each merge kept only when it uncovers no voxel face of the pair
  // (leaks elsewhere, there before, are not this stage's).
  const std::map<Pair, size_t> leaksBefore = leakingFacesByPair(frame, set.cell, quadsOf(set.portals));
  const std::map<Pair, size_t> leaksAfter = leakingFacesByPair(frame, set.cell, quadsOf(assemble()));
  auto leaksOf = [](const std::map<Pair, size_t>& leaks, const Pair& p) {
    const auto it = leaks.find({std::min(p.first, p.second), std::max(p.first, p.second)});
    return it == leaks.end() ? size_t(0) : it->second;
  };
  for (const auto& [pair, list] : before) {
    if (after[pair].size() == list.size() || leaksOf(leaksAfter, pair) <= leaksOf(leaksBefore, pair))
      continue;
    ++out.pairsKept;
    const size_t base = leaksOf(leaksBefore, pair);
    after[pair] =
        mergePair(list, float(frame.voxel), params, [&](const std::vector<FittedPortal>& candidate) {
          return leaksOf(leakingFacesByPair(frame, set.cell, quadsOf(candidate)), pair) <= base;
        });
  }
  set.portals = assemble();
  for (const auto& [pair, list] : before) out.merged += int(list.size() - after[pair].size());
  set.leakingFaces = countLeakingFaces(frame, set.cell, quadsOf(set.portals));
  return out;
}

}  // namespace cpgi::decomp
