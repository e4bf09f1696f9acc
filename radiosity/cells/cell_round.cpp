#include "radiosity/cells/cell_round.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <tuple>

#include <tbb/parallel_for.h>

namespace cpgi {
namespace {

glm::dvec3 texelPower(const glm::vec3& v, float area) {
  return glm::dvec3(v) * double(area);
}

// One link's send: the irradiance collected on the sending side becomes exitance on the far side.
PortalSend sendThrough(const PortalLink& link, const CellState& s, const SolveResult& solved,
                       const std::vector<CellState>& cells, const RayScene* rays, int binRays,
                       std::vector<std::vector<int32_t>>* hits) {
  const LightmapAtlas& to = cells[link.to].atlas;
  glm::dvec3 sent(0.0), arrived(0.0);
  for (const auto& [tt, ft] : link.texels) arrived += texelPower(solved.incident[ft], to.area[tt]);
  for (int m = 0; m < 2; ++m) {
    if (m == 1 && link.fromPatches[1] == link.fromPatches[0]) break;
    const Patch& F = s.atlas.patches[link.fromPatches[m]];
    for (int j = 0; j < F.h; ++j)
      for (int i = 0; i < F.w; ++i) {
        const size_t t = size_t(F.y + j) * s.atlas.width + F.x + i;
        if (s.atlas.patch[t] == link.fromPatches[m]) sent += texelPower(solved.incident[t], s.atlas.area[t]);
      }
  }
  PortalSend send;
  send.portal = link.portal, send.from = link.from, send.to = link.to;
  for (int k = 0; k < 3; ++k) send.scale[k] = arrived[k] > 0.0 ? float(sent[k] / arrived[k]) : 0.0f;
  send.exitance.reserve(link.texels.size());
  for (const auto& [tt, ft] : link.texels) {
    const glm::vec3 e = solved.incident[ft] * send.scale;
    send.exitance.push_back({tt, e});
    send.arriving += (double(e.r) + e.g + e.b) * to.area[tt];
    send.arrivingRgb += texelPower(e, to.area[tt]);
  }
  send.watts = sent.r + sent.g + sent.b;
  // Directional portals: the moments go along in world coordinates (the far side's normal is this side's
  // negated, as the moments assume), weighted like the exitance they describe.
  if (!solved.arrivals.empty()) {
    const float weight = (send.scale.r + send.scale.g + send.scale.b) / 3.0f;
    send.moments.reserve(link.texels.size());
    for (const auto& [tt, ft] : link.texels) send.moments.push_back(solved.arrivals[ft] * weight);
  }
  if (rays && binRays > 0) {
    std::vector<glm::vec3> weights;
    weights.reserve(send.exitance.size());
    for (const auto& [tt, e] : send.exitance) weights.push_back(e);
    send.bins = portalArrivalBins(s, solved, *rays, link, weights, binRays, hits);
  }
  return send;
}

}  // namespace

double cellPower(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas) {
  double sum = 0.0;
  for (size_t i = 0; i < exitance.size(); ++i)
    if (atlas.patch[i] >= 0) sum += (double(exitance[i].r) + exitance[i].g + exitance[i].b) * atlas.area[i];
  return sum;
}

glm::dvec3 cellPowerRgb(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas) {
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < exitance.size(); ++i)
    if (atlas.patch[i] >= 0) sum += texelPower(exitance[i], atlas.area[i]);
  return sum;
}

std::vector<char> reflectorTexels(const CellState& s) {
  const std::vector<char> onPortal = portalPatchFlags(s);
  std::vector<char> reflector(s.atlas.texelCount(), 0);
  for (size_t t = 0; t < reflector.size(); ++t) {
    const int p = s.atlas.patch[t];
    if (p < 0 || onPortal[size_t(p)]) continue;
    reflector[t] = !s.cs.scene.materials[s.atlas.patches[size_t(p)].material].isEmitter();
  }
  return reflector;
}

bool cellSolvesRound(const CellState& s, double target) {
  return cellPower(s.pending, s.atlas) > 1e-6 * target;
}

SolverParams roundBudget(const CellSolveParams& params, double target, double unshot, double emitted,
                         SolveControls& controls, ShotShape& shape, size_t globalPatches) {
  const SolverParams& settings = params.solver;
  SolverParams round = settings;
  round.unshotFraction = std::clamp(0.5 * target / unshot, 1e-9, 0.999999);
  controls.minShotPower = 0.5 * target / double(std::max<size_t>(globalPatches, 1));
  shape.strongShotPower = settings.strongShotFraction * emitted;
  shape.emittersAreLamps = false;  // a cell's emitters are its portals; its lamps shot first, globally
  shape.openingPoints = std::max(1, int(std::lround(4.0f / params.portalDensityScale)));
  round.coverageRays = std::min(settings.coverageRays, kCellCoverageRays);
  return round;
}

