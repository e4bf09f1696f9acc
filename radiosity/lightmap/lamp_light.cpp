#include "radiosity/lightmap/lamp_light.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "radiosity/lightmap/occluder_pieces.h"

namespace cpgi {

namespace {

/// A lamp as the solver sees it: one planar polygon (a chart's parallelogram or a loose triangle) of
/// uniform exitance, emitting on the side of `normal`.
struct Lamp {
  std::array<glm::vec3, 4> corner{};
  int corners = 4;
  glm::vec3 normal{0.0f};
  glm::vec3 exitance{0.0f};  ///< W/m²: the patch's power over its area
  double power = 0.0;        ///< W, R + G + B
  int patch = -1;
  glm::vec3 centre{0.0f};
  float radius = 0.0f;  ///< of the sphere about `centre` that holds the polygon
  float area = 0.0f;    ///< m²

  /// A point of the polygon, uniform in area, for (a, b) uniform in [0, 1)².
  glm::vec3 at(float a, float b) const {
    if (corners == 4) return corner[0] + a * (corner[1] - corner[0]) + b * (corner[3] - corner[0]);
    const float s = std::sqrt(a);
    return (1.0f - s) * corner[0] + s * (1.0f - b) * corner[1] + s * b * corner[2];
  }
};

/// F(dA → lamp) at x (normal n), unoccluded: Lambert's contour over the polygon clipped to x's front. In
/// double from the corners on: a lamp a nanometre wide (a hostile file's 5e-19 m² speck) lost its edges in
/// float differences of metre-long vectors and gave nothing, though it emits 1e20 W.
float contourFormFactor(const Lamp& lamp, const glm::vec3& x, const glm::vec3& n) {
  glm::dvec3 clipped[5];
  int m = 0;
  const glm::dvec3 at(x), normal(n);
  for (int i = 0; i < lamp.corners; ++i) {
    const glm::dvec3 a = glm::dvec3(lamp.corner[i]) - at,
                     b = glm::dvec3(lamp.corner[(i + 1) % lamp.corners]) - at;
    const double da = glm::dot(normal, a), db = glm::dot(normal, b);
    if (da >= 0.0) clipped[m++] = a;
    if ((da >= 0.0) != (db >= 0.0)) clipped[m++] = a + (da / (da - db)) * (b - a);
  }
  if (m < 3) return 0.0f;
  double sum = 0.0;
  for (int i = 0; i < m; ++i) {
    const glm::dvec3 c = glm::cross(clipped[i], clipped[(i + 1) % m]);
    const double length = glm::length(c);
    if (length > 0.0)
      sum += std::atan2(length, glm::dot(clipped[i], clipped[(i + 1) % m])) * glm::dot(normal, c) / length;
  }
  return float(std::abs(sum) / (2.0 * std::numbers::pi));
}

uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Uniforms for one texel and lamp, from their indices alone.
class TexelRandom {
 public:
  TexelRandom(size_t texel, size_t lamp) : state_(mix(uint64_t(texel) * 0x100000001B3ull ^ mix(lamp))) {}
  float next() {
    state_ = mix(state_);
    return float(state_ >> 40) * 0x1p-24f;
  }

