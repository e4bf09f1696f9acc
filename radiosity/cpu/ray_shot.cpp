#include "radiosity/cpu/ray_shot.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "radiosity/solve/emission_bins.h"
#include "radiosity/solve/emission_lobes.h"

namespace cpgi {
namespace {

constexpr float kPi = 3.14159265358979f;
// A node holding binned texels stands for them whole only beyond this many of its radii, where it looks
// smaller than about half the narrowest bins (shaders/directional.glsl, BIN_FAR).
constexpr float kBinFar = 10.0f;
// The most sub-disks per edge of a binned texel near a receiver (Gather::nearSubdisks; receive.comp's
// NEAR_BIN_SUBDISKS).
constexpr int kNearBinSubdisks = 32;

// A shooter texel: where it is, its area, its unshot radiosity.
struct ShooterTexel {
  glm::vec3 position{0.0f};
  float area = 0.0f;
  glm::vec3 radiosity{0.0f};
  glm::vec4 lobe{0.0f};  // ShooterEmission::lobes; zero: Lambertian
};

// A piece of a region (a block, or the whole region) as seen from afar: its area and mean radiosity, the
// mean and spread of its power over the chart (texels), and the disk round it that "far" is measured from.
struct FarPiece {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  float area = 0.0f;
  glm::vec3 radiosity{0.0f};
  glm::vec3 mean{0.0f}, spreadU{0.0f}, spreadV{0.0f};  // world-space: mean ± spreadU ± spreadV
  /// Its texels' lobes mixed (mixedLobe); a node holding binned texels: (n, −(k + 1)), its bins the k-th
  /// slot (kBinSlotFloats) of RegionPieces::nodeBins.
  glm::vec4 lobe{0.0f};
};

// A node of a region's quadtree (receive.comp walks the GPU's residual pyramid the same way): a texel, or
// up to four children over the halves of its rectangle.
struct PieceNode {
  FarPiece piece;
  int32_t texel = -1;  // a leaf: its index in RegionPieces::texels
  std::array<int32_t, 4> children{-1, -1, -1, -1};
};

struct RegionPieces {
  double power = 0.0;  // R + G + B, W
  size_t member = 0;   // its patch's place among the shot's (ShotMember)
  // Its receivers see it through its own eyes (true), or through those of the group it closes or sits in:
  // a cluster's regions follow each other, the first holding the cluster's eyes (eyePower: theirs all).
  bool groupEnd = true;
  double eyePower = 0.0;
  // Drawn by power, stratified: each stands for an equal share of it. `sets` interleaved sets of them
  // (RayShotParams::eyeSetsPerEdge): set k is eyes k, k + sets, k + 2 sets, ..., itself stratified.
  std::vector<glm::vec3> eyes;
  int sets = 1;
  size_t eyesPerSet() const { return eyes.size() / size_t(sets); }
  std::vector<PieceNode> nodes;  // nodes[0]: the whole region
  std::vector<ShooterTexel> texels;
  std::vector<float> nodeBins;  // kBinSlotFloats per binned node (FarPiece::lobe)
  const FarPiece& whole() const { return nodes[0].piece; }
};

using ChartTexels = std::vector<std::pair<glm::ivec2, ShooterTexel>>;

float channelSum(const glm::vec3& v) {
  return v.r + v.g + v.b;
}

// The piece of patch `p` over chart texels [i0, i1) × [j0, j1), from its texels `cells` (chart coordinates).
FarPiece farPiece(const Patch& p, const ChartTexels& cells) {
  FarPiece f;
  double weight = 0.0;
  glm::dvec2 m(0.0), m2(0.0);
  glm::dvec3 flux(0.0);
  glm::ivec2 lo(1 << 30), hi(-(1 << 30));
  for (const auto& [c, t] : cells) {
    f.area += t.area;
    flux += glm::dvec3(t.radiosity) * double(t.area);
    const double w = double(channelSum(t.radiosity)) * t.area;
    const glm::dvec2 at = glm::dvec2(c) + 0.5;
    weight += w, m += w * at, m2 += w * at * at;
    lo = glm::min(lo, c), hi = glm::max(hi, c + 1);
  }
  if (f.area <= 0.0f || weight <= 0.0) {
    f.area = 0.0f;
    return f;
  }
  f.radiosity = glm::vec3(flux / double(f.area));
  const glm::dvec2 mean = m / weight;
  // The power's spread along each axis, a texel's own (uniform, 1/12) included: for a uniform piece the
  // points mean ± spread are the 2×2 Gauss rule (receive.comp, nodePiece).
  const glm::dvec2 sd = glm::sqrt(glm::max(m2 / weight - mean * mean, 0.0) + 1.0 / 12.0);
  f.mean = p.origin + float(mean.x) * p.texelU + float(mean.y) * p.texelV;
  f.spreadU = float(sd.x) * p.texelU, f.spreadV = float(sd.y) * p.texelV;
  const glm::vec2 mid = 0.5f * glm::vec2(lo + hi), size = glm::vec2(hi - lo);
  f.centre = p.origin + mid.x * p.texelU + mid.y * p.texelV;
  f.radius = 0.5f * std::max(glm::length(size.x * p.texelU + size.y * p.texelV),
                             glm::length(size.x * p.texelU - size.y * p.texelV));
  return f;
}

uint32_t regionHash(uint32_t r) {
  uint32_t h = r * 0x9E3779B9u + 0x7F4A7C15u;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  return h;
}

// The moment-matched mixture of lobes (shaders/directional.glsl, addLobe and mixedLobe): weight, centre
// and spread of the Gaussians by power, which keeps the mixture normalised. Binned lobes do not mix.
struct LobeMix {
  glm::vec4 sum{0.0f}, second{0.0f};
  void add(const glm::vec4& lobe, const glm::vec3& n, float power) {
    if (lobe.w < 0.0f) {
      second.w = 1.0f;
      return;
    }
    const float a = glm::dot(glm::vec3(lobe), n);
    const glm::vec3 s0 = glm::vec3(lobe) - a * n;
    const float pa = power * std::max(a, 0.0f);
    sum += glm::vec4(pa * s0, pa);
    second += glm::vec4(pa * lobe.w, pa * glm::dot(s0, s0), power, 0.0f);
  }
  bool binned() const { return second.w > 0.0f; }
  glm::vec4 mixed(const glm::vec3& n) const {
    if (!(sum.w > 0.0f) || !(second.z > 0.0f)) return glm::vec4(0.0f);
    const glm::vec3 s0 = glm::vec3(sum) / sum.w;
    const float sigma2 = second.x / sum.w + 0.5f * std::max(second.y / sum.w - glm::dot(s0, s0), 0.0f);
    return glm::vec4(s0 + (sum.w / second.z) * n, sigma2);
  }
};

// A piece's bins, a slot of kBinSlotFloats from `bins` (ShooterEmission::bins for a texel,
// RegionPieces::nodeBins for a node, told apart as the shader does: a node's lobe holds the shooter's
// normal).
const float* binsOf(const glm::vec4& lobe, const glm::vec3& n, std::span<const float> texelBins,
                    std::span<const float> nodeBins) {
  const size_t k = size_t(-lobe.w) - 1;
  return (glm::dot(glm::vec3(lobe), n) > 0.5f ? nodeBins.data() : texelBins.data()) + k * kBinSlotFloats;
}

// f of a slot towards a direction, per channel, interpolated between its bins (emission_bins.h).
glm::vec3 binFactor(const float* slot, const BinTaps& taps) {
  glm::vec3 f(0.0f);
  for (int k = 0; k < 4; ++k) {
    const int b = taps.bin[size_t(k)];
    f += taps.weight[size_t(k)] * glm::vec3(slot[4 * b], slot[4 * b + 1], slot[4 * b + 2]);
  }
  return f;
}

// Node `index`'s lobe from its children's (or its texel's), and for one holding binned texels the
// power-weighted mean of their bins, each channel by its own power (a Lambertian's all ones:
// shooter_pyramid.comp, mixNodeBins).
void mixNodeLobe(const Patch& p, int32_t index, std::span<const float> texelBins, RegionPieces& out) {
  PieceNode& node = out.nodes[size_t(index)];
  if (node.texel >= 0) {
    node.piece.lobe = out.texels[size_t(node.texel)].lobe;
    return;
  }
  LobeMix mix;
  for (int32_t c : node.children)
    if (c >= 0) {
      const FarPiece& f = out.nodes[size_t(c)].piece;
      mix.add(f.lobe, p.normal, channelSum(f.radiosity) * f.area);
    }
  if (!mix.binned()) {
    node.piece.lobe = mix.mixed(p.normal);
    return;
  }
  std::vector<double> bins(kBinSlotFloats, 0.0);
  glm::dvec3 sum(0.0);
  for (int32_t c : node.children) {
    if (c < 0) continue;
    const FarPiece& f = out.nodes[size_t(c)].piece;
    const glm::dvec3 w = glm::dvec3(f.radiosity) * double(f.area);
    const float* from = f.lobe.w < 0.0f ? binsOf(f.lobe, p.normal, texelBins, out.nodeBins) : nullptr;
    for (int i = 0; i < kBinSlotFloats; ++i)
      if (i % 4 < 3) bins[size_t(i)] += w[i % 4] * (from ? double(from[i]) : 1.0);
    sum += w;
  }
  const size_t k = out.nodeBins.size() / kBinSlotFloats;
  for (int i = 0; i < kBinSlotFloats; ++i) {
    const double total = i % 4 < 3 ? sum[i % 4] : 0.0;
    out.nodeBins.push_back(total > 0.0 ? float(bins[size_t(i)] / total) : 1.0f);
  }
  out.nodes[size_t(index)].piece.lobe = glm::vec4(p.normal, -float(k + 1));
}

// The quadtree over chart texels [lo, hi) of `cells` (all inside it), appended to `out`; its index, or -1
// when nothing in it has area. With `emission`, each node's lobe mixed from its children's.
int32_t buildNode(const Patch& p, const ChartTexels& cells, glm::ivec2 lo, glm::ivec2 hi,
                  const ShooterEmission* emission, RegionPieces& out) {
  const FarPiece piece = farPiece(p, cells);
  if (piece.area <= 0.0f) return -1;
  const int32_t index = int32_t(out.nodes.size());
  out.nodes.push_back({piece});
  if (cells.size() == 1 && hi - lo == glm::ivec2(1)) {
    out.nodes[size_t(index)].texel = int32_t(out.texels.size());
    out.texels.push_back(cells[0].second);
    if (emission) mixNodeLobe(p, index, emission->bins, out);
    return index;
  }
  // Halves along each axis longer than a texel.
  const glm::ivec2 size = hi - lo, mid = lo + size / 2;
  auto quarter = [&](glm::ivec2 c) {
    return (size.x > 1 && c.x >= mid.x ? 1 : 0) + (size.y > 1 && c.y >= mid.y ? 2 : 0);
  };
  std::array<ChartTexels, 4> quarters;
  for (const auto& cell : cells) quarters[size_t(quarter(cell.first))].push_back(cell);
  for (int q = 0; q < 4; ++q) {
    if (quarters[size_t(q)].empty()) continue;
    const glm::ivec2 qlo{q & 1 ? mid.x : lo.x, q & 2 ? mid.y : lo.y};
    const glm::ivec2 qhi{q & 1 || size.x == 1 ? hi.x : mid.x, q & 2 || size.y == 1 ? hi.y : mid.y};
    out.nodes[size_t(index)].children[size_t(q)] = buildNode(p, quarters[size_t(q)], qlo, qhi, emission, out);
  }
  if (emission) mixNodeLobe(p, index, emission->bins, out);
  return index;
}

// The bits of x and y (each under 2^16) interleaved: the texel's place along a Z-order curve.
uint32_t zOrder(glm::ivec2 c) {
  auto spread = [](uint32_t v) {
    v &= 0xFFFFu;
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    return (v | (v << 1)) & 0x55555555u;
  };
  return spread(uint32_t(c.x)) | (spread(uint32_t(c.y)) << 1);
}

// `draws` texels of a region drawn with probability ∝ their unshot power at u, u + 1/draws, ... along a
// Z-order curve from its corner `corner`, as pick_eyes.comp's descent of the residual pyramid draws them:
// each eye stands for a compact block of the region. In rows, eight eyes of a region 8 texels square fell
// one a row, anywhere along it, and a door's light into the next room varied nearly as much from draw to draw
// with four times the eyes (tests/radiosity/cpu/eye_sets_test.cpp).
std::vector<glm::vec3> drawEyes(const ChartTexels& all, glm::ivec2 corner, float u, int draws) {
  std::vector<std::pair<uint32_t, size_t>> order(all.size());
  for (size_t i = 0; i < all.size(); ++i) order[i] = {zOrder(all[i].first - corner), i};
  std::sort(order.begin(), order.end());
  std::vector<double> cumulative(all.size());
  double sum = 0.0;
  for (size_t i = 0; i < order.size(); ++i) {
    const ShooterTexel& t = all[order[i].second].second;
    sum += std::max(double(channelSum(t.radiosity)) * t.area, 0.0);
    cumulative[i] = sum;
  }
  std::vector<glm::vec3> eyes;
  for (int k = 0; k < draws; ++k) {
    const double target = double(std::fmod(u + float(k) / float(draws), 1.0f)) * sum;
    const size_t i =
        size_t(std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
    eyes.push_back(all[order[std::min(i, order.size() - 1)].second].second.position);
  }
  return eyes;
}

// A cluster's eyes (ShotMember): drawEyes over every texel of its patches, placed on the Z-order curve of
// the first patch's chart grid (their common plane), one eye and one set when the cluster is no wider than
// `oneEyeRadius` as a region would be. The first region, which holds them, sees for all.
void clusterEyes(const RayShotScene& s, std::span<const ShotMember> members,
                 std::span<const glm::vec3> residual, uint32_t shotNumber, int eyes, int sets,
                 float oneEyeRadius, std::vector<RegionPieces>& regions) {
  const Patch& first = s.atlas.patches[size_t(members.front().patch)];
  const glm::vec3 du = first.texelU / glm::dot(first.texelU, first.texelU),
                  dv = first.texelV / glm::dot(first.texelV, first.texelV);
  ChartTexels all;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const ShotMember& m : members)
    for (uint32_t t : s.patchTexels[size_t(m.patch)]) {
      const glm::vec3 at = s.atlas.position[t] - first.origin;
      const glm::ivec2 cell(int(std::floor(glm::dot(at, du))), int(std::floor(glm::dot(at, dv))));
      all.push_back({cell, {s.atlas.position[t], s.atlas.area[t], residual[t]}});
      lo = glm::min(lo, s.atlas.position[t]), hi = glm::max(hi, s.atlas.position[t]);
    }
  glm::ivec2 corner(1 << 30);
  for (const auto& [c, t] : all) corner = glm::min(corner, c);
  if (all.size() == 1 || 0.5f * glm::length(hi - lo) < oneEyeRadius) eyes = 1, sets = 1;
  RegionPieces& lead = regions.front();
  lead.sets = sets, lead.eyes.clear(), lead.eyePower = 0.0;
  const float u =
      float((regionHash(uint32_t(members.front().patch)) + shotNumber * 0x9E3779B9u) >> 8) / 16777216.0f;
  for (const glm::vec3& eye : drawEyes(all, corner, u, eyes * sets))
    lead.eyes.push_back(eye + first.normal * s.offset);
  for (RegionPieces& r : regions) {
    lead.eyePower += r.power;
    r.groupEnd = false;
    if (&r != &lead) r.eyes.clear();
  }
  regions.back().groupEnd = true;
}

// The region's pieces and its eyes: texels drawn with probability ∝ their unshot power (pick_eyes.comp's
// sequence: a hashed offset per region, the golden ratio per shot), stratified; `eyes` per set, `sets`
// interleaved sets.
RegionPieces regionPieces(const RayShotScene& s, int shooter, const glm::ivec4& rect,
                          std::span<const glm::vec3> residual, uint32_t region, uint32_t shotNumber, int eyes,
                          int sets, float oneEyeRadius, const ShooterEmission& emission) {
  const Patch& p = s.atlas.patches[size_t(shooter)];
  RegionPieces out;
  ChartTexels all;
  for (int j = rect.y; j < rect.w; ++j)
    for (int i = rect.x; i < rect.z; ++i) {
      const size_t t = size_t(p.y + j) * s.atlas.width + size_t(p.x + i);
      if (s.atlas.patch[t] != shooter) continue;
      ShooterTexel st{s.atlas.position[t], s.atlas.area[t], residual[t]};
      if (!emission.lobes.empty()) st.lobe = emission.lobes[t];
      all.push_back({{i, j}, st});
      out.power += double(channelSum(st.radiosity)) * st.area;
    }
  if (!(out.power > 0.0)) return out;
  const ShooterEmission* lobed = emission.lobes.empty() ? nullptr : &emission;
  if (buildNode(p, all, {rect.x, rect.y}, {rect.z, rect.w}, lobed, out) != 0) {
    out.power = 0.0;
    return out;
  }
  // One eye where more would see the same: every draw lands on a region of one texel, and eyes on a
  // region a hand's width across (a book's spine) sit closer together than the coarse texels that receive.
  if (all.size() == 1 || out.whole().radius < oneEyeRadius) eyes = 1, sets = 1;
  out.sets = sets;
  out.eyePower = out.power;
  const float u = float((regionHash(region) + shotNumber * 0x9E3779B9u) >> 8) / 16777216.0f;
  for (const glm::vec3& eye : drawEyes(all, {rect.x, rect.y}, u, eyes * sets))
    out.eyes.push_back(eye + p.normal * s.offset);
  return out;
}

// The form factor kernels of receive.comp: ΔB F(dA_x → piece) with the shooter's normal `ns`, times the
// piece's emission lobe towards the receiver when the shooter is not Lambertian (shaders/directional.glsl).
struct Gather {
  glm::vec3 x, n, ns;
  float farField;
  const ShooterEmission* emission = nullptr;  // null: every piece Lambertian
  std::span<const float> nodeBins = {};       // the region's (RegionPieces::nodeBins)
  BinFrame frame{};                           // the shooter's bins' frame
  float receiverArea = 0.0f;                  // m², for the lobe's blur over the receiver texel

