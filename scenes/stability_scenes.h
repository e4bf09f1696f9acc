// Small scenes where a method is known to fail (design.md §6, "the stability suite"), each with its
// hand-made cells. Every one pins one failure: tests and the report measure it.
#pragma once

#include <string>
#include <vector>

#include "scenes/seed_scenes.h"

namespace cpgi {

/// Two rooms A and B (seed dimensions) joined by a 1.0 m × 2.1 m door. A has no ordinary light: a
/// spot-like lamp (a 0.3 m emissive square at the back of a 0.5 m deep black housing) stands against A's
/// west wall aimed +x through the door, so a pool of light falls on B's east wall. A diffuse portal
/// re-emitter spreads that pool over all of B; the truth keeps it concentrated.
SeedScene makeSpotThroughDoor();

/// Two rooms A and B (seed dimensions) joined by the seed door, lit by nothing but a KHR_lights_punctual
/// point light (about 100 W) in the middle of A, 0.8 m under its ceiling: B gets only what passes the door.
SeedScene makePointLightRooms();

/// The same rooms lit by a punctual spot light in A (inner cone 8°, outer 11°, about 47 W) aimed +x through
/// the door at door height, the punctual twin of makeSpotThroughDoor: the beam lands on B's east wall.
SeedScene makeSpotLightThroughDoor();

/// Two rooms sharing one wall of `thickness` metres (0: two coincident back-to-back faces) with no
/// opening: A is lit, B must stay exactly black. Light in B is a leak. `shiftB` slides B along the wall
/// (z), so that a side wall of each room meets the other's wall mid-span (T-junctions).
SeedScene makeThinWall(float thickness, float shiftB = 0.0f);

/// Names of the built-in scenes `cpgi generate` knows, and the scene for a name (std::invalid_argument
/// for an unknown one).
const std::vector<std::string>& builtinSceneNames();
SeedScene makeBuiltinScene(const std::string& name);

}  // namespace cpgi