 private:
  uint64_t state_;
};

float fraction(float x) {
  return x - std::floor(x);
}

/// What one texel sees of one lamp: the footprint's mean of F × seen share, and whether rays disagreed.
enum class Seen : uint8_t { None, Hidden, Whole, Part };  ///< no ray in front; none, all or some got through

struct TexelLamp {
  float formFactor = 0.0f;
  Seen seen = Seen::None;
};

/// How far off its surface a shadow ray starts: the reference's, so both see thin walls.
float rayOffset(const RayScene& occluders) {
  return std::max(1e-5f * occluders.diagonal(), 1e-6f);
}

/// A shadow ray stops this share of its length (and the ray offset) short of the lamp, which must not hide
/// itself.
constexpr float kShortOfLamp = 1e-4f;

/// The texels a lamp cannot reach past one occluder piece (occluder_pieces.h), whose rays to it need no
/// tracing. The pieces tried on a texel: those the rays from its chart's centre and four inner points to
/// the lamp's centre meet first, from either end (one of them hides the whole chart from a lamp two rooms
/// away), then those its own centre's two rays meet (a texel beside a door). Deterministic: a texel's
/// answer is its own, whatever the threads.
class LampShadows {
 public:
  LampShadows(const Lamp& lamp, const OccluderPieces& pieces, const RayScene& occluders,
              const LightmapAtlas& atlas, float offset)
      : lamp_(lamp), pieces_(pieces), occluders_(occluders), atlas_(atlas), offset_(offset) {
    for (int c = 0; c < lamp.corners; ++c) lampCorners_.push_back(glm::dvec3(lamp.corner[size_t(c)]));
    // No ray is longer than the scene's diagonal (and its two offsets).
    shortfall_ =
        double(kShortOfLamp) * (double(occluders.diagonal()) + 2.0 * double(offset)) + double(offset);
    candidates_.resize(atlas.patches.size());
    whole_.assign(atlas.patches.size(), 0);
    clear_.assign(atlas.patches.size(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, atlas.patches.size(), 16),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t p = range.begin(); p < range.end(); ++p) findCandidates(p);
                      });
  }

  /// True when texel t (of a chart) is known hidden from the whole lamp.
  bool hidden(size_t t) const {
    const size_t p = size_t(atlas_.patch[t]);
    if (whole_[p]) return true;
    const Patch& P = atlas_.patches[p];
    const std::array<glm::dvec3, 4> footprint =
        parallelogram(atlas_.position[t] - 0.5f * (P.texelU + P.texelV), P.texelU, P.texelV, P.normal);
    for (int32_t piece : candidates_[p])
      if (pieces_.blocks(piece, footprint, lampCorners_, shortfall_)) return true;
    if (clear_[p]) return false;  // the chart sees the lamp: its texels' own rays would find no piece
    for (int32_t piece : firstPieces(atlas_.position[t], P.normal).piece)
      if (pieces_.blocks(piece, footprint, lampCorners_, shortfall_)) return true;
    return false;
  }

 private:
  // The corners of origin + [0, 1]·u + [0, 1]·v, moved off the surface as the rays' origins are.
  std::array<glm::dvec3, 4> parallelogram(const glm::vec3& origin, const glm::vec3& u, const glm::vec3& v,
                                          const glm::vec3& n) const {
    const glm::dvec3 o = glm::dvec3(origin) + double(offset_) * glm::dvec3(n);
    return {o, o + glm::dvec3(u), o + glm::dvec3(u + v), o + glm::dvec3(v)};
  }

  // The pieces met first on the segment between x (off a surface of normal n) and the lamp's centre, from
  // each end (-1 where none), and whether nothing lies on it.
  struct FirstPieces {
    std::array<int32_t, 2> piece{-1, -1};
    bool clear = false;
  };
  FirstPieces firstPieces(const glm::vec3& x, const glm::vec3& n) const {
    const glm::vec3 from = x + offset_ * n, to = lamp_.centre + offset_ * lamp_.normal, d = to - from;
    const float length = glm::length(d);
    if (!(length > 2.0f * offset_)) return {};
    const glm::vec3 w = d / length;
    const float far = length * (1.0f - kShortOfLamp);
    const RayScene::Hit a = occluders_.intersect(from, w, 0.0f, far);
    if (!a) return {{-1, -1}, true};
    const RayScene::Hit b = occluders_.intersect(to, -w, 0.0f, far);
    return {{pieces_.pieceOf(a.triangle), b ? pieces_.pieceOf(b.triangle) : -1}, false};
  }

