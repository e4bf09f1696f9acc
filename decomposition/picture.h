// decomposition.png: the cells seen from above (plan) and from the front (elevation), one colour per
// cell, portals drawn as black lines with a white core.
#pragma once

#include "core/image_io.h"
#include "decomposition/decompose.h"

namespace cpgi::decomp {

struct PictureParams {
  int targetWidth = 900;  ///< pixels across the longer horizontal side; each voxel becomes a square of pixels
};

/// Plan (looking down −y, x to the right, z down the page) above elevation (looking along −z, y up). Each
/// pixel column shows the cell most of the voxels behind it belong to; walls dark grey, outside white,
/// void (inside closed solids) mid grey. Linear colours in [0, 1] for writePng.
ImageRGB drawDecomposition(const Decomposition& d, const PictureParams& params = {});

/// A distinct colour for cell c (golden-ratio hue steps), linear RGB.
glm::vec3 cellColour(int c);

}  // namespace cpgi::decomp