std::vector<ArrivalBins> portalArrivalBins(const CellState& s, const SolveResult& solved,
                                           const RayScene& rays, const PortalLink& link,
                                           const std::vector<glm::vec3>& weights, int rayCount,
                                           std::vector<std::vector<int32_t>>* hits) {
  const LightmapAtlas& a = s.atlas;
  if (hits) hits->resize(link.texels.size());
  // A binned emitter (a portal of this cell re-emitting its neighbour's light) is met by many of the
  // rays: its bins normalised once here, not per ray over all kArrivalBins of them.
  std::vector<BinnedEmitter> emitters;
  emitters.reserve(s.pendingBins.size());
  std::vector<int32_t> emitterOf(s.pendingBins.empty() ? 0 : a.texelCount(), -1);
  std::vector<uint8_t> binned(a.texelCount(), 0);  // the texels a ray's direction matters for
  for (const auto& [t, b] : s.pendingBins) {
    if (size_t(t) >= emitterOf.size()) continue;
    emitterOf[size_t(t)] = int32_t(emitters.size());
    binned[size_t(t)] = 1;
    emitters.push_back(binnedEmitter(b, a.normal[size_t(t)]));
  }
  // What texel t shot in this solve towards ω (W/m² per channel): its pending exitance (the atlas's
  // emission) and what it gained, less what it left unshot; a binned emitter shapes it by its own bins.
  const ExitanceToward shotToward = [&](size_t t, const glm::vec3& omega) {
    glm::vec3 shot =
        glm::max(a.emission[t] + a.albedo[t] * solved.incident[t] - solved.residual[t], glm::vec3(0.0f));
    if (shot.r + shot.g + shot.b > 0.0f && t < emitterOf.size() && emitterOf[t] >= 0)
      shot *= binnedEmissionFactor(emitters[size_t(emitterOf[t])], omega);
    return shot;
  };
  std::vector<ArrivalBins> bins(link.texels.size());
  tbb::parallel_for(size_t(0), link.texels.size(), [&](size_t k) {
    const size_t ft = size_t(link.texels[k].second);
    const Patch& p = a.patches[size_t(a.patch[ft])];
    const int i = int(ft % size_t(a.width)) - p.x, j = int(ft / size_t(a.width)) - p.y;
    const glm::vec3 origin = p.origin + float(i) * p.texelU + float(j) * p.texelV;
    // Seeded by where the texel is, not by any index: a cell job's graph numbers its portals its own way.
    uint32_t seed = 0x811C9DC5u;
    for (int axis = 0; axis < 3; ++axis) seed = (seed ^ std::bit_cast<uint32_t>(origin[axis])) * 0x01000193u;
    std::vector<int32_t> traced;
    std::vector<int32_t>& met = hits ? (*hits)[k] : traced;
    if (met.size() != size_t(rayCount))
      met = traceArrivalHits(rays, a, origin, p.texelU, p.texelV, a.normal[ft], rayCount, seed);
    ArrivalBins b = arrivalBinsAlongHits(met, a.normal[ft], seed, shotToward, binned);
    const glm::dvec3 sum = binTotals(b);
    const glm::vec3 w = k < weights.size() ? weights[k] : glm::vec3(0.0f);
    // Each channel scaled to the light the solve delivered; a channel no ray met (a sliver the rays
    // missed) spread as a Lambertian.
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < b.size(); ++i)
        b[i][c] = sum[c] > 0.0 ? float(double(b[i][c]) * w[c] / sum[c])
                               : float(double(w[c]) * binProjectedArea(int(i)));
    bins[k] = b;
  });
  return bins;
}