  void findCandidates(size_t p) {
    if (int(p) == lamp_.patch) return;
    const Patch& P = atlas_.patches[p];
    const glm::vec3 u = float(P.w) * P.texelU, v = float(P.h) * P.texelV;
    const std::array<glm::dvec3, 4> chart = parallelogram(P.origin, u, v, P.normal);
    // A chart wholly behind the lamp's plane, or with the lamp wholly behind its own, gets no ray.
    bool front = false, faces = false;
    for (const glm::dvec3& c : chart)
      front = front || glm::dot(glm::dvec3(lamp_.normal), c - lampCorners_[0]) > 0.0;
    for (const glm::dvec3& c : lampCorners_)
      faces = faces || glm::dot(glm::dvec3(P.normal), c - chart[0]) > 0.0;
    if (!front || !faces) return;
    std::vector<int32_t>& found = candidates_[p];
    bool clear = true;
    for (const glm::vec2 at : {glm::vec2(0.5f), glm::vec2(0.25f), glm::vec2(0.75f, 0.25f),
                               glm::vec2(0.25f, 0.75f), glm::vec2(0.75f)}) {
      const FirstPieces first = firstPieces(P.origin + at.x * u + at.y * v, P.normal);
      clear = clear && first.clear;
      for (int32_t piece : first.piece)
        if (piece >= 0 && std::find(found.begin(), found.end(), piece) == found.end()) found.push_back(piece);
    }
    clear_[p] = clear;
    for (int32_t piece : found)
      if (pieces_.blocks(piece, chart, lampCorners_, shortfall_)) {
        whole_[p] = 1;
        return;
      }
  }

  const Lamp& lamp_;
  const OccluderPieces& pieces_;
  const RayScene& occluders_;
  const LightmapAtlas& atlas_;
  float offset_ = 0.0f;
  double shortfall_ = 0.0;
  std::vector<glm::dvec3> lampCorners_;
  std::vector<std::vector<int32_t>> candidates_;  ///< per patch
  std::vector<char> whole_;                       ///< per patch: the whole chart hidden
  std::vector<char> clear_;                       ///< per patch: the lamp's centre seen from its five points
};

/// How a texel's footprint and a lamp face each other: every point of each in front of the other (each of
/// the texel's points then has a contour form factor and each of its rays a kernel), one wholly behind the
/// other (none has), or it depends on the point. Each by `margin` off the other's plane, far above the
/// rounding of the rays' directions.
enum class Facing : uint8_t { Away, Wholly, Partly };

Facing facingOf(const Lamp& lamp, const glm::vec3& centre, const glm::vec3& n, const glm::vec3& u,
                const glm::vec3& v, float offset, double margin) {
  double lampLow = 1e300, lampHigh = -1e300, texelLow = 1e300, texelHigh = -1e300;
  for (int c = 0; c < lamp.corners; ++c) {
    const double d = glm::dot(glm::dvec3(n), glm::dvec3(lamp.corner[size_t(c)]) - glm::dvec3(centre));
    lampLow = std::min(lampLow, d), lampHigh = std::max(lampHigh, d);
  }
  const glm::dvec3 origin = glm::dvec3(centre) + double(offset) * glm::dvec3(n), du(u), dv(v);
  for (const glm::dvec3 x : {origin - 0.5 * (du + dv), origin + 0.5 * (du - dv), origin + 0.5 * (du + dv),
                             origin - 0.5 * (du - dv)}) {
    const double d = glm::dot(glm::dvec3(lamp.normal), x - glm::dvec3(lamp.corner[0]));
    texelLow = std::min(texelLow, d), texelHigh = std::max(texelHigh, d);
  }
  if (lampHigh < -margin || texelHigh < -margin) return Facing::Away;
  if (lampLow > margin && texelLow > margin && lamp.area > 0.0f) return Facing::Wholly;
  return Facing::Partly;
}

/// Whether one texel's rays to one lamp need tracing: decided at its first ray (most texels facing away
/// never get one) and kept for its penumbra pass. A texel LampShadows finds wholly hidden gets every ray
/// hidden without tracing it: what tracing would give, exactly.
class TexelSight {
 public:
  TexelSight(const LampShadows* shadows, size_t texel, int8_t& state)
      : shadows_(shadows), texel_(texel), state_(state) {}
  bool hidden() {
    if (state_ < 0) state_ = shadows_ && shadows_->hidden(texel_) ? 1 : 0;
    return state_ == 1;
  }

 private:
  const LampShadows* shadows_;
  size_t texel_;
  int8_t& state_;  ///< -1 undecided, 0 traced, 1 hidden
};

/// From `origin` (off a receiver of normal n) to the lamp's point y: the point-to-point kernel cosθ cosθ' /
/// r², 0 where either side faces away, and whether a shadow ray (traced only when the kernel is not 0 and
/// `sight` does not know the texel hidden) finds y.
struct RayToLamp {
  double kernel = 0.0;
  bool seen = false;
};

