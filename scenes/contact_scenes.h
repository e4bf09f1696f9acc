// Faces that run through other solids, as IFC exports and game maps give them (issues 46, 47): a window's
// reveal through its pane (the opening and its glazing two objects), a wall through a floor slab,
// furniture sunk into a floor. Each has one side lit and another that must stay black: light there came
// through a solid. Y up, metres.
#pragma once

#include "scenes/seed_scenes.h"

namespace cpgi {

/// The box [lo, hi]'s faces that look along an axis: faces outward (an object) or inward (a room), as
/// bits of `faces`: 1 −x, 2 +x, 4 −y, 8 +y, 16 −z, 32 +z.
struct BoxFaces {
  static constexpr unsigned kAll = 63, kNoBottom = 63 & ~4u, kSides = 1 | 2 | 16 | 32;
};

/// A closed room 4 × 3 × 4 m (x, y, z from 0) inside 20 cm walls, floor and roof (closed outside faces),
/// with a 1 × 1 m hole through its north wall (z 4 to 4.2; x 1.5 to 2.5, y 1 to 2) and a 2 cm pane (z 4.09
/// to 4.11) across the hole. `throughPane`: the reveal's four faces run the wall's whole thickness through
/// the pane, a box of its own (an IFC opening with its glazing as another object); else they stop at the
/// pane on either side (a massing cut at the pane). Lit from outside (a sun), the room stays black. Cells
/// "room" and "outside"; a camera in the room looking at the window.
SeedScene makePaneRoom(bool throughPane);

/// Two storeys of 4 × 3 × 4 m over each other with a 20 cm slab between (y 3 to 3.2): a 0.6 m lamp under
/// the lower ceiling, nothing in the upper storey. A 10 cm fin wall (x 1.95 to 2.05, z 1 to 3) runs from the
/// ground through the slab to the roof; a cabinet and a table's four legs stand 5 cm deep in the slab's top,
/// a wardrobe 5 cm deep in its underside. The upper storey stays black. Cells "lower" and "upper"; a camera
/// in each.
SeedScene makeStoreysThroughSlab();

}  // namespace cpgi
