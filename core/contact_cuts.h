// Faces cut where other geometry runs through them (issue 46: IFC walls through slabs, panes set in
// reveals, furniture sunk into floors or standing on them). A lightmap chart that runs across a solid mixes,
// in every bilinear lookup near the contact line, the light of its visible side with the black of the part
// buried in the solid: a light or dark strip along the line. Cut along the contact lines, the buried pieces
// dropped, the visible part's chart ends at the line with its own gutter, and the buried part costs no
// texels.
//
// Runs on the loaded scene before anything charts it (core/scene_io.cpp, LoadOptions::cutContacts), so that
// the bake, the reference, the views and compare-light all see the same triangles.
#pragma once

#include <cstddef>

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi {

struct ContactCutParams {
  /// Metres: an intersection segment shorter than this, or within it of a face's edge, cuts nothing; a
  /// cut within it of another along the same axis is the same cut.
  double tolerance = 1e-4;
  /// Metres a piece's test point is lifted off its front before its rays leave (far below a pane's 2 cm).
  double lift = 1e-3;
  /// Metres: a solid whose foot (an edge of its) lies within this of a face's plane, the rest of it in front,
  /// stands on the face; its outline cuts the face and the piece under it goes (a cabinet set on a floor, or
  /// a few millimetres above it). A foot's cut within this of the face's edge lies on the edge.
  double standOff = 5e-3;
  /// Metres: an edge of a foot shorter than this cuts nothing (a table's or a chair's leg: its shade is a
  /// contact shadow under a texel, and the cuts round it would split the floor for nothing).
  double minFootprint = 0.1;
  /// Rays over the front hemisphere of a piece's test point; the piece is buried when at least
  /// `buriedShare` of them first meet a face from behind (the point lies inside a solid).
  int rays = 16;
  double buriedShare = 0.75;
  /// A face whose cut would make more pieces than this is left whole (a game map's brush faces crossing
  /// many others); such faces are counted in ContactCuts::leftWhole.
  size_t maxPiecesPerFace = 64;
};

/// What cutAtContacts did.
struct ContactCuts {
  size_t trianglesBefore = 0, trianglesAfter = 0;
  size_t facesCut = 0;      ///< quads and loose triangles cut into pieces
  size_t buriedPieces = 0;  ///< pieces dropped as lying inside a solid
  double buriedArea = 0.0;  ///< m² of faces dropped
  size_t leftWhole = 0;     ///< faces maxPiecesPerFace kept from cutting
};

/// Cuts every face of `scene` along the segments where other triangles cross or touch it from one of its
/// edges to another (CGAL's Box_intersection_d for the candidate pairs, its triangle–triangle intersection
/// for the segments), and along the outline of a solid standing on its front (a foot within
/// ContactCutParams::standOff of its plane, projected onto it exactly and clipped to it), and drops the
/// pieces that lie inside a closed solid: the floor under a cabinet, the wall behind a wardrobe, whose dark
/// texels the bilinear lookup would bleed into the floor round the foot. A quad (core/quads.h) whose cuts all
/// run along its edges is cut into rectangles (the grid through its cuts, merged back into the largest
/// rectangles that cross no cut), so that its pieces are quads again (an askew foot leaves a quad whole); any
/// other face is cut by a constrained Delaunay triangulation in its plane. Pieces keep their face's material,
/// node, texture coordinates (SurfaceUV holds over the plane) and cell; normals are interpolated. Faces no
/// segment crosses keep their triangles and order. Must run before charting: it renumbers the triangles, and
/// `cells` (hand-made cells) with them. The pieces dropped go to Scene::buriedPieces (the decomposition's
/// solid).
ContactCuts cutAtContacts(Scene& scene, CellGraph& cells, const ContactCutParams& params = {});

}  // namespace cpgi