RayToLamp rayToLamp(const Lamp& lamp, const RayScene& occluders, float offset, const glm::vec3& origin,
                    const glm::vec3& n, const glm::vec3& y, TexelSight& sight, uint64_t& rays) {
  const glm::vec3 d = y - origin;
  const float r2 = glm::dot(d, d);
  if (!(r2 > 0.0f)) return {};
  const float r = std::sqrt(r2);
  const glm::vec3 w = d / r;
  const float cosX = glm::dot(n, w), cosY = -glm::dot(lamp.normal, w);
  if (cosX <= 0.0f || cosY <= 0.0f) return {};
  const double kernel = double(cosX) * cosY / r2;
  if (sight.hidden()) return {kernel, false};
  ++rays;
  const float far = r * (1.0f - kShortOfLamp) - offset;
  return {kernel, !(far > 0.0f && occluders.occluded(origin, w, 0.0f, far))};
}

/// `side` × `side` points over the texel, `perPoint` rays to the lamp from each. The points sit at their
/// squares' centres, where F's mean is a smooth function's (random points there added 0.2–0.3 points of
/// per-texel error on the walls next to seed1's lamps), or with `jitter` anywhere in them: in a penumbra,
/// where what the points see changes across the texel.
TexelLamp seeLamp(const Lamp& lamp, const RayScene& occluders, float offset, const glm::vec3& centre,
                  const glm::vec3& n, const glm::vec3& u, const glm::vec3& v, int side, int perPoint,
                  bool jitter, TexelRandom& random, TexelSight& sight, uint64_t& rays) {
  TexelLamp out;
  int seen = 0, tried = 0;
  const float share = 1.0f / float(side * side), step = 1.0f / float(side);
  for (int m = 0; m < side * side; ++m) {
    const float ju = jitter ? random.next() : 0.5f, jv = jitter ? random.next() : 0.5f;
    const float su = (float(m % side) + ju) * step - 0.5f, sv = (float(m / side) + jv) * step - 0.5f;
    const glm::vec3 x = centre + su * u + sv * v;
    const float f = contourFormFactor(lamp, x, n);
    if (!(f > 0.0f)) continue;
    const glm::vec3 origin = x + offset * n;
    // Roberts' R2 points, shifted at random: well spread over the lamp for any count.
    const float shiftA = random.next(), shiftB = random.next();
    double weighted = 0.0, visible = 0.0;
    for (int k = 0; k < perPoint; ++k) {
      const glm::vec3 y =
          lamp.at(fraction(shiftA + float(k) * 0.7548776662f), fraction(shiftB + float(k) * 0.5698402910f));
      const RayToLamp ray = rayToLamp(lamp, occluders, offset, origin, n, y, sight, rays);
      if (!(ray.kernel > 0.0)) continue;
      weighted += ray.kernel;
      ++tried;
      if (!ray.seen) continue;
      visible += ray.kernel;
      ++seen;
    }
    if (weighted > 0.0) out.formFactor += share * f * float(visible / weighted);
  }
  out.seen = tried == 0 ? Seen::None : seen == 0 ? Seen::Hidden : seen == tried ? Seen::Whole : Seen::Part;
  return out;
}

/// A penumbra texel's mean F × seen share by area sampling, every ray from its own point of the texel to its
/// own point of the lamp on a 4-D low-discrepancy set (Roberts' R4, shifted at random): mean of A V k / π.
/// Where a few lamp points per texel point gave each point's share in steps of a quarter (±12 % per texel
/// at 256 rays, spot-door's beam edge), the joint set spreads over both at once.
float penumbraFormFactor(const Lamp& lamp, const RayScene& occluders, float offset, const glm::vec3& centre,
                         const glm::vec3& n, const glm::vec3& u, const glm::vec3& v, int count,
                         float lampArea, TexelRandom& random, TexelSight& sight, uint64_t& rays) {
  constexpr float a1 = 0.8566748839f, a2 = 0.7338918566f, a3 = 0.6287067210f,
                  a4 = 0.5385972498f;  // 1/g^i, g⁵ = g + 1
  const float s1 = random.next(), s2 = random.next(), s3 = random.next(), s4 = random.next();
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const glm::vec3 x =
        centre + (fraction(s1 + float(k) * a1) - 0.5f) * u + (fraction(s2 + float(k) * a2) - 0.5f) * v;
    const glm::vec3 y = lamp.at(fraction(s3 + float(k) * a3), fraction(s4 + float(k) * a4));
    const RayToLamp ray = rayToLamp(lamp, occluders, offset, x + offset * n, n, y, sight, rays);
    if (ray.seen) sum += ray.kernel;
  }
  return float(sum * lampArea / (std::numbers::pi * double(count)));
}

