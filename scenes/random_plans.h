// Random floor plans (issue 47 item 3, design.md §5 "Many layouts, not one"): a method's error is a
// distribution over plans, and the project's own scenes are too few and too alike to show it. One storey of
// 3–12 rectangular rooms cut by recursive splits of a rectangular footprint; interior walls 0.1–0.3 m thick
// or of zero thickness (two coincident back-to-back faces); doors 0.6–2 m wide anywhere along their wall
// (beside a corner too), some interior windows with a sill and a head; walls of random colours, some
// strongly coloured; emissive ceiling quads in some rooms only, placed so that rooms two and three
// openings from any lamp exist where the plan allows. The doors join every room to the others (a random
// spanning tree of the rooms that share a wall, plus extra doors), the outside is closed (inward faces of
// a closed footprint, no exterior opening). Each room is a hand-made cell (node paths "R3/...", its empty
// box as a `cellvolume:`), each opening a portal at its wall's mid-plane. Y up, metres. Deterministic for
// a seed on every platform (its own uniform draws over std::mt19937_64, whose sequence the standard fixes).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/seed_scenes.h"

namespace cpgi {

/// One room: its empty space spans [lo.x, hi.x] × [0, height] × [lo.y, hi.y] (lo, hi are x and z).
struct PlanRoom {
  std::string name;  ///< "R1", "R2", ...
  glm::vec2 lo{0.0f}, hi{0.0f};
  bool lamp = false;
};

/// An opening through the wall two rooms share. The wall is perpendicular to `axis` (0: x, 2: z) and
/// fills [faceA, faceB] along it (faceA == faceB: a zero-thickness wall); room `a` lies on the low side.
/// The opening spans [t0, t1] along the wall (the other horizontal axis) and [y0, y1] in height.
struct PlanOpening {
  int a = -1, b = -1;  ///< indices into RandomPlan::rooms
  int axis = 0;
  float faceA = 0.0f, faceB = 0.0f;
  float t0 = 0.0f, t1 = 0.0f, y0 = 0.0f, y1 = 0.0f;
  bool window = false;  ///< an interior window (y0 > 0, its sill), else a door (y0 == 0)
  float midPlane() const { return 0.5f * (faceA + faceB); }
};

/// The plan before it becomes triangles: what the tests and the bench read to check it.
struct RandomPlan {
  uint64_t seed = 0;
  float height = 2.6f;        ///< floor to ceiling, every room
  glm::vec2 footprint{0.0f};  ///< the rooms fill [0, footprint.x] × [0, footprint.y] with their walls
  std::vector<PlanRoom> rooms;
  std::vector<PlanOpening> openings;
};

struct RandomPlanOptions {
  uint64_t seed = 1;
  int rooms = 0;  ///< 3–12; 0: drawn from the seed
};

/// The layout of a plan. Throws std::invalid_argument for a room count outside [3, 12] (0 allowed).
RandomPlan randomPlanLayout(const RandomPlanOptions& options);

/// Per room, how many openings separate it from the nearest room with a lamp (0: lit itself; -1: no
/// path, never in a valid plan).
std::vector<int> openingsFromLamp(const RandomPlan& plan);

/// The scene of a plan: faces, lamps, cameras (one per room), cells and portals.
SeedScene buildRandomPlan(const RandomPlan& plan);

/// randomPlanLayout then buildRandomPlan.
SeedScene makeRandomPlan(const RandomPlanOptions& options);

}  // namespace cpgi
