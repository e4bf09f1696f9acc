// A building of many rooms for baking past one machine (issue 16): storeys of a grid of 4 × 4 m rooms,
// 3 m high, walls and slabs 0.2 m thick, a 1 × 2.1 m door in every wall between two rooms of a storey and
// a 1.2 × 1.2 m hatch in the slab between the corner rooms of consecutive storeys. One room in three has a
// 0.6 m square lamp under its ceiling, so most light reaches a room through its doors. Each room is a
// hand-made cell (node paths "F1-R2-C3/..."), each door and hatch a portal at its wall's or slab's
// mid-plane. Closed: no outside cell. Y up, metres.
#pragma once

#include "scenes/seed_scenes.h"

namespace cpgi {

struct OfficeLayout {
  int storeys = 3, rows = 6, columns = 6;  ///< 108 rooms
};

/// Throws std::invalid_argument unless every count is in [1, 64].
SeedScene makeOfficeBuilding(const OfficeLayout& layout);

}  // namespace cpgi