std::vector<Lamp> lampsOf(const Scene& scene, const LightmapAtlas& atlas, const std::vector<char>& shoot) {
  std::vector<Lamp> lamps;
  std::vector<glm::dvec3> power(atlas.patches.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    const int p = atlas.patch[t];
    if (p >= 0 && shoot[size_t(p)]) power[size_t(p)] += glm::dvec3(atlas.emission[t]) * double(atlas.area[t]);
  }
  for (size_t p = 0; p < atlas.patches.size(); ++p) {
    if (!shoot[p]) continue;
    const Patch& P = atlas.patches[p];
    Lamp lamp;
    lamp.patch = int(p);
    lamp.normal = P.normal;
    if (P.quad >= 0) {
      const glm::vec3 a = float(P.w) * P.texelU, b = float(P.h) * P.texelV;
      lamp.corner = {P.origin, P.origin + a, P.origin + a + b, P.origin + b};
    } else {
      const Triangle& tri = scene.triangles[size_t(P.triangles.at(0))];
      lamp.corner = {tri.p[0], tri.p[1], tri.p[2], tri.p[2]};
      lamp.corners = 3;
    }
    for (int c = 0; c < lamp.corners; ++c) lamp.centre += lamp.corner[c] / float(lamp.corners);
    for (int c = 0; c < lamp.corners; ++c)
      lamp.radius = std::max(lamp.radius, glm::length(lamp.corner[c] - lamp.centre));
    lamp.power = power[p].r + power[p].g + power[p].b;
    if (!(P.area > 0.0f) || !(lamp.power > 0.0)) continue;
    lamp.exitance = glm::vec3(power[p] / double(P.area));
    lamp.area = P.area;
    lamps.push_back(lamp);
  }
  return lamps;
}

constexpr float kNearTexels = 3.0f;

/// One lamp's light on the atlas: per texel its footprint's mean F × seen share, and whether the texel is
/// near the lamp.
struct OneLamp {
  std::vector<float> formFactor;
  std::vector<char> near;
  uint64_t rays = 0;
  uint64_t hidden = 0;        ///< texels facing the lamp whose rays were not traced, known hidden
  uint64_t tracedHidden = 0;  ///< texels whose traced rays were all hidden
};

