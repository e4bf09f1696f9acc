#include "core/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/ray_triangle.h"

namespace cpgi {

namespace {

// Distance along +y from `o` to triangle `t`; +inf if missed.
float upHit(const glm::vec3& o, const Triangle& t) {
  return rayTriangleDistance(o, glm::vec3(0.0f, 1.0f, 0.0f), t);
}

// The ceilings (faces turned down) binned on a grid over x and z, so a ray up tests only its column's.
struct CeilingGrid {
  static constexpr int kCells = 64;
  glm::vec2 lo{0.0f}, size{1.0f};
  std::vector<std::vector<uint32_t>> cells = std::vector<std::vector<uint32_t>>(kCells * kCells);

  int index(float x, float z) const {
    const int i = std::clamp(int((x - lo.x) / size.x * kCells), 0, kCells - 1);
    const int j = std::clamp(int((z - lo.y) / size.y * kCells), 0, kCells - 1);
    return j * kCells + i;
  }
  CeilingGrid(const Scene& scene) {
    const Bounds b = scene.bounds();
    lo = glm::vec2(b.lo.x, b.lo.z);
    size = glm::max(glm::vec2(b.hi.x - b.lo.x, b.hi.z - b.lo.z), glm::vec2(1e-6f));
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
      const Triangle& tri = scene.triangles[t];
      if (tri.geometricNormal().y > -0.5f) continue;
      float x0 = tri.p[0].x, x1 = x0, z0 = tri.p[0].z, z1 = z0;
      for (const glm::vec3& q : tri.p) {
        x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
        z0 = std::min(z0, q.z), z1 = std::max(z1, q.z);
      }
      const int a = index(x0, z0), c = index(x1, z1);
      for (int j = a / kCells; j <= c / kCells; ++j)
        for (int i = a % kCells; i <= c % kCells; ++i) cells[size_t(j * kCells + i)].push_back(t);
    }
  }
};

// The value a share `q` of the way up `values` (reordered).
double quantile(std::vector<float>& values, double q) {
  const auto at = values.begin() + std::ptrdiff_t(q * double(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

bool isFloor(const Triangle& t) {
  return t.geometricNormal().y > std::cos(25.0f * 3.14159265f / 180.0f);
}

// The lowest tenth of the rises between floor levels: each vertical face's height when its bottom and its
// top both lie at some floor's height (a riser between two treads, a ledge's side between its foot and
// its top), 0 when there are fewer than kMinRises. A wall up to a ceiling is no rise: its top is no
// floor's height.
double lowestRises(const Scene& scene) {
  std::vector<float> levels;
  for (const Triangle& t : scene.triangles)
    if (isFloor(t))
      for (const glm::vec3& p : t.p) levels.push_back(p.y);
  std::sort(levels.begin(), levels.end());
  const float tolerance = 1e-5f * glm::length(scene.bounds().size());
  auto isLevel = [&](float y) {
    const auto it = std::lower_bound(levels.begin(), levels.end(), y - tolerance);
    return it != levels.end() && *it <= y + tolerance;
  };
  std::vector<float> rises;
  for (const Triangle& t : scene.triangles) {
    if (std::abs(t.geometricNormal().y) > 0.05f) continue;
    const float lo = std::min({t.p[0].y, t.p[1].y, t.p[2].y}), hi = std::max({t.p[0].y, t.p[1].y, t.p[2].y});
    if (hi - lo > tolerance && isLevel(lo) && isLevel(hi)) rises.push_back(hi - lo);
  }
  return rises.size() < kMinRises ? 0.0 : quantile(rises, 0.1);
}

// The distances straight up from up to kUnitsSamples points spread over the floors by area (the k-th at
// cumulative area (k + ½)/N of the total) to the nearest ceiling, for the points that have one.
std::vector<float> clearancesOverTheFloors(const Scene& scene) {
  std::vector<uint32_t> floors;
  std::vector<double> cumulative;
  double total = 0.0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t)
    if (isFloor(scene.triangles[t])) {
      total += scene.triangles[t].area();
      floors.push_back(t), cumulative.push_back(total);
    }
  std::vector<float> heights;
  if (floors.empty() || !(total > 0.0)) return heights;
  const CeilingGrid grid(scene);
  const float offset = 1e-5f * glm::length(scene.bounds().size());
  for (int k = 0; k < kUnitsSamples; ++k) {
    const double at = (k + 0.5) / kUnitsSamples * total;
    const size_t f = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin());
    const Triangle& t = scene.triangles[floors[std::min(f, floors.size() - 1)]];
    const glm::vec3 o = t.centroid() + glm::vec3(0.0f, offset, 0.0f);
    float nearest = std::numeric_limits<float>::infinity();
    for (uint32_t c : grid.cells[size_t(grid.index(o.x, o.z))])
      nearest = std::min(nearest, upHit(o, scene.triangles[c]));
    if (std::isfinite(nearest)) heights.push_back(nearest);
  }
  return heights;
}

// The unit from the storeys (median h) and the steps (core/units.h says why each band); sets out.unit and
// out.scale, or leaves them empty for metres or a scene that cannot say. Returns the note after the flag.
const char* unitFromTheRooms(UnitsCheck& out) {
  const double h = out.storeyHeight, step = out.stepHeight;
  const bool steps = step > 0.0;
  if (h <= kFeetStoreys.second) {
    // A building's storeys in feet are of about one height and its stairs rise 4 inches a step or more.
    if (out.lowStoreyHeight < kFeetUniformStoreys * h || (steps && step < kFeetLowestStep)) return nullptr;
    out.unit = "feet", out.scale = 0.3048;
  } else if (h <= 60.0) {
    return nullptr;  // a hangar in feet or an arena under its sky in metres: see kFeetStoreys
  } else if (h <= 200.0) {
    out.unit = "inches (Quake units)", out.scale = 0.0254;
  } else if (h <= 600.0) {
    out.unit = "centimetres", out.scale = 0.01;
    return "or inches as in a Quake map: --scale 0.0254";
  } else if (h <= 2000.0 || (steps && step < kInchSteps.second)) {
    // Millimetres would be rooms under 2 m, and their stairs rise 100 units or more; a game's open arenas
    // are this tall in inches, and its sky box 50–150 m up over a space map.
    out.unit = "inches (Quake units)", out.scale = 0.0254;
  } else if (h <= 6000.0) {
    out.unit = "millimetres", out.scale = 0.001;
  }
  return nullptr;
}

}  // namespace

UnitsCheck checkUnits(const Scene& scene) {
  UnitsCheck out;
  std::vector<float> heights = clearancesOverTheFloors(scene);
  out.samples = int(heights.size());
  char line[300];
  if (out.samples < kUnitsSamples / 8) {
    // Mostly open: no storey to measure, but a daylit game level's steps still tell a scene in inches.
    // Only over a Quake map's breadth: a town of blocks in metres, kerbless, rises 2–24 m too.
    if (glm::length(scene.bounds().size()) < kOpenInchSceneSize) return out;
    out.stepHeight = lowestRises(scene);
    if (out.stepHeight >= kInchSteps.first && out.stepHeight < kInchSteps.second) {
      out.unit = "centimetres", out.scale = 0.01;
      std::snprintf(
          line, sizeof line,
          "units: the steps are %.0f units tall, so the scene is not in metres; it looks like "
          "centimetres or inches: --scale 0.01 or, as in a Quake map, --scale 0.0254 makes it metres",
          out.stepHeight);
      out.warning = line;
    }
    return out;
  }
  // Spaces of a person's height in metres over a share of the floors: the scene is in metres whatever its
  // median says. A game level's sealed sky box, 30–54 m over most of its floor, read as storeys in feet,
  // while its corridors and rooms are 2–6 m; in feet or any smaller unit no room is that low.
  const auto personHeight = std::count_if(heights.begin(), heights.end(), [](float x) {
    return x >= kPersonHeightInMetres.first && x <= kPersonHeightInMetres.second;
  });
  out.storeyHeight = quantile(heights, 0.5);
  out.lowStoreyHeight = quantile(heights, 0.1);
  if (out.storeyHeight <= kFeetStoreys.first ||
      double(personHeight) >= kPersonHeightShare * double(heights.size()))
    return out;
  out.stepHeight = lowestRises(scene);
  // Steps under an inch-scene's: a game level in metres whose sky box reads as tall storeys.
  if (out.storeyHeight > 60.0 && out.stepHeight > 0.0 && out.stepHeight < kMetreSteps) return out;
  const char* why = unitFromTheRooms(out);
  const double h = out.storeyHeight;
  if (out.scale > 0.0)
    std::snprintf(line, sizeof line,
                  "units: the rooms are %.0f units tall, so the scene is not in metres; it looks like %s: "
                  "--scale %g makes it metres%s%s%s",
                  h, out.unit.c_str(), out.scale, why ? " (" : "", why ? why : "", why ? ")" : "");
  else if (h > 6000.0)
    std::snprintf(line, sizeof line,
                  "units: the rooms are %.0f units tall, so the scene is not in metres; give --scale F, the "
                  "metres per unit of the file",
                  h);
  else
    return out;
  out.warning = line;
  return out;
}

}  // namespace cpgi
