// Whether a scene is in metres (issue 46): cpgi takes a file's coordinates as metres (glTF's unit), but a
// game map comes in Quake units (inches) and a CAD export often in centimetres or millimetres; taken as
// metres, a level is 1 664 m wide, its pilot atlas and sky gather run for half an hour, and its light
// (W/m² over areas 1 500 times too large) is wrong. The storey height tells: rays straight up from the
// floors to the ceilings above them measure it, and a median over ten metres is not a room in metres.
#pragma once

#include <string>
#include <utility>

#include "core/scene.h"

namespace cpgi {

struct UnitsCheck {
  /// The median, over floors that have a ceiling above them, of the distance up to it (scene units, y up);
  /// 0 when too few floors have one (an open landscape) to say.
  double storeyHeight = 0.0;
  int samples = 0;  ///< floor points whose ray up met a ceiling
  /// The likely unit and the --scale that makes it metres ("" with scale 0: in metres, or cannot say).
  std::string unit;
  double scale = 0.0;
  /// One line for the user when the scene is not in metres, else "".
  std::string warning;
};

/// The storey height is measured from up to kUnitsSamples points on the floors (faces whose normal is
/// within 25° of +y, spread over them by area), each a ray straight up to the nearest face turned down.
/// Storeys of 10 to 20 units are feet (--scale 0.3048), 60 to 200 inches (0.0254: Quake's units), 200 to
/// 600 centimetres or inches (a game's tall rooms: the warning names both), 600 to 2 000 inches (a game's
/// open arenas: OpenArena's oa_ctf2 measures 864; millimetres would be rooms under 2 m), 2 000 to 6 000
/// millimetres. OpenArena's maps measure 144 (dm4ish), 160 (aggressor), 218 (oa_dm1), 256 (kaos), 448
/// (hydronex), 864 (oa_ctf2). A scene with spaces of a person's height in metres under a share of its
/// floors is in metres whatever its median (a game level in metres under a sealed sky box 30–54 m up).
/// Storeys of 20 to 60 units are told as nothing: in feet they would be 6–18 m over most of the floor, a
/// hangar's and no building's storey, while a game level in metres measures just that from its open
/// arenas up to its sky box (OpenArena's oa_shouse 30, islanddm 35, czest1tourney 54 at 0.03 m a unit).
/// A level's proportions are a feet building's (16-unit steps are 0.48 m at 0.03 m a unit), so nothing in
/// the heights tells the two apart; a metre scene called feet would be shrunk 3.3 times by a user who
/// believed it, a hangar in feet left untold is only baked at its size.
inline constexpr int kUnitsSamples = 256;
/// The storey heights, units, read as feet: a room's 3–6 m.
inline constexpr std::pair<double, double> kFeetStoreys{10.0, 20.0};
/// Heights under a ceiling that are a room's or a corridor's in metres (and too low for one in feet).
inline constexpr std::pair<float, float> kPersonHeightInMetres{1.8f, 6.0f};
/// The share of the samples at those heights that says a scene is in metres whatever its median height.
inline constexpr double kPersonHeightShare = 0.05;
UnitsCheck checkUnits(const Scene& scene);

}  // namespace cpgi
