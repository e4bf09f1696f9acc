// The seed scenes of design.md §4, rebuilt from the thesis's description: three 4 m × 4 m × 3 m rooms
// A, B, C along +x joined by 1.0 m × 2.1 m doors, lights 1 cm under the ceilings of A and C, with their
// hand-made cells and the two door portals at the wall mid-planes.
#pragma once

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi {

struct SeedScene {
  Scene scene;
  CellGraph cells;
};

/// @param level  1: the bare rooms; 2: plus a cube and a panel per room; 3: seed2 plus 4×4 columns in C
///               and B's walls, floor and ceiling subdivided. Throws std::invalid_argument otherwise.
SeedScene makeSeedScene(int level);

}  // namespace cpgi
