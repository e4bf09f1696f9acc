// The files every lightmap producer writes (design.md §3), in one place so that `cpgi bake` and
// `cpgi reference` stay comparable file for file: lightmap.exr, lightmap.png, baked.glb and the view
// pictures.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/views.h"

namespace cpgi {

struct LightmapOutputs {
  float exposure = 1.0f;                  ///< used for the glb's texture (viewExposure)
  std::vector<std::string> views;         ///< camera names, files view-NAME.exr / .png
  std::vector<std::string> skippedViews;  ///< cameras not rendered: the deadline came first
};

/// Dilates `radiosity` (per atlas texel, W/m², padding ignored) and stages through `out`:
///  - lightmap.exr: R, G, B = radiosity B; channel "area" (m² per texel, 0 on padding) and any `extra`;
///  - lightmap.png: the lightmap as radiance B/π at `exposure`, as the glb shows it;
///  - baked.glb: the scene (with `cells` and their portals, when there are any) with the atlas as
///    TEXCOORD_1 and the lightmap (B/π at `exposure`) as an unlit texture, so any glTF viewer shows the
///    baked light;
///  - view-NAME.exr / .png for every camera (renderViews), those `viewsDeadline` leaves time for.
/// Nothing appears in the folder before out.commit().
LightmapOutputs writeLightmapOutputs(
    OutputDir& out, const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
    std::vector<glm::vec3> radiosity, const std::vector<ExrChannel>& extra, Context& ctx,
    const ViewParams& viewParams = {},
    std::chrono::steady_clock::time_point viewsDeadline = std::chrono::steady_clock::time_point::max());

}  // namespace cpgi
