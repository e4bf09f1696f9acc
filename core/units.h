// Whether a scene is in metres (issue 46): cpgi takes a file's coordinates as metres (glTF's unit), but a
// game map comes in Quake units (inches) and a CAD export often in centimetres or millimetres; taken as
// metres, a level is 1 664 m wide, its pilot atlas and sky gather run for half an hour, and its light
// (W/m² over areas 1 500 times too large) is wrong. The storey height tells: rays straight up from the
// floors to the ceilings above them measure it, and a median over ten metres is not a room in metres.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include "core/scene.h"

namespace cpgi {

struct UnitsCheck {
  /// The median, over floors that have a ceiling above them, of the distance up to it (scene units, y up);
  /// 0 when too few floors have one (an open landscape) to say.
  double storeyHeight = 0.0;
  int samples = 0;  ///< floor points whose ray up met a ceiling
  /// The lowest tenth of those distances (scene units): the level's low rooms and corridors, where the
  /// median may be a game level's sky box over its open arenas.
  double lowStoreyHeight = 0.0;
  /// The lowest tenth of the rises between two floor levels (scene units): the heights of the vertical
  /// faces whose bottom and top each lie at a floor's height (a stair's risers, a ledge's side); 0 when
  /// the scene has none.
  double stepHeight = 0.0;
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
/// millimetres, or inches when the steps are an inch-scene's (a Quake map's sky box 100 m up over a space
/// map). A scene with spaces of a person's height in metres under a share of its floors is in metres
/// whatever its median (a game level in metres under a sealed sky box 30–54 m up).
/// The median alone cannot tell a game level in metres from a building in another unit: a sealed level's
/// floors lie mostly under its sky box (15 m over OpenArena's pxlfan, 104 m over cbctf1), which reads as
/// storeys in feet or inches. The level's rooms tell, two ways:
/// - its steps: rises between floor levels under kMetreSteps units are a stair's or a ledge's in metres
///   (a Quake map's 8- and 16-unit steps are 0.24 and 0.48 m); in inches, centimetres or millimetres no
///   stair rises less than an inch. So a scene whose median reads inches or smaller but whose steps are
///   under that is in metres.
/// - its storeys: a building in feet has its floors under storeys of about one height (the lowest tenth
///   at least kFeetUniformStoreys of the median) and stairs whose risers are 4 inches or more; a game
///   level in metres has arenas under its sky beside low rooms, and 8-unit (0.24) steps.
/// Storeys of 20 to 60 units are told as nothing: in feet they would be 6–18 m over most of the floor, a
/// hangar's and no building's storey, while a game level in metres measures just that from its open
/// arenas up to its sky box (OpenArena's oa_shouse 30, islanddm 35, czest1tourney 54 at 0.03 m a unit).
/// A metre scene called feet would be shrunk 3.3 times by a user who believed it, a hangar in feet left
/// untold is only baked at its size: where the rooms cannot tell, the line says nothing.
inline constexpr int kUnitsSamples = 256;
/// The storey heights, units, read as feet: a room's 3–6 m.
inline constexpr std::pair<double, double> kFeetStoreys{10.0, 20.0};
/// Heights under a ceiling that are a room's or a corridor's in metres (and too low for one in feet).
inline constexpr std::pair<float, float> kPersonHeightInMetres{1.8f, 6.0f};
/// The share of the samples at those heights that says a scene is in metres whatever its median height.
inline constexpr double kPersonHeightShare = 0.05;
/// Steps (the lowest tenth of the rises between floor levels) under this many units: a scene in metres.
inline constexpr double kMetreSteps = 1.0;
/// Steps of this many units (the lowest tenth of the rises): a scene in inches or centimetres (a Quake
/// map's 8- and 16-unit steps, a stair's 15–20 cm), not millimetres; on a scene with no storey to measure
/// (a daylit level open to the sky) they alone say it is not in metres.
inline constexpr std::pair<double, double> kInchSteps{2.0, 24.0};
/// A scene open to the sky is told by its steps only when it is this many units across (its bounds'
/// diagonal): every Quake map is (its smallest arena is 40 m, 1 300 units), while a town of blocks in
/// metres whose rises are all 2–24 m (no kerb, no stair) would be told wrongly if a few hundred metres.
inline constexpr float kOpenInchSceneSize = 1000.0f;
/// The fewest rises between floor levels that say what a scene's steps are.
inline constexpr size_t kMinRises = 16;
/// The lowest tenth of a building's storeys in feet is at least this share of their median.
inline constexpr double kFeetUniformStoreys = 0.75;
/// A stair in feet rises at least 4 inches a step: lower steps are a game level's in metres.
inline constexpr double kFeetLowestStep = 4.0 / 12.0;
UnitsCheck checkUnits(const Scene& scene);

}  // namespace cpgi
