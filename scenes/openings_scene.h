// A scene for light that arrives through openings (issue 11): rooms A, B, C along +x, a lamp only in A.
// A|B is a thick (0.3 m) wall with a wide door and an interior window; B|C a zero-thickness partition
// (two coincident back-to-back faces) with a narrow door, so C is two openings from the lamp. Hand-made
// cells A, B, C and one portal per opening, at the wall mid-planes.
#pragma once

#include "scenes/seed_scenes.h"

namespace cpgi {

/// The openings' sizes (metres), as the tests read them.
struct OpeningsLayout {
  static constexpr float kRoom = 3.0f, kHeight = 2.6f;  ///< every room 3 × 3 m, 2.6 m high
  static constexpr float kThickWall = 0.3f;             ///< A|B; B|C has no thickness
  static constexpr float kWideDoorZ0 = 0.3f, kWideDoorZ1 = 1.7f, kDoorTop = 2.1f;  ///< A|B, 1.4 m
  static constexpr float kWindowZ0 = 2.0f, kWindowZ1 = 2.7f, kWindowY0 = 1.0f, kWindowY1 = 1.7f;  ///< A|B
  static constexpr float kNarrowDoorZ0 = 2.1f, kNarrowDoorZ1 = 2.7f;  ///< B|C, 0.6 m, kDoorTop high
  static constexpr float kLampSize = 0.8f, kLampEmission = 100.0f;    ///< 1 cm under A's ceiling centre
};

SeedScene makeOpeningsScene();

}  // namespace cpgi