OneLamp shootOne(const Lamp& lamp, size_t k, const RayScene& occluders, const OccluderPieces* pieces,
                 const LightmapAtlas& atlas, int rays) {
  const float offset = rayOffset(occluders);
  const int perPoint = rays / 4;
  const size_t n = atlas.texelCount();
  OneLamp out;
  out.formFactor.assign(n, 0.0f);
  out.near.assign(n, 0);
  std::vector<Seen> seen(n, Seen::None);
  std::vector<int8_t> sight(n, -1);
  std::optional<LampShadows> shadows;
  if (pieces) shadows.emplace(lamp, *pieces, occluders, atlas, offset);
  std::atomic<uint64_t> traced{0};
  // Within a few texels of the lamp F is steep over the texel (a housing's walls where they meet the
  // lamp): 2×2 points made spot-door's tube gather 3.4 % more than its lamp emits, and the scale back
  // darkened both rooms alike. There 8×8 points, with fewer rays each.
  auto layout = [&](size_t i, int& side, int& perSide) {
    const Patch& P = atlas.patches[size_t(atlas.patch[i])];
    const float texelSize = std::max(glm::length(P.texelU), glm::length(P.texelV));
    const bool near = glm::length(atlas.position[i] - lamp.centre) - lamp.radius < kNearTexels * texelSize;
    out.near[i] = near;
    side = near ? 8 : 2;
    perSide = near ? std::max(1, perPoint / 16) : perPoint;
  };
  auto trace = [&](size_t i, int side, int perSide, bool jitter, TexelRandom& random, uint64_t& count) {
    const Patch& P = atlas.patches[size_t(atlas.patch[i])];
    TexelSight ownSight(shadows ? &*shadows : nullptr, i, sight[i]);
    return seeLamp(lamp, occluders, offset, atlas.position[i], atlas.normal[i], P.texelU, P.texelV, side,
                   perSide, jitter, random, ownSight, count);
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& range) {
    uint64_t count = 0;
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (atlas.patch[i] < 0 || atlas.patch[i] == lamp.patch) continue;
      int side = 2, perSide = 1;
      layout(i, side, perSide);
      if (shadows) {  // what the points and rays below would find, known without them
        const Patch& P = atlas.patches[size_t(atlas.patch[i])];
        const Facing facing =
            facingOf(lamp, atlas.position[i], atlas.normal[i], P.texelU, P.texelV, offset, pieces->margin());
        if (facing == Facing::Away) continue;  // no point with a contour, no ray with a kernel: None
        if (facing == Facing::Wholly && TexelSight(&*shadows, i, sight[i]).hidden()) {
          seen[i] = Seen::Hidden;
          continue;
        }
      }
      TexelRandom random(i, 2 * k);
      const TexelLamp t = trace(i, side, perSide, false, random, count);
      out.formFactor[i] = t.formFactor;
      seen[i] = t.seen;
    }
    traced += count;
  });
  // Penumbrae: texels whose rays disagreed, and those beside one that saw the lamp otherwise (a sliver of
  // the lamp that the first rays all missed: spot-door's beam edge, 14 % dark at 16 rays), again from all
  // over the texel, since what a point sees changes across it there (2×2 points left the mean 20 % off
  // whatever the rays): near the lamp 8×8 points with 4× the rays, elsewhere 16× the rays on the joint
  // set (spot-door's lit room 7.4 % per texel at 4×, 3.7 % at 16×, for 1.13× the lamps' time with the
  // office's 36 lamps).
  const int width = atlas.width, height = atlas.height;
  auto penumbra = [&](size_t i) {
    if (seen[i] == Seen::Part) return true;
    if (seen[i] == Seen::None) return false;
    const int x = int(i % size_t(width)), y = int(i / size_t(width));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        const size_t j = size_t(ny) * size_t(width) + size_t(nx);
        if (atlas.patch[j] == atlas.patch[i] && seen[j] != Seen::None && seen[j] != seen[i]) return true;
      }
    return false;
  };
  std::vector<float> again(n, -1.0f);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& range) {
    uint64_t count = 0;
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (atlas.patch[i] < 0 || atlas.patch[i] == lamp.patch || !penumbra(i)) continue;
      if (sight[i] == 1) {  // every ray hidden: nothing seen, as the rays would find
        again[i] = 0.0f;
        continue;
      }
      int side = 2, perSide = 1;
      layout(i, side, perSide);
      TexelRandom random(i, 2 * k + 1);
      if (out.near[i]) {  // F steep over the texel: its contour at each of 8×8 points
        again[i] = trace(i, 8, std::max(1, 4 * perSide * side * side / 64), true, random, count).formFactor;
      } else {
        const Patch& P = atlas.patches[size_t(atlas.patch[i])];
        TexelSight ownSight(shadows ? &*shadows : nullptr, i, sight[i]);
        again[i] = penumbraFormFactor(lamp, occluders, offset, atlas.position[i], atlas.normal[i], P.texelU,
                                      P.texelV, 16 * rays, lamp.area, random, ownSight, count);
      }
    }
    traced += count;
  });
  for (size_t i = 0; i < n; ++i) {
    if (again[i] >= 0.0f) out.formFactor[i] = again[i];
    out.hidden += sight[i] == 1 && seen[i] == Seen::Hidden;
    out.tracedHidden += sight[i] != 1 && seen[i] == Seen::Hidden;
  }
  out.rays = traced.load();
  return out;
}

}  // namespace

