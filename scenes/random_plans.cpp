#include "scenes/random_plans.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <random>
#include <stdexcept>
#include <utility>

#include "scenes/scene_builder.h"

namespace cpgi {
namespace {

constexpr float kMinSide = 2.2f;         // the narrowest room, metres
constexpr float kMinShared = 0.8f;       // the shortest stretch of shared wall that takes an opening
constexpr float kMaxWall = 0.3f;         // the thickest interior wall
constexpr float kLampEmission = 100.0f;  // W/m², as the seed scenes
constexpr int kMaxAttempts = 64;

// Uniform draws from the engine's raw output: std::uniform_real_distribution's algorithm is left to each
// library, and a plan must be the same for a seed everywhere.
class Draw {
 public:
  explicit Draw(uint64_t seed) : engine_(seed) {}
  double unit() { return double(engine_() >> 11) * 0x1.0p-53; }
  float uniform(float lo, float hi) { return lo + float(unit()) * (hi - lo); }
  int integer(int lo, int hi) { return lo + int(unit() * double(hi - lo + 1)); }  ///< in [lo, hi]
  bool chance(double p) { return unit() < p; }

 private:
  std::mt19937_64 engine_;
};

float roundTo(float v, float step) {
  return std::round(v / step) * step;
}

struct Rect {
  float x0, z0, x1, z1;
  float side(int axis) const { return axis == 0 ? x1 - x0 : z1 - z0; }
  float area() const { return (x1 - x0) * (z1 - z0); }
};

// Recursive splits of the footprint: the largest room that can be split is cut across its longer side
// (the shorter when the longer cannot take it) by a wall of random thickness, until `count` rooms.
bool splitFootprint(Draw& draw, glm::vec2 footprint, int count, std::vector<Rect>& rooms) {
  rooms = {{0.0f, 0.0f, footprint.x, footprint.y}};
  while (int(rooms.size()) < count) {
    std::vector<size_t> order(rooms.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return rooms[a].area() > rooms[b].area(); });
    const float wall = draw.chance(0.25) ? 0.0f : roundTo(draw.uniform(0.1f, kMaxWall), 0.01f);
    bool split = false;
    for (size_t i : order) {
      const Rect r = rooms[i];
      const int longer = r.side(0) >= r.side(2) ? 0 : 2;
      for (int axis : {longer, 2 - longer}) {
        const float lo = (axis == 0 ? r.x0 : r.z0) + kMinSide + 0.5f * wall;
        const float hi = (axis == 0 ? r.x1 : r.z1) - kMinSide - 0.5f * wall;
        if (hi < lo) continue;
        const float at = std::clamp(roundTo(lo + draw.uniform(0.15f, 0.85f) * (hi - lo), 0.05f), lo, hi);
        Rect a = r, b = r;
        if (axis == 0)
          a.x1 = at - 0.5f * wall, b.x0 = at + 0.5f * wall;
        else
          a.z1 = at - 0.5f * wall, b.z0 = at + 0.5f * wall;
        rooms[i] = a;
        rooms.push_back(b);
        split = true;
        break;
      }
      if (split) break;
    }
    if (!split) return false;
  }
  return true;
}

// Where two rooms share a wall: `a` on the low side of a wall perpendicular to `axis`, the shared stretch
// [t0, t1] along it.
struct Shared {
  int a, b, axis;
  float faceA, faceB, t0, t1;
};

std::vector<Shared> sharedWalls(const std::vector<Rect>& rooms) {
  std::vector<Shared> out;
  for (int i = 0; i < int(rooms.size()); ++i)
    for (int j = 0; j < int(rooms.size()); ++j) {
      if (i == j) continue;
      const Rect &a = rooms[size_t(i)], &b = rooms[size_t(j)];
      // b just past a's high x face, or just past its high z face, with a gap no thicker than a wall.
      const float gapX = b.x0 - a.x1, gapZ = b.z0 - a.z1;
      if (gapX > -1e-4f && gapX < kMaxWall + 1e-3f) {
        const float t0 = std::max(a.z0, b.z0), t1 = std::min(a.z1, b.z1);
        if (t1 - t0 >= kMinShared) out.push_back({i, j, 0, a.x1, b.x0, t0, t1});
      }
      if (gapZ > -1e-4f && gapZ < kMaxWall + 1e-3f) {
        const float t0 = std::max(a.x0, b.x0), t1 = std::min(a.x1, b.x1);
        if (t1 - t0 >= kMinShared) out.push_back({i, j, 2, a.z1, b.z0, t0, t1});
      }
    }
  return out;
}

// A random spanning tree of the rooms over the shared walls (Kruskal on shuffled edges); false when the
// shared walls do not join every room.
bool spanningTree(Draw& draw, size_t roomCount, const std::vector<Shared>& walls, std::vector<bool>& inTree) {
  std::vector<size_t> order(walls.size());
  std::iota(order.begin(), order.end(), 0);
  for (size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[size_t(draw.integer(0, int(i) - 1))]);
  std::vector<int> parent(roomCount);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  inTree.assign(walls.size(), false);
  size_t joined = 0;
  for (size_t e : order) {
    const int ra = root(walls[e].a), rb = root(walls[e].b);
    if (ra == rb) continue;
    parent[size_t(ra)] = rb;
    inTree[e] = true;
    ++joined;
  }
  return joined + 1 == roomCount;
}

// An opening of `width` somewhere in [lo, hi]: beside one end (a corner, or where another wall meets this
// one) one time in three, else anywhere.
std::pair<float, float> placeAlong(Draw& draw, float lo, float hi, float width) {
  const float slack = std::max(0.0f, hi - lo - width);
  float start = lo + draw.uniform(0.0f, 1.0f) * slack;
  if (draw.chance(1.0 / 3.0)) {
    const float offset = std::min(slack, roundTo(draw.uniform(0.0f, 0.1f), 0.01f));
    start = draw.chance(0.5) ? lo + offset : hi - width - offset;
  }
  start = roundTo(start, 0.01f);
  start = std::clamp(start, lo, hi - width);
  return {start, start + width};
}

// The openings of one shared wall: a door when `door`, a window when `window` and the rest of the wall
// leaves room for one, each apart from the other.
void openWall(Draw& draw, const Shared& s, float height, bool door, bool window,
              std::vector<PlanOpening>& out) {
  const PlanOpening base{s.a, s.b, s.axis, s.faceA, s.faceB, 0.0f, 0.0f, 0.0f, 0.0f, false};
  float lo = s.t0, hi = s.t1;
  if (door) {
    const float width = roundTo(draw.uniform(0.6f, std::min(2.0f, s.t1 - s.t0)), 0.01f);
    const auto [t0, t1] = placeAlong(draw, s.t0, s.t1, std::min(width, s.t1 - s.t0));
    PlanOpening d = base;
    d.t0 = t0, d.t1 = t1, d.y1 = roundTo(std::min(draw.uniform(2.0f, 2.2f), height - 0.2f), 0.01f);
    out.push_back(d);
    // The window goes on the longer side the door leaves, 0.2 m clear of it.
    if (t0 - s.t0 >= s.t1 - t1)
      hi = t0 - 0.2f;
    else
      lo = t1 + 0.2f;
  }
  if (!window || hi - lo < 0.6f) return;
  const float width = roundTo(draw.uniform(0.6f, std::min(1.6f, hi - lo)), 0.01f);
  const auto [t0, t1] = placeAlong(draw, lo, hi, std::min(width, hi - lo));
  PlanOpening w = base;
  w.window = true;
  w.t0 = t0, w.t1 = t1;
  w.y0 = roundTo(draw.uniform(0.8f, 1.1f), 0.01f);
  w.y1 = roundTo(std::min(draw.uniform(1.7f, 2.1f), height - 0.2f), 0.01f);
  out.push_back(w);
}

std::vector<int> distancesFrom(const RandomPlan& plan, const std::vector<int>& sources) {
  std::vector<std::vector<int>> next(plan.rooms.size());
  for (const PlanOpening& o : plan.openings) {
    next[size_t(o.a)].push_back(o.b);
    next[size_t(o.b)].push_back(o.a);
  }
  std::vector<int> dist(plan.rooms.size(), -1);
  std::queue<int> queue;
  for (int s : sources) dist[size_t(s)] = 0, queue.push(s);
  while (!queue.empty()) {
    const int r = queue.front();
    queue.pop();
    for (int n : next[size_t(r)])
      if (dist[size_t(n)] < 0) dist[size_t(n)] = dist[size_t(r)] + 1, queue.push(n);
  }
  return dist;
}

// Lamps in some rooms only: the first in a room at the end of the plan's longest path of openings, then
// one more per five rooms where that keeps a room as many openings from any lamp as the plan allows up to
// three, so that light reaches some rooms only through two or three openings.
void placeLamps(Draw& draw, RandomPlan& plan) {
  const int n = int(plan.rooms.size());
  std::vector<int> fromAny = distancesFrom(plan, {draw.integer(0, n - 1)});
  const int first = int(std::max_element(fromAny.begin(), fromAny.end()) - fromAny.begin());
  std::vector<int> lamps = {first};
  const std::vector<int> fromFirst = distancesFrom(plan, lamps);
  const int keep = std::min(3, *std::max_element(fromFirst.begin(), fromFirst.end()));
  for (int extra = n / 5; extra > 0; --extra) {
    const std::vector<int> now = distancesFrom(plan, lamps);
    std::vector<int> candidates;
    for (int r = 0; r < n; ++r)
      if (now[size_t(r)] >= 2) candidates.push_back(r);
    while (!candidates.empty()) {
      const size_t pick = size_t(draw.integer(0, int(candidates.size()) - 1));
      std::vector<int> with = lamps;
      with.push_back(candidates[pick]);
      const std::vector<int> after = distancesFrom(plan, with);
      if (*std::max_element(after.begin(), after.end()) >= keep) {
        lamps = std::move(with);
        break;
      }
      candidates.erase(candidates.begin() + std::ptrdiff_t(pick));
    }
  }
  for (int r : lamps) plan.rooms[size_t(r)].lamp = true;
}

// One attempt at a plan from the draws so far; false when the footprint would not split into the rooms or
// the shared walls would not join them all (the caller draws again).
bool tryLayout(Draw& draw, int count, RandomPlan& plan) {
  const float area = float(count) * draw.uniform(9.0f, 18.0f), aspect = draw.uniform(1.0f, 1.8f);
  plan.footprint = {roundTo(std::sqrt(area * aspect), 0.1f), 0.0f};
  plan.footprint.y = roundTo(area / plan.footprint.x, 0.1f);
  plan.height = roundTo(draw.uniform(2.5f, 3.0f), 0.05f);
  std::vector<Rect> rects;
  if (!splitFootprint(draw, plan.footprint, count, rects)) return false;
  const std::vector<Shared> walls = sharedWalls(rects);
  std::vector<bool> inTree;
  if (!spanningTree(draw, rects.size(), walls, inTree)) return false;
  plan.rooms.clear();
  for (size_t i = 0; i < rects.size(); ++i)
    plan.rooms.push_back(
        {"R" + std::to_string(i + 1), {rects[i].x0, rects[i].z0}, {rects[i].x1, rects[i].z1}});
  plan.openings.clear();
  for (size_t e = 0; e < walls.size(); ++e) {
    const bool door = inTree[e] || draw.chance(0.3);
    const bool window = draw.chance(inTree[e] ? 0.2 : 0.35);
    openWall(draw, walls[e], plan.height, door, window, plan.openings);
  }
  if (std::none_of(plan.openings.begin(), plan.openings.end(),
                   [](const PlanOpening& o) { return o.window; })) {
    // Every plan has an interior window: in the longest shared wall, beside what is there.
    const auto longest = std::max_element(walls.begin(), walls.end(), [](const Shared& a, const Shared& b) {
      return a.t1 - a.t0 < b.t1 - b.t0;
    });
    std::vector<PlanOpening> added;
    const bool hasDoor = inTree[size_t(longest - walls.begin())];
    openWall(draw, *longest, plan.height, hasDoor, true, added);
    plan.openings.erase(
        std::remove_if(plan.openings.begin(), plan.openings.end(),
                       [&](const PlanOpening& o) { return o.a == longest->a && o.b == longest->b; }),
        plan.openings.end());
    plan.openings.insert(plan.openings.end(), added.begin(), added.end());
  }
  placeLamps(draw, plan);
  return true;
}

// ---- Triangles -------------------------------------------------------------------------------------------

// An axis-aligned rectangle in a wall perpendicular to `axis` (0 or 2) at `at`, over [t0, t1] along the
// wall and [y0, y1] in height.
void wallRect(SceneBuilder& b, int axis, float at, float sign, float t0, float t1, float y0, float y1,
              uint32_t material, uint32_t node) {
  if (t1 - t0 < 1e-4f || y1 - y0 < 1e-4f) return;
  if (axis == 0)
    b.rect(0, at, sign, {y0, t0}, {y1, t1}, material, node);
  else
    b.rect(2, at, sign, {t0, y0}, {t1, y1}, material, node);
}

// One face of a room's wall over [lo, hi] with `holes` cut out (sorted along the wall, disjoint): full-height
// strips between them, the parts below and above each.
void wallWithHoles(SceneBuilder& b, int axis, float at, float sign, float lo, float hi, float height,
                   std::vector<PlanOpening> holes, uint32_t material, uint32_t node) {
  std::sort(holes.begin(), holes.end(),
            [](const PlanOpening& p, const PlanOpening& q) { return p.t0 < q.t0; });
  float t = lo;
  for (const PlanOpening& h : holes) {
    wallRect(b, axis, at, sign, t, h.t0, 0.0f, height, material, node);
    wallRect(b, axis, at, sign, h.t0, h.t1, 0.0f, h.y0, material, node);
    wallRect(b, axis, at, sign, h.t0, h.t1, h.y1, height, material, node);
    t = h.t1;
  }
  wallRect(b, axis, at, sign, t, hi, 0.0f, height, material, node);
}

// The reveal of an opening through a thick wall, cut at the mid-plane: the half on a's side under a's node,
// the other under b's; its bottom is floor for a door, wall for a window's sill.
void reveal(SceneBuilder& b, const RandomPlan& plan, const PlanOpening& o, uint32_t wall, uint32_t floor) {
  const float mid = o.midPlane();
  for (int side = 0; side < 2; ++side) {
    const float n0 = side == 0 ? o.faceA : mid, n1 = side == 0 ? mid : o.faceB;
    if (n1 - n0 < 1e-4f) continue;
    const PlanRoom& owner = plan.rooms[size_t(side == 0 ? o.a : o.b)];
    const PlanRoom& other = plan.rooms[size_t(side == 0 ? o.b : o.a)];
    const uint32_t node = b.node(owner.name + "/reveal-" + other.name + (o.window ? "-window" : ""));
    const uint32_t bottom = o.window ? wall : floor;
    if (o.axis == 0) {
      b.rect(2, o.t0, +1, {n0, o.y0}, {n1, o.y1}, wall, node);
      b.rect(2, o.t1, -1, {n0, o.y0}, {n1, o.y1}, wall, node);
      b.rect(1, o.y1, -1, {o.t0, n0}, {o.t1, n1}, wall, node);
      b.rect(1, o.y0, +1, {o.t0, n0}, {o.t1, n1}, bottom, node);
    } else {
      b.rect(0, o.t0, +1, {o.y0, n0}, {o.y1, n1}, wall, node);
      b.rect(0, o.t1, -1, {o.y0, n0}, {o.y1, n1}, wall, node);
      b.rect(1, o.y1, -1, {n0, o.t0}, {n1, o.t1}, wall, node);
      b.rect(1, o.y0, +1, {n0, o.t0}, {n1, o.t1}, bottom, node);
    }
  }
}

PortalQuad portalOf(const RandomPlan& plan, const PlanOpening& o) {
  PortalQuad p;
  p.name = "portal:" + plan.rooms[size_t(o.a)].name + ":" + plan.rooms[size_t(o.b)].name +
           (o.window ? ".window" : "");
  const float m = o.midPlane();
  auto at = [&](float t, float y) { return o.axis == 0 ? glm::vec3(m, y, t) : glm::vec3(t, y, m); };
  p.corners = {at(o.t0, o.y0), at(o.t1, o.y0), at(o.t1, o.y1), at(o.t0, o.y1)};
  p.cellA = o.a, p.cellB = o.b;
  computePortalFrame(p);
  const glm::vec3 aToB = o.axis == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  if (glm::dot(p.normal, aToB) < 0.0f) {
    std::swap(p.corners[1], p.corners[3]);
    computePortalFrame(p);
  }
  return p;
}

// A wall colour: a light neutral most of the time, one of a few strong colours (red, green, blue, yellow)
// in about one wall of four, so that colour bleeding through a door is measurable.
glm::vec3 wallColour(Draw& draw) {
  static const glm::vec3 strong[] = {
      {0.7f, 0.15f, 0.1f}, {0.15f, 0.6f, 0.2f}, {0.2f, 0.3f, 0.7f}, {0.75f, 0.6f, 0.15f}};
  if (draw.chance(0.25)) return strong[draw.integer(0, 3)];
  const float grey = draw.uniform(0.5f, 0.8f);
  return glm::vec3(grey) + glm::vec3(draw.uniform(-0.05f, 0.05f), 0.0f, draw.uniform(-0.05f, 0.05f));
}

// A room's floor, ceiling, four walls with their openings cut out, its lamp, and its camera.
void addRoom(SceneBuilder& b, Draw& draw, const RandomPlan& plan, size_t index, uint32_t floor,
             uint32_t ceiling, uint32_t lamp, Scene& scene) {
  const PlanRoom& r = plan.rooms[index];
  const float h = plan.height;
  auto node = [&](const std::string& part) { return b.node(r.name + "/" + part); };
  b.rect(1, 0.0f, +1, {r.lo.y, r.lo.x}, {r.hi.y, r.hi.x}, floor, node("floor"));
  b.rect(1, h, -1, {r.lo.y, r.lo.x}, {r.hi.y, r.hi.x}, ceiling, node("ceiling"));
  // West, east (perpendicular to x, along z) and south, north (perpendicular to z, along x).
  const struct {
    const char* name;
    int axis;
    float at, sign, lo, hi;
  } faces[] = {{"wall-west", 0, r.lo.x, +1, r.lo.y, r.hi.y},
               {"wall-east", 0, r.hi.x, -1, r.lo.y, r.hi.y},
               {"wall-south", 2, r.lo.y, +1, r.lo.x, r.hi.x},
               {"wall-north", 2, r.hi.y, -1, r.lo.x, r.hi.x}};
  for (const auto& f : faces) {
    std::vector<PlanOpening> holes;
    for (const PlanOpening& o : plan.openings) {
      const bool low = o.a == int(index) && f.sign < 0, high = o.b == int(index) && f.sign > 0;
      if (o.axis == f.axis && (low || high)) holes.push_back(o);
    }
    const uint32_t material = b.material(r.name + "-" + f.name, wallColour(draw));
    wallWithHoles(b, f.axis, f.at, f.sign, f.lo, f.hi, h, holes, material, node(f.name));
  }
  const glm::vec2 c = 0.5f * (r.lo + r.hi), size = r.hi - r.lo;
  if (r.lamp) {
    const float half =
        0.5f * roundTo(draw.uniform(0.5f, std::min(1.0f, 0.4f * std::min(size.x, size.y))), 0.01f);
    b.rect(1, h - 0.01f, -1, {c.y - half, c.x - half}, {c.y + half, c.x + half}, lamp, node("lamp"));
  }
  scene.cameras.push_back(
      lookAt(r.name, {r.lo.x + 0.3f, 1.6f, r.lo.y + 0.3f}, {r.hi.x - 0.2f, 0.7f, r.hi.y - 0.2f}));
}

}  // namespace