  // The receiver texel's angular variance seen from the shooter (directional.glsl, receiverBlur): a beam
  // narrower than the texel would otherwise light it fully or not at all.
  float receiverBlur(const glm::vec3& v) const {
    const float r2 = glm::dot(v, v), r = std::sqrt(r2);
    const float cr = std::abs(glm::dot(n, v)) / r, cs = std::max(std::abs(glm::dot(ns, v)) / r, 0.1f);
    return std::min(receiverArea * cr / (12.0f * r2 * cs * cs * cs), 0.1f);
  }
  glm::vec3 emitted(const glm::vec3& f, const glm::vec4& lobe, const glm::vec3& v) const {
    if (!emission || lobe == glm::vec4(0.0f)) return f;
    const glm::vec3 omega = -glm::normalize(v);
    if (lobe.w < 0.0f)
      return f * binFactor(binsOf(lobe, ns, emission->bins, nodeBins), binTaps(frame, omega));
    return f * emissionLobeFactor(lobe, ns, omega, receiverBlur(v));
  }
  glm::vec3 point(const glm::vec3& c, float area, const glm::vec3& b, const glm::vec4& lobe) const {
    const glm::vec3 v = c - x;
    const float r2 = glm::dot(v, v), ci = glm::dot(n, v), cs = -glm::dot(ns, v);
    if (ci <= 0.0f || cs <= 0.0f || r2 <= 0.0f) return glm::vec3(0.0f);
    return emitted(b * (area * ci * cs / (kPi * r2 * r2)), lobe, v);
  }
  glm::vec3 disk(const glm::vec3& c, float area, const glm::vec3& b, const glm::vec4& lobe) const {
    const glm::vec3 v = c - x;
    const float r2 = glm::dot(v, v), ci = glm::dot(n, v), cs = -glm::dot(ns, v);
    if (ci <= 0.0f || cs <= 0.0f || r2 <= 0.0f) return glm::vec3(0.0f);
    return emitted(b * (area * ci * cs / (r2 * (kPi * r2 + area))), lobe, v);
  }
  bool far(const glm::vec3& c, float radius) const {
    const glm::vec3 d = c - x;
    const float f = farField * radius;
    return glm::dot(d, d) > f * f;
  }
  // Far enough for a piece (centre c, radius) to stand for its texels, and its lobe wider than the piece
  // looks from here (directional.glsl, lobeResolvesPiece): a narrow beam through a door is sent from
  // where each texel sends it, a binned node's only from kBinFar of its radii.
  bool farFor(const glm::vec3& c, float radius, const glm::vec4& lobe) const {
    if (!far(c, radius)) return false;
    if (!emission) return true;
    const glm::vec3 d = c - x;
    const float r2 = glm::dot(d, d), rr = radius * radius, a = glm::dot(glm::vec3(lobe), ns);
    if (lobe.w < 0.0f) return !(a > 0.5f) || r2 >= kBinFar * kBinFar * rr;
    return !(a > 0.0f) || lobe.w * r2 >= rr;
  }
  bool farPieceFor(const FarPiece& f) const { return farFor(f.centre, f.radius, f.lobe); }
  glm::vec3 piece(const FarPiece& f) const {
    const float a = 0.25f * f.area;
    const glm::vec3 &c = f.mean, &u = f.spreadU, &v = f.spreadV;
    return point(c - u - v, a, f.radiosity, f.lobe) + point(c + u - v, a, f.radiosity, f.lobe) +
           point(c - u + v, a, f.radiosity, f.lobe) + point(c + u + v, a, f.radiosity, f.lobe);
  }
  // Sub-disks per edge of a near shooter texel: 4, or for a binned texel (a portal's) enough that their
  // spacing is at most a quarter of the receiver's distance from its plane, up to kNearBinSubdisks. Its bins
  // are read at each sub-disk's direction, and next to the plane a step along it is a large step in
  // direction (at 1.5 cm from it, sub-disks 2.5 cm apart are 40° apart): read that sparsely, the bins'
  // peaks were missed and the floor beside a door's plane came out 17 % dark, a seam along every portal
  // (bench/RESULTS.md, "The seam on a portal's plane").
  int nearSubdisks(const glm::vec3& c, const glm::vec4& lobe, const glm::vec3& tu,
                   const glm::vec3& tv) const {
    if (!emission || !(lobe.w < 0.0f)) return 4;
    const float edge = std::max(glm::length(tu), glm::length(tv));
    const float distance = std::max(std::abs(glm::dot(x - c, ns)), 1e-4f);
    return std::clamp(int(std::ceil(4.0f * edge / distance)), 4, kNearBinSubdisks);
  }
  glm::vec3 texel(const ShooterTexel& t, const glm::vec3& tu, const glm::vec3& tv, float radius) const {
    if (farFor(t.position, radius, t.lobe)) {  // 2×2 Gauss points
      const float g = 0.5f * 0.5773502692f, a = 0.25f * t.area;
      const glm::vec3 u = g * tu, v = g * tv;
      return point(t.position - u - v, a, t.radiosity, t.lobe) +
             point(t.position + u - v, a, t.radiosity, t.lobe) +
             point(t.position - u + v, a, t.radiosity, t.lobe) +
             point(t.position + u + v, a, t.radiosity, t.lobe);
    }
    // Near: k×k sub-disks, which keep F finite as r → 0 (k as nearSubdisks says).
    const int k = nearSubdisks(t.position, t.lobe, tu, tv);
    const float step = 1.0f / float(k), a = t.area / float(k * k);
    glm::vec3 sum(0.0f);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        sum +=
            disk(t.position + ((float(i) + 0.5f) * step - 0.5f) * tu + ((float(j) + 0.5f) * step - 0.5f) * tv,
                 a, t.radiosity, t.lobe);
    return sum;
  }
  // The region's light at the receiver through its quadtree, each piece handed to `use(point, light)`:
  // a node far from the receiver whole, a texel near it by itself (`point`: the piece's power mean, or the
  // texel's centre, which a caller may test for visibility).
  template <class Use>
  void walk(const RegionPieces& r, const Patch& p, float texelRadius, Use&& use) const {
    // Depth first: at most three nodes wait per level, and a chart's edge (≤ the atlas's 8 192 texels) gives
    // at most 14 levels.
    int32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const PieceNode& node = r.nodes[size_t(stack[--top])];
      if (node.texel >= 0) {
        const ShooterTexel& t = r.texels[size_t(node.texel)];
        use(t.position, texel(t, p.texelU, p.texelV, texelRadius));
        continue;
      }
      if (farPieceFor(node.piece)) {
        use(node.piece.mean, piece(node.piece));
        continue;
      }
      for (int32_t c : node.children)
        if (c >= 0) stack[top++] = c;
    }
  }
  glm::vec3 region(const RegionPieces& r, const Patch& p, float texelRadius) const {
    glm::vec3 sum(0.0f);
    walk(r, p, texelRadius, [&](const glm::vec3&, const glm::vec3& light) { sum += light; });
    return sum;
  }
};

// Texel t's footprint as a receiver: its parallelogram's edges (a quad's texel is whole; a loose triangle's
// valid texel is shrunk to its area).
void footprint(const LightmapAtlas& atlas, uint32_t t, glm::vec3& u, glm::vec3& v) {
  const Patch& p = atlas.patches[size_t(atlas.patch[t])];
  const float whole = glm::length(glm::cross(p.texelU, p.texelV));
  const float shrink = whole > 0.0f ? std::min(1.0f, std::sqrt(atlas.area[t] / whole)) : 0.0f;
  u = shrink * p.texelU, v = shrink * p.texelV;
}

// Share of region r's eye's hemisphere (cosine-weighted) covered by a receiver facing it, and open.
glm::dvec2 eyeCoverage(const RayShotScene& s, const ShooterLayout& l, const glm::vec3& eye, int rays,
                       uint32_t shotNumber) {
  const int side = std::max(1, int(std::lround(std::sqrt(double(rays)))));
  // A shot's strata shifted by a 2D golden-ratio step, so successive shots sample between each other's.
  const float du = float(std::fmod(0.7548776662 * shotNumber, 1.0)),
              dv = float(std::fmod(0.5698402910 * shotNumber, 1.0));
  double covered = 0.0, open = 0.0;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const float u1 = (float(i) + std::fmod(0.5f + du, 1.0f)) / float(side);
      const float u2 = (float(j) + std::fmod(0.5f + dv, 1.0f)) / float(side);
      const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
      const glm::vec3 d = r * std::cos(phi) * l.tangent + r * std::sin(phi) * l.bitangent +
                          std::sqrt(std::max(0.0f, 1.0f - u1)) * l.normal;
      const RayScene::Hit hit = s.rays.intersect(eye, d, 0.0f);
      if (!hit) {
        open += 1.0;
        continue;
      }
      const int32_t patch = s.trianglePatch[size_t(hit.triangle)];
      if (patch >= 0 && !s.patchTexels[size_t(patch)].empty() &&
          glm::dot(s.atlas.patches[size_t(patch)].normal, d) < 0.0f)
        covered += 1.0;
    }
  return glm::dvec2(covered, open) / double(side * side);
}