std::vector<char> lampPatches(const Scene& scene, const LightmapAtlas& atlas) {
  std::vector<char> lamps(atlas.patches.size(), 0);
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    const int p = atlas.patch[t];
    if (p < 0 || atlas.emission[t] == glm::vec3(0.0f)) continue;
    const uint32_t material = atlas.patches[size_t(p)].material;
    if (material < scene.materials.size() && scene.materials[material].emission != glm::vec3(0.0f))
      lamps[size_t(p)] = 1;
  }
  return lamps;
}

LampLight shootLampsByRays(const Scene& scene, const RayScene& occluders, const LightmapAtlas& atlas,
                           const std::vector<char>& shoot, int rays, Context& ctx,
                           std::chrono::steady_clock::time_point deadline, LampCull cull) {
  if (rays < 4 || rays % 4 != 0)
    throw std::invalid_argument("shootLampsByRays: rays must be a multiple of 4");
  if (shoot.size() != atlas.patches.size())
    throw std::invalid_argument("shootLampsByRays: one flag per patch");
  auto timer = ctx.time("lamps by rays");
  LampLight out;
  out.irradiance.assign(atlas.texelCount(), glm::vec3(0.0f));
  out.shot.assign(atlas.patches.size(), 0);
  const std::vector<Lamp> lamps = lampsOf(scene, atlas, shoot);
  if (lamps.empty()) return out;
  // The scene's occluder pieces, and the margin every test of the cull keeps: 10× the rays' offset, and
  // far above the rounding of float coordinates where a scene lies far from its origin.
  std::optional<OccluderPieces> pieces;
  if (cull == LampCull::Occluders) {
    const Bounds box = scene.bounds();
    const glm::vec3 farthest = box.empty() ? glm::vec3(0.0f) : glm::max(glm::abs(box.lo), glm::abs(box.hi));
    const double extent = std::max({farthest.x, farthest.y, farthest.z});
    pieces.emplace(scene, std::max(10.0 * double(rayOffset(occluders)), 1e-5 * extent));
  }
  // Points on a texel sample F where it is steep next to a lamp (a housing's walls): those texels can
  // gather more than the lamp emits (spot-door's tube +1 % at 8×8 points). The far texels' estimate is
  // exact in expectation, so the excess comes off the near texels' share, and off all only when the far
  // ones alone pass the power: no light is made up. Lamp by lamp, in texel order: the same sums, and so
  // the same result, whatever the threads.
  for (size_t k = 0; k < lamps.size(); ++k) {
    if (std::chrono::steady_clock::now() >= deadline) break;
    const Lamp& lamp = lamps[k];
    out.shot[size_t(lamp.patch)] = 1;
    out.emitted += lamp.power;
    ctx.progress("lamps", double(k) / double(lamps.size()),
                 "lamp " + std::to_string(k + 1) + " of " + std::to_string(lamps.size()) + " by rays");
    const OneLamp one = shootOne(lamp, k, occluders, pieces ? &*pieces : nullptr, atlas, rays);
    out.rays += one.rays;
    out.hiddenTexels += one.hidden;
    out.tracedHiddenTexels += one.tracedHidden;
    const double perFormFactor = double(lamp.exitance.r) + lamp.exitance.g + lamp.exitance.b;
    double all = 0.0, near = 0.0;
    for (size_t i = 0; i < one.formFactor.size(); ++i) {
      const double power = perFormFactor * one.formFactor[i] * atlas.area[i];
      all += power;
      if (one.near[i]) near += power;
    }
    float nearScale = 1.0f, farScale = 1.0f;
    if (all > lamp.power) {
      if (all - near < lamp.power && near > 0.0)
        nearScale = float((lamp.power - (all - near)) / near);
      else
        nearScale = farScale = float(lamp.power / all);
    }
    for (size_t i = 0; i < one.formFactor.size(); ++i) {
      if (!(one.formFactor[i] > 0.0f)) continue;
      const glm::vec3 got = lamp.exitance * (one.formFactor[i] * (one.near[i] ? nearScale : farScale));
      out.irradiance[i] += got;
      out.landed += (double(got.r) + got.g + got.b) * atlas.area[i];
    }
  }
  return out;
}

}  // namespace cpgi