CellRound cellRoundOf(size_t c, const CellState& s, const SolveResult& solved,
                      const std::vector<PortalLink>& links, const std::vector<CellState>& cells, int binRays,
                      ArrivalHitCache* hits) {
  CellRound r;
  r.cell = int(c);
  r.solved = true;
  r.timedOut = solved.timedOut;
  // What the solve left unshot is shot at the next one; it is in the radiosity already.
  r.kept = solved.residual;
  r.carried = solved.residual;
  r.keptPower = cellPower(r.kept, s.atlas);
  r.keptRgb = cellPowerRgb(r.kept, s.atlas);
  // A texel's residual is the part of its pending exitance it did not shoot (portal texels have albedo 0
  // and gain none), so its moments (and bins) are the pending ones scaled by the same share.
  for (const auto& [t, bins] : s.pendingBins) {
    const glm::vec3 pending = s.pending[size_t(t)], left = r.kept[size_t(t)];
    if (!(pending.r + pending.g + pending.b > 0.0f && left.r + left.g + left.b > 0.0f)) continue;
    glm::vec3 share(0.0f);
    for (int c = 0; c < 3; ++c)
      if (pending[c] > 0.0f) share[c] = std::clamp(left[c] / pending[c], 0.0f, 1.0f);
    ArrivalBins kept = bins;
    for (glm::vec3& x : kept) x *= share;
    r.keptBins.emplace(t, kept);
  }
  if (!s.pendingMoments.empty()) {
    r.keptMoments.assign(s.pendingMoments.size(), glm::vec4(0.0f));
    for (size_t i = 0; i < r.keptMoments.size(); ++i) {
      const float pending = s.pending[i].r + s.pending[i].g + s.pending[i].b;
      const float left = r.kept[i].r + r.kept[i].g + r.kept[i].b;
      if (s.pendingMoments[i].w > 0.0f && pending > 0.0f && left > 0.0f)
        r.keptMoments[i] = s.pendingMoments[i] * std::min(left / pending, 1.0f);
    }
  }
  if (!s.boundary) {
    r.radiosity.resize(s.atlas.texelCount());
    for (size_t t = 0; t < r.radiosity.size(); ++t) r.radiosity[t] = solved.radiosity[t] - s.carried[t];
    const std::vector<char> reflector = reflectorTexels(s);
    for (size_t t = 0; t < r.radiosity.size(); ++t)
      if (reflector[t])
        r.reflectorGain += (double(r.radiosity[t].r) + r.radiosity[t].g + r.radiosity[t].b) * s.atlas.area[t];
  }
  double collected = 0.0;
  // Sized by the caller: cells solved side by side each touch their own links' entries only.
  if (hits && hits->size() != links.size())
    throw std::invalid_argument("cellRoundOf: not one hit list a link");
  std::unique_ptr<RayScene> rays;
  if (binRays > 0 &&
      std::any_of(links.begin(), links.end(), [&](const PortalLink& l) { return l.from == int(c); }))
    rays = std::make_unique<RayScene>(s.cs.scene);
  for (size_t l = 0; l < links.size(); ++l) {
    const PortalLink& link = links[l];
    if (link.from != int(c)) continue;
    r.sends.push_back(sendThrough(link, s, solved, cells, rays.get(), binRays, hits ? &(*hits)[l] : nullptr));
    collected += r.sends.back().watts;
  }
  r.shots = solved.shots;
  r.seconds = solved.seconds;
  r.shot = solved.energy.shot;
  r.received = solved.energy.received;
  r.escaped = solved.energy.escaped();
  r.created = solved.energy.created;
  r.worstShotGain = solved.energy.worstShotGain;
  // Portal texels have albedo 0: all they received counts as absorbed by the solver.
  r.absorbed = solved.energy.absorbed - collected;
  return r;
}

CellRound waitingCellRound(size_t c, const CellState& s) {
  CellRound r;
  r.cell = int(c);
  r.kept = s.pending;
  r.carried = s.carried;
  r.keptMoments = s.pendingMoments;
  r.keptBins = s.pendingBins;
  r.keptPower = cellPower(r.kept, s.atlas);
  r.keptRgb = cellPowerRgb(r.kept, s.atlas);
  return r;
}

namespace {

// `addOwn()` and `addSend(send)` for each of `arriving` in the solver's order: a waiting cell's own share
// first, otherwise by sending cell with its own share at its own index.
template <class Own, class Send>
void inSolverOrder(const CellRound& own, const std::vector<const PortalSend*>& arriving, Own addOwn,
                   Send addSend) {
  bool ownAdded = !own.solved;
  if (ownAdded) addOwn();
  for (const PortalSend* send : arriving) {
    if (!ownAdded && send->from > own.cell) {
      addOwn();
      ownAdded = true;
    }
    addSend(*send);
  }
  if (!ownAdded) addOwn();
}

// Per texel, `ownShare` and each send's entries added in the solver's order: a waiting cell's own share
// first, otherwise by sending cell with its own share at its own index. `entry(send, k)` is what a send's
// k-th exitance entry adds (at that entry's texel), for k below `count(send)`.
template <class T, class Count, class Entry>
std::vector<T> gatherInSolverOrder(const CellRound& own, const std::vector<T>& ownShare,
                                   const std::vector<const PortalSend*>& arriving, size_t texels, Count count,
                                   Entry entry) {
  std::vector<T> sum(texels, T(0.0f));
  inSolverOrder(
      own, arriving,
      [&] {
        for (size_t i = 0; i < ownShare.size() && i < texels; ++i) sum[i] += ownShare[i];
      },
      [&](const PortalSend& send) {
        for (size_t k = 0; k < count(send); ++k) sum[size_t(send.exitance[k].first)] += entry(send, k);
      });
  return sum;
}

}  // namespace