// The shot's coverage and open share (RayShotGain::covered, open): each region's eyes' by its power.
glm::dvec2 shotCoverage(const RayShotScene& s, const ShooterLayout& layout,
                        const std::vector<RegionPieces>& regions, int coverageRays, uint32_t shotNumber) {
  double shotPower = 0.0;
  for (const RegionPieces& r : regions) shotPower += r.power;
  std::vector<glm::dvec2> seen(regions.size());
  tbb::parallel_for(size_t(0), regions.size(), [&](size_t r) {
    for (const glm::vec3& eye : regions[r].eyes)  // a cluster's: its first region's, for all its power
      seen[r] += eyeCoverage(s, layout, eye, coverageRays / int(regions[r].eyes.size()), shotNumber) /
                 double(regions[r].eyes.size());
  });
  glm::dvec2 out(0.0);
  for (size_t r = 0; r < regions.size(); ++r) out += regions[r].eyePower / shotPower * seen[r];
  return out;
}

// Per eye of the shot (regions in order) and receiver tile, 1 when one surface hides the whole tile from
// the eye (occluder_cull.h). A tile that no eye segment could reach anyway (facing away from the eye, or
// behind the shooter), of a few texels, or the shooter's own is not tested: its ray would cost as much as
// it saves. A region's eyes are asked together, one surface for all of them at the rays of one eye: asked
// one by one, the interleaved sets' four times the eyes cost four times the tests, each leaving out a
// quarter of the segments (a tile's texels share the sets out).
std::vector<uint8_t> hiddenTiles(const RayShotScene& s, int shooter, std::span<const uint8_t> shooters,
                                 const std::vector<RegionPieces>& regions, size_t& tests) {
  size_t eyeCount = 0;
  for (const RegionPieces& r : regions) eyeCount += r.eyes.size();
  const size_t tiles = s.tiles.spheres.size();
  const glm::vec3 ns = s.atlas.patches[size_t(shooter)].normal;
  std::vector<uint8_t> hidden(eyeCount * tiles, 0);
  std::vector<uint32_t> tested(tiles, 0);
  tbb::parallel_for(size_t(0), tiles, [&](size_t tile) {
    const int32_t patch = s.tiles.patches[tile];
    if (s.tiles.counts[tile] < 4 || patch == shooter || (!shooters.empty() && shooters[size_t(patch)]))
      return;
    const glm::vec4 sphere = s.tiles.spheres[tile];
    const glm::vec3 centre(sphere);
    std::vector<glm::vec3> group;
    std::vector<size_t> index;
    size_t base = 0;
    for (const RegionPieces& r : regions) {
      group.clear(), index.clear();
      for (size_t e = 0; e < r.eyes.size(); ++e) {
        const glm::vec3 toEye = r.eyes[e] - centre;
        if (glm::dot(s.tiles.normals[tile], toEye) <= -sphere.w || glm::dot(ns, toEye) >= sphere.w) continue;
        group.push_back(r.eyes[e]), index.push_back(base + e);
      }
      base += r.eyes.size();
      if (group.empty()) continue;
      const uint8_t h = s.occluders.hidesFromEvery(s.rays, group, sphere, s.offset) ? 1 : 0;
      for (size_t e : index) hidden[e * tiles + tile] = h;
      ++tested[tile];
    }
  });
  for (uint32_t n : tested) tests += n;
  return hidden;
}

