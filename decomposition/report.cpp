#include "decomposition/report.h"

#include <algorithm>

namespace cpgi::decomp {
namespace {

nlohmann::json vec(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

nlohmann::json decompositionReport(const Decomposition& d, const DecomposeParams& params,
                                   const Context& ctx) {
  using nlohmann::json;
  json j;
  j["scene"] = params.sourceName;
  j["parameters"] = {
      {"voxel_m", d.frame.voxel},
      {"voxel_choice", d.voxelChoice},
      {"seal_m", params.sealRadius},
      {"level_step_voxels", params.watershed.levelStep},
      {"saddle_ratio", params.merge.saddleRatio},
      {"outside_saddle_ratio", params.merge.outsideSaddleRatio},
      {"min_depth_m", params.merge.minDepth},
      {"opening_ratio", params.merge.openingRatio},
      {"min_cell_volume_m3", params.merge.minCellVolume},
      {"storey_spread", params.merge.storeySpread},
      {"storey_opening", params.merge.storeyOpening},
      {"gallery_floor_rise_m", params.merge.galleryFloorRise},
      {"gallery_headroom_m", params.merge.galleryHeadroom},
      {"min_component_volume_m3", params.classify.minComponentVolume},
      {"portal_margin_voxels", params.portals.marginVoxels},
      {"portal_search_m", params.portals.searchRange},
  };
  size_t counts[4] = {0, 0, 0, 0};
  for (Space s : d.space) ++counts[size_t(s)];
  j["grid"] = {{"dims", {d.frame.dims.x, d.frame.dims.y, d.frame.dims.z}},
               {"origin_m", {d.frame.origin.x, d.frame.origin.y, d.frame.origin.z}},
               {"voxels", d.frame.count()},
               {"solid", counts[size_t(Space::Solid)]},
               {"inside", counts[size_t(Space::Inside)]},
               {"outside", counts[size_t(Space::Outside)]},
               {"void", counts[size_t(Space::Void)]},
               {"sealed", d.sealedVoxels}};
  j["enclosed"] = d.enclosed;
  j["outside_cell"] =
      d.outsideCell >= 0 ? nlohmann::json(d.graph.cells[size_t(d.outsideCell)].name) : nlohmann::json();
  json cells = json::array();
  for (size_t c = 0; c < d.graph.cells.size(); ++c) {
    const CellStats& s = d.cellStats[c];
    cells.push_back({{"name", d.graph.cells[c].name},
                     {"exterior", int(c) == d.outsideCell},
                     {"kind", int(c) == d.outsideCell                            ? "outside"
                              : c < d.closedRoom.size() && d.closedRoom[c]       ? "closed_room"
                              : c < d.outsidePocket.size() && d.outsidePocket[c] ? "outside_pocket"
                                                                                 : "room"},
                     {"reachable", c < d.reachable.size() && d.reachable[c]},
                     {"volume_m3", s.volume},
                     {"bounds_m", {vec(s.bounds.lo), vec(s.bounds.hi)}},
                     {"peak_m", s.peak},
                     {"voxels", s.voxels},
                     {"triangles", d.graph.cells[c].triangles.size()},
                     {"portals", d.graph.portalsOf(int(c))}});
  }
  j["cells"] = cells;
  json portals = json::array();
  for (size_t p = 0; p < d.graph.portals.size(); ++p) {
    const PortalQuad& q = d.graph.portals[p];
    json corners = json::array();
    for (const glm::vec3& c : q.corners) corners.push_back(vec(c));
    json e = {{"name", q.name},
              {"cells", {d.graph.cells[size_t(q.cellA)].name, d.graph.cells[size_t(q.cellB)].name}},
              {"corners", corners},
              {"centre", vec(q.centre())},
              {"normal", vec(q.normal)},
              {"area_m2", q.area}};
    if (p < d.portals.size())
      e["half_width_m"] = d.portals[p].halfWidth, e["interface_faces"] = d.portals[p].faces;
    portals.push_back(e);
  }
  j["portals"] = portals;
  j["counts"] = {{"cells", d.graph.cells.size()},
                 {"portals", d.graph.portals.size()},
                 {"basins", d.basins},
                 {"triangles_in", d.inputTriangles},
                 {"triangles_out", d.scene.triangles.size()},
                 {"split_triangles", d.splitTriangles},
                 {"fallback_triangles", d.fallbackTriangles}};
  size_t closedRooms = 0, pockets = 0;
  for (char c : d.closedRoom) closedRooms += c ? 1 : 0;
  for (char c : d.outsidePocket) pockets += c ? 1 : 0;
  // connected: every cell but the closed rooms (and a sealed level's outside with its pockets) reachable
  // through portals; reachable_or_closed: every cell reachable from the main part or a closed room;
  // graph_connected: all cells.
  j["checks"] = {{"leaking_faces", d.leakingFaces},
                 {"thin_wall_area_m2", d.thinWallArea},
                 {"connected", d.connectedOpen},
                 {"reachable_or_closed", d.reachableOrClosed},
                 {"graph_connected", d.graph.connected()},
                 {"closed_rooms", closedRooms},
                 {"outside_pockets", pockets},
                 {"regions", d.regions},
                 {"leak_merges", d.leakMerges},
                 {"leak_placements", d.leakPlacements},
                 {"behind_geometry_folded", d.foldedBehind},
                 {"unfaced_closed_dropped", d.droppedUnfaced},
                 {"portal_pieces_merged", d.mergedPortalPieces},
                 {"covered_outside_share", d.covered.outsideShare()}};
  json timings = json::object();
  double total = 0.0;
  for (const Context::Timing& t : ctx.timings()) {
    timings[t.stage] = timings.value(t.stage, 0.0) + t.seconds;
    if (t.stage.find('.') == std::string::npos) total += t.seconds;  // "stage.part" is inside "stage"
  }
  timings["total"] = total;  // the decomposition's stages, not "stage.part" sub-timers
  j["timings_s"] = timings;
  j["warnings"] = ctx.warnings();
  return j;
}

std::string graphSummary(const Decomposition& d) {
  int reached = 0, closed = 0;
  std::string closedNames, apartNames;
  for (size_t c = 0; c < d.graph.cells.size(); ++c) {
    const std::string& name = d.graph.cells[c].name;
    if (c < d.reachable.size() && d.reachable[c]) ++reached;
    if (c < d.closedRoom.size() && d.closedRoom[c])
      ++closed, closedNames += (closedNames.empty() ? "" : ", ") + name;
    else if (c < d.reachable.size() && !d.reachable[c])
      apartNames += (apartNames.empty() ? "" : ", ") + name;
  }
  const int parts = std::max(d.regions, 1);
  const int apart = std::max(0, parts - closed - (reached > 0 ? 1 : 0));
  auto count = [](int n, const char* one, const char* many) {
    return (n == 1 ? std::string("one ") + one : std::to_string(n) + " " + many);
  };
  std::string line = "graph: " + count(parts, "part", "parts") + " — ";
  std::string sep;
  if (reached > 0) {
    line += parts == 1 ? "every cell reached through portals"
                       : "the main one of " + count(reached, "cell", "cells") + " joined by portals";
    sep = ", ";
  }
  if (closed > 0)
    line += sep + count(closed, "closed room", "closed rooms") + " with no opening (" + closedNames +
            (closed == 1 ? ": lit by its own lamps alone)" : ": each lit by its own lamps alone)"),
        sep = ", ";
  if (apart > 0)
    line += sep + count(apart, "part", "parts") + " apart that no portal joins to the main one (" +
            apartNames + ")";
  return line;
}

}  // namespace cpgi::decomp
