// A procedural one-storey house for the decomposition benchmark: a row of rooms each side of a hallway,
// walls as boxes with door gaps, rooms full of box furniture, wall faces cut into a grid so the
// triangle count reaches that of a real model. Y up, metres. Deterministic for a given seed.
#pragma once

#include <random>

#include "core/scene.h"

namespace cpgi::bench {

struct HouseParams {
  int roomsPerSide = 3;        ///< rooms along x on each side of the hallway
  float roomX = 5.0f, roomZ = 4.0f, hallZ = 1.6f, height = 2.7f, wall = 0.15f;
  float doorWidth = 0.9f, doorHeight = 2.1f;
  int furniturePerRoom = 30;   ///< boxes (tables, beds, shelves, chairs ...) per room
  float wallCell = 0.3f;       ///< wall and floor faces cut into squares of this size
  unsigned seed = 1;
};

/// The house; `expectedCells` gets rooms + hallway, `doors` the number of door openings.
Scene makeHouse(const HouseParams& p, int* expectedCells = nullptr, int* doors = nullptr);

}  // namespace cpgi::bench