// A shot's segments of a chunk of receivers, each with the light it carries when nothing hides it.
struct Pending {
  uint32_t receiver;
  glm::vec3 light;
  glm::vec3 source;  // where on the shooter it left (for the arrival moments)
};
struct Queued {
  float offset = 0.0f;  // RayShotScene::offset
  std::vector<RayScene::Segment> segments;
  std::vector<Pending> light;
  std::vector<uint8_t> hidden;
  size_t saved = 0;
  void add(uint32_t k, const glm::vec3& from, const glm::vec3& to, const glm::vec3& light,
           const glm::vec3& source) {
    const glm::vec3 d = to - from;
    const float length = glm::length(d);
    if (length <= 2.0f * offset) return;
    segments.push_back({from, length - offset, d / length});
    this->light.push_back({k, light, source});
  }
};

// Where a receiver texel's segments end: its centre lifted off its surface, or an opening's texel
// (RayShotParams::openings) RayShotParams::openingPoints² points over it, each with its share of the light. A
// portal sits at its wall's mid-plane behind reveals, and the jamb nearer a shooter hides a strip along the
// portal's edge, from the edge itself; a texel's centre saw past strips under half the texel, and the
// light through plan 8's doors and windows was 5–13 % more than the reference's (bench/RESULTS.md, "The
// portals' error").
struct ReceiverEnds {
  glm::vec3 lifted{0.0f}, u{0.0f}, v{0.0f};
  uint32_t k = 0;
  int points = 1;  // per edge
  ReceiverEnds(const RayShotScene& s, uint32_t t, uint32_t index, const RayShotParams& params)
      : lifted(s.atlas.position[t] + s.atlas.normal[t] * s.offset), k(index) {
    if (params.openings.empty() || params.openings[size_t(s.atlas.patch[t])] == 0) return;
    footprint(s.atlas, t, u, v);
    points = std::max(params.openingPoints, 1);
  }
  // The segment between the receiver and `other`, the receiver's end first when `fromReceiver`.
  void queue(Queued& q, bool fromReceiver, const glm::vec3& other, const glm::vec3& light,
             const glm::vec3& source) const {
    const int m = points;
    const glm::vec3 part = light / float(m * m);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const glm::vec3 at =
            lifted + ((float(i) + 0.5f) / float(m) - 0.5f) * u + ((float(j) + 0.5f) / float(m) - 0.5f) * v;
        if (fromReceiver)
          q.add(k, at, other, part, source);
        else
          q.add(k, other, at, part, source);
      }
  }
};

