// measureAtlas: the size of the atlas buildAtlas (atlas.h) would lay out, without filling its texels.
#pragma once

#include <cstddef>

#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// The size of buildAtlas's atlas, from its charts alone (laid out and packed, no texel filled): a texel
/// budget's scale is found on these, the per-texel arrays made once at the scale that fits.
struct AtlasSize {
  int width = 0, height = 0;
  size_t validTexels = 0;  ///< as LightmapAtlas::validTexels() of the atlas built with the same input
  size_t texelCount() const { return size_t(width) * size_t(height); }
};
AtlasSize measureAtlas(const Scene& scene, const QuadSet& quads, const AtlasParams& params);

}  // namespace cpgi
