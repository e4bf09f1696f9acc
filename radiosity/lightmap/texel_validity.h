// Texel sample points out of solids (issues 46, 47). A face that runs through another solid — a window's
// reveal through its pane, a wall through a floor slab, a cabinet's side into a wall, a table leg into the
// floor, as IFC exports and game maps give them everywhere — has texels whose centre lies inside that
// solid, or on the far side of it from the rest of the texel. Lit from there, the texel carries the light of
// the other side (the sunlit outside onto a closed room's reveal). Lightmappers treat it the same way
// (Godot's lightmapper, "unocclude"; Bakery's and Unity's texel validity): rays from the texel's centre in
// its own plane find a face seen from behind within the texel, i.e. a solid the centre is in, and the
// sample point moves just past it, onto the open side.
//
// Run on a filled atlas, before anything lights it, every engine and the reference read the same moved
// atlas.position. buildAtlas does not run it yet: the lamps' shot (lamp_light.cpp, seeLamp) samples points
// over the texel's footprint around its sample point, and those still reach past the solid — moved, the
// bottom row of a fin wall through a slab came out lit in the storey above (bench/RESULTS.md, "Light
// through a solid a face runs through"); and a coarse texel moved to one side carries both sides' light.
#pragma once

#include <cstddef>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// Moves the sample point (atlas.position) of every valid texel of `atlas` whose centre lies inside a solid
/// of `scene` out to its nearest open side, within one texel of it. Inside: the first face that one of four
/// rays from the centre along the texel's axes in its plane (lifted off it by a thousandth of the texel)
/// meets within a texel is seen from behind; the point goes just past the nearest such face. A centre in the
/// open meets front faces only and stays, so a floor texel in a room's corner keeps its point. `rays` must be
/// built from `scene`. Returns how many texels moved; a centre deeper in a solid than a texel stays.
size_t moveSamplePointsOutOfSolids(LightmapAtlas& atlas, const Scene& scene, const RayScene& rays);

}  // namespace cpgi