RandomPlan randomPlanLayout(const RandomPlanOptions& options) {
  if (options.rooms != 0 && (options.rooms < 3 || options.rooms > 12))
    throw std::invalid_argument("random plan: rooms must be in [3, 12] (0: drawn from the seed)");
  Draw draw(options.seed);
  const int count = options.rooms != 0 ? options.rooms : draw.integer(3, 12);
  RandomPlan plan;
  plan.seed = options.seed;
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt)
    if (tryLayout(draw, count, plan)) return plan;
  throw std::runtime_error("random plan: no valid layout for seed " + std::to_string(options.seed));
}

std::vector<int> openingsFromLamp(const RandomPlan& plan) {
  std::vector<int> lamps;
  for (size_t r = 0; r < plan.rooms.size(); ++r)
    if (plan.rooms[r].lamp) lamps.push_back(int(r));
  return distancesFrom(plan, lamps);
}

SeedScene buildRandomPlan(const RandomPlan& plan) {
  SeedScene out;
  SceneBuilder b(out.scene);
  // The colours come from a stream of their own, so that they do not move the layout's draws.
  Draw draw(plan.seed ^ 0x9e3779b97f4a7c15ull);
  const uint32_t floor =
      b.material("floor", glm::vec3(draw.uniform(0.35f, 0.55f)) * glm::vec3(1.0f, 0.9f, 0.8f));
  const uint32_t ceiling = b.material("ceiling", glm::vec3(0.8f));
  const uint32_t revealMaterial = b.material("reveal", glm::vec3(0.7f));
  const uint32_t lamp = b.material("light", glm::vec3(0.8f), glm::vec3(kLampEmission));
  std::vector<std::string> names;
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    addRoom(b, draw, plan, r, floor, ceiling, lamp, out.scene);
    names.push_back(plan.rooms[r].name);
  }
  for (const PlanOpening& o : plan.openings) reveal(b, plan, o, revealMaterial, floor);
  cellsFromNodePaths(out.scene, names, out.cells);
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    const PlanRoom& room = plan.rooms[r];
    appendBoxVolume({room.lo.x, 0.0f, room.lo.y}, {room.hi.x, plan.height, room.hi.y},
                    out.cells.cells[r].volume);
  }
  for (const PlanOpening& o : plan.openings) out.cells.portals.push_back(portalOf(plan, o));
  return out;
}

SeedScene makeRandomPlan(const RandomPlanOptions& options) {
  return buildRandomPlan(randomPlanLayout(options));
}

}  // namespace cpgi