// The shot's regions, every member's, with light (power > 0), each with its pieces and eyes; a cluster's
// regions see through one set of eyes (clusterEyes).
std::vector<RegionPieces> shotRegions(const RayShotScene& s, std::span<const ShotMember> members,
                                      std::span<const glm::vec3> residual, uint32_t shotNumber,
                                      const RayShotParams& params, const ShooterEmission& emission) {
  const int setsEdge = std::max(params.eyeSetsPerEdge, 1);
  std::vector<std::pair<size_t, size_t>> rects;  // (member, rect)
  for (size_t m = 0; m < members.size(); ++m)
    for (size_t r = 0; r < members[m].layout->rects.size(); ++r) rects.push_back({m, r});
  std::vector<RegionPieces> regions(rects.size());
  tbb::parallel_for(size_t(0), regions.size(), [&](size_t r) {
    const auto [m, rect] = rects[r];
    regions[r] =
        regionPieces(s, members[m].patch, members[m].layout->rects[rect], residual, uint32_t(r), shotNumber,
                     params.eyesPerRegion, setsEdge * setsEdge, params.oneEyeRadius, emission);
    regions[r].member = m;
  });
  std::erase_if(regions, [](const RegionPieces& r) { return !(r.power > 0.0); });
  if (members.size() > 1 && !regions.empty())
    clusterEyes(s, members, residual, shotNumber, params.eyesPerRegion, setsEdge * setsEdge,
                params.oneEyeRadius, regions);
  return regions;
}