std::vector<glm::vec3> gatherPending(const CellRound& own, const std::vector<const PortalSend*>& arriving,
                                     size_t texels) {
  return gatherInSolverOrder(
      own, own.kept, arriving, texels, [](const PortalSend& s) { return s.exitance.size(); },
      [](const PortalSend& s, size_t k) { return s.exitance[k].second; });
}

std::map<int32_t, ArrivalBins> gatherPendingBins(const CellRound& own,
                                                 const std::vector<const PortalSend*>& arriving) {
  // In the solver's order, so that jobs and one process add the same floats.
  std::map<int32_t, ArrivalBins> sum;
  auto add = [&](int32_t t, const ArrivalBins& b) {
    ArrivalBins& into = sum.try_emplace(t, ArrivalBins{}).first->second;
    for (size_t i = 0; i < b.size(); ++i) into[i] += b[i];
  };
  inSolverOrder(
      own, arriving,
      [&] {
        for (const auto& [t, b] : own.keptBins) add(t, b);
      },
      [&](const PortalSend& send) {
        for (size_t k = 0; k < std::min(send.bins.size(), send.exitance.size()); ++k)
          add(send.exitance[k].first, send.bins[k]);
      });
  return sum;
}

std::vector<glm::vec4> gatherPendingMoments(const CellRound& own,
                                            const std::vector<const PortalSend*>& arriving, size_t texels) {
  bool any = !own.keptMoments.empty();
  for (const PortalSend* send : arriving) any = any || !send->moments.empty();
  if (!any) return {};
  return gatherInSolverOrder(
      own, own.keptMoments, arriving, texels,
      [](const PortalSend& s) { return std::min(s.moments.size(), s.exitance.size()); },
      [](const PortalSend& s, size_t k) { return s.moments[k]; });
}

std::vector<const PortalSend*> sendsTo(int to, const std::vector<const PortalSend*>& sends) {
  std::vector<const PortalSend*> out;
  for (const PortalSend* s : sends)
    if (s->to == to) out.push_back(s);
  std::sort(out.begin(), out.end(), [](const PortalSend* a, const PortalSend* b) {
    return std::tie(a->from, a->portal) < std::tie(b->from, b->portal);
  });
  return out;
}

double roundUnshot(const std::vector<double>& keptPower, std::vector<const PortalSend*> sends) {
  std::sort(sends.begin(), sends.end(), [](const PortalSend* a, const PortalSend* b) {
    return std::tie(a->to, a->from, a->portal) < std::tie(b->to, b->from, b->portal);
  });
  double unshot = 0.0;
  size_t k = 0;
  for (size_t c = 0; c < keptPower.size(); ++c) {
    unshot += keptPower[c];
    for (; k < sends.size() && sends[k]->to == int(c); ++k) unshot += sends[k]->arriving;
  }
  return unshot;
}

void addCellRound(const CellRound& r, const CellState& s, const CellGraph& graph, SolveResult& result) {
  if (!r.solved) return;
  CellSolveData& d = *result.perCell;
  CellEnergy& ce = d.cells[size_t(r.cell)];
  ++ce.solves;
  ce.shots += r.shots;
  result.shots += r.shots;
  ce.seconds += r.seconds;
  ce.escaped += r.escaped;
  ce.created += r.created;
  ce.worstShotGain = std::max(ce.worstShotGain, r.worstShotGain);
  result.energy.created += r.created;
  result.energy.worstShotGain = std::max(result.energy.worstShotGain, r.worstShotGain);
  result.energy.shot += r.shot;
  result.energy.received += r.received;
  if (!r.radiosity.empty())
    for (const auto& [g, t] : s.toGlobal) result.radiosity[g] += r.radiosity[t];
  for (const PortalSend& send : r.sends) {
    ce.sent += send.watts;
    d.cells[size_t(send.to)].received += send.watts;
    PortalEnergy& pe = d.portals[size_t(send.portal)];
    (send.from == graph.portals[size_t(send.portal)].cellA ? pe.aToB : pe.bToA) += send.watts;
  }
  ce.absorbed += r.absorbed;
}

}  // namespace cpgi
