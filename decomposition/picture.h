// decomposition.png: the cells in plan, one horizontal section per storey side by side (so an upper floor
// never hides the one below), then an elevation from the front; one colour per cell, its name on it,
// portals drawn as black lines with a red core, a scale bar in every panel. Its cost grows with the grid's
// plan and front areas, not its volume.
#pragma once

#include "core/cell_palette.h"  // cellColour: the same colours as report.html
#include "core/image_io.h"
#include "decomposition/decompose.h"

namespace cpgi::decomp {

struct PictureParams {
  int targetWidth = 900;  ///< pixels across the longer horizontal side; each voxel becomes a square of pixels
};

/// One plan per storey (looking down −y, x to the right, z down the page; "STOREY k" at its top left),
/// side by side, then the elevation (looking along −z, y up), all in one row. A plan is the voxel layer
/// 1.2 m above the storey's floor, storeys being the cells' floors clustered 1.5 m apart (one mid-height
/// layer without rooms), with the doors and windows it cuts and the holes in the floor below it, and each
/// cell's name on it; the elevation's pixels are the cell most of a sample of the voxels behind them
/// belong to. Every panel has a scale bar. Walls dark grey, outside white, void (inside closed solids)
/// mid grey. Linear colours in [0, 1] for writePng.
ImageRGB drawDecomposition(const Decomposition& d, const PictureParams& params = {});

}  // namespace cpgi::decomp