// A point of the plane receivers behind which get nothing: the lowest of the regions' centres along the
// normal (a cluster's patches lie within ShooterClusterParams::planeGap of each other).
glm::vec3 lowestCentre(std::span<const RegionPieces> regions, const glm::vec3& normal) {
  glm::vec3 plane = regions.front().whole().centre;
  for (const RegionPieces& r : regions)
    if (glm::dot(normal, r.whole().centre - plane) < 0.0f) plane = r.whole().centre;
  return plane;
}

}  // namespace

RayShotScene::RayShotScene(const Scene& sc, const LightmapAtlas& a, const RayScene& r)
    : scene(sc),
      atlas(a),
      rays(r),
      trianglePatch(sc.triangles.size(), -1),
      patchTexels(a.patches.size()),
      occluders(sc, a) {
  for (size_t t = 0; t < a.texelCount(); ++t)
    if (a.patch[t] >= 0)
      texels.push_back(uint32_t(t)), patchTexels[size_t(a.patch[t])].push_back(uint32_t(t));
  for (size_t p = 0; p < a.patches.size(); ++p)
    for (int32_t t : a.patches[p].triangles)
      if (t >= 0 && size_t(t) < trianglePatch.size()) trianglePatch[size_t(t)] = int32_t(p);
  offset = 1e-4f * r.diagonal();
  tiles = receiverTiles(a, texels, offset);
}

RayShotGain shootByRays(const RayShotScene& s, int shooter, const ShooterLayout& layout,
                        std::span<const glm::vec3> residual, uint32_t shotNumber, const RayShotParams& params,
                        const ShooterEmission& emission) {
  const ShotMember alone{shooter, &layout};
  return shootByRays(s, std::span<const ShotMember>(&alone, 1), residual, shotNumber, params, emission);
}

RayShotGain shootByRays(const RayShotScene& s, std::span<const ShotMember> members,
                        std::span<const glm::vec3> residual, uint32_t shotNumber, const RayShotParams& params,
                        const ShooterEmission& emission) {
  const int shooter = members.front().patch;
  const Patch& p = s.atlas.patches[size_t(shooter)];
  const ShooterLayout& layout = *members.front().layout;
  const int setsEdge = std::max(params.eyeSetsPerEdge, 1);
  const std::vector<RegionPieces> regions = shotRegions(s, members, residual, shotNumber, params, emission);
  RayShotGain out;
  out.irradiance.assign(s.texels.size(), glm::vec3(0.0f));
  if (emission.arrivals) out.arrivals.assign(s.texels.size(), glm::vec4(0.0f));
  if (regions.empty()) return out;
  std::vector<uint8_t> shooters;  // per patch, 1 for the shot's (a cluster's)
  if (members.size() > 1) {
    shooters.assign(s.atlas.patches.size(), 0);
    for (const ShotMember& m : members) shooters[size_t(m.patch)] = 1;
  }
  const bool lobed = !emission.lobes.empty();
  const BinFrame frame = binFrame(p.normal);

  const glm::dvec2 seen = shotCoverage(s, layout, regions, params.coverageRays, shotNumber);
  out.covered = seen.x, out.open = seen.y;

  const glm::vec3 ns = p.normal;
  const glm::vec3 plane = lowestCentre(regions, ns);
  std::vector<size_t> eyeBase(regions.size(), 0);  // each region's first eye among all the shot's
  for (size_t r = 1; r < regions.size(); ++r) eyeBase[r] = eyeBase[r - 1] + regions[r - 1].eyes.size();
  const std::vector<uint8_t> hidden =
      params.cull ? hiddenTiles(s, shooter, shooters, regions, out.cullTests) : std::vector<uint8_t>{};
  std::atomic<size_t> saved{0};
  const size_t tileCount = s.tiles.spheres.size();
  // Region r's light at g's receiver when far from it; near it (nearer than farField × its radius), each
  // piece queued with its own segment and nothing returned. One eye for the region put a cube standing on
  // a floor in the dark wherever the eye was on its far side (its faces gathered 12–68 % of the floor's
  // light, bench/shot_probe.cpp), and the shot's scaling to its power spread what they missed over every
  // other receiver.
  const auto farLight = [&](Gather& g, const RegionPieces& r, const ReceiverEnds& ends, Queued& q) {
    // Facing away from the whole region (its bounding disk): nothing of it reaches the receiver.
    if (glm::dot(g.n, r.whole().centre - g.x) < -(r.whole().radius + s.offset)) return glm::vec3(0.0f);
    const Patch& rp = s.atlas.patches[size_t(members[r.member].patch)];
    const float texelRadius = members[r.member].layout->texelRadius;
    g.nodeBins = r.nodeBins;
    if (params.nearRays && !g.far(r.whole().centre, r.whole().radius)) {
      g.walk(r, rp, texelRadius, [&](const glm::vec3& y, const glm::vec3& light) {
        if (light != glm::vec3(0.0f)) ends.queue(q, true, y + ns * s.offset, light, y);
      });
      return glm::vec3(0.0f);
    }
    return g.farPieceFor(r.whole()) ? g.piece(r.whole()) : g.region(r, rp, texelRadius);
  };
  // Per chunk of receivers, every piece's light waits on its segment; the segments are traced together.
  // The chunks are fixed (a simple partitioner splits the same way every run): Embree packs a stream's
  // rays into packets, whose answers for a ray grazing an edge may differ from a single ray's, and chunks
  // that followed the threads' stealing made the bake differ in the 8th digit from run to run.
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, s.texels.size(), 64),
      [&](const tbb::blocked_range<size_t>& range) {
        Queued q;  // per chunk, not per thread: nothing here may share it with another chunk
        q.offset = s.offset;
        for (size_t k = range.begin(); k < range.end(); ++k) {
          const uint32_t t = s.texels[k];
          const int32_t at = s.atlas.patch[t];
          if (at == shooter || (!shooters.empty() && shooters[size_t(at)])) continue;
          const glm::vec3 x = s.atlas.position[t], n = s.atlas.normal[t];
          // Behind the shooter's plane every piece's cosine is ≤ 0: the receiver gets nothing, its form
          // factors spared (the margin keeps receivers on the plane on the whole path).
          if (glm::dot(ns, x - plane) < -s.offset) continue;
          Gather g{x, n, ns, params.farField};
          const ReceiverEnds ends(s, t, uint32_t(k), params);
          // The receiver's eye set: its place in a setsEdge × setsEdge tile of the atlas.
          const size_t place = (t % s.atlas.width) % size_t(setsEdge) +
                               size_t(setsEdge) * ((t / s.atlas.width) % size_t(setsEdge));
          if (lobed) g.emission = &emission, g.frame = frame, g.receiverArea = s.atlas.area[t];
          // A region's light from afar, summed over its group (a cluster's regions), goes through the
          // group's eyes; near it, each piece is gated by its own segment.
          const RegionPieces* lead = nullptr;
          glm::vec3 f(0.0f);
          for (const RegionPieces& r : regions) {
            if (!lead) lead = &r, f = glm::vec3(0.0f);
            f += farLight(g, r, ends, q);
            if (!r.groupEnd) continue;
            const RegionPieces& eyes = *lead;
            lead = nullptr;
            if (f == glm::vec3(0.0f)) continue;
            const size_t set = place % size_t(eyes.sets), stride = size_t(eyes.sets);
            const glm::vec3 share = f / float(eyes.eyesPerSet());
            const uint8_t* eyeHides =
                hidden.empty() ? nullptr : &hidden[eyeBase[&eyes - regions.data()] * tileCount];
            for (size_t e = set; e < eyes.eyes.size(); e += stride) {
              const glm::vec3& eye = eyes.eyes[e];
              const glm::vec3 toEye = eye - x;
              if (!(glm::dot(n, toEye) > 0.0f && glm::dot(ns, toEye) < 0.0f)) continue;
              if (eyeHides && eyeHides[e * tileCount + s.tiles.tileOf[k]])
                ++q.saved;
              else
                ends.queue(q, false, eye, share, eye);
            }
          }
        }
        q.hidden.resize(q.segments.size());
        s.rays.occluded(q.segments, q.hidden);
        for (size_t i = 0; i < q.light.size(); ++i) {
          if (q.hidden[i]) continue;
          const Pending& got = q.light[i];
          out.irradiance[got.receiver] += got.light;
          if (emission.arrivals) {  // shaders/directional.glsl, noteArrival: travelling from the source
            const uint32_t t = s.texels[got.receiver];
            const glm::vec3 omega = glm::normalize(s.atlas.position[t] - got.source);
            out.arrivals[got.receiver] += arrivalMoment(omega, -s.atlas.normal[t], channelSum(got.light));
          }
        }
        saved += q.saved;
      },
      tbb::simple_partitioner());
  out.cullSaved = saved;
  // Summed in texel order, so that a shot's scaling, and the bake, do not depend on the threads' split.
  for (size_t k = 0; k < s.texels.size(); ++k)
    out.gathered += double(channelSum(out.irradiance[k])) * s.atlas.area[s.texels[k]];
  return out;
}

}  // namespace cpgi
