// Pictures of a baked lightmap: Embree primary rays from pinhole cameras, the hit triangle's lightmap
// coordinates (LightmapAtlas::triangleUV) interpolated by the hit's barycentrics, a bilinear lookup, and
// radiance L = B/π (diffuse surfaces). Used by `cpgi bake` and `cpgi reference` alike, so the two can be
// compared picture by picture (view-*.exr; each PNG's exposure comes from what its camera sees).
#pragma once

#include <chrono>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

class RayScene;

struct ViewParams {
  int width = 640;      ///< pixels, in [16, 8192]
  int height = 0;       ///< pixels, in [16, 8192]; 0: from the width and the camera's aspect ratio
  int supersample = 2;  ///< n × n rays per pixel, box-filtered. In [1, 8].
  /// Scale applied before the PNG's clamp and sRGB curve; ≤ 0 → chosen per picture from what it sees
  /// (its pixels' 90th percentile of radiance to 0.8, as viewExposure does for the lightmap).
  float exposure = 0.0f;
};

/// The longest edge of a view picture, in pixels: the width's range, and the edge a height made from a
/// camera's aspect ratio is clamped to (an aspect of 0.001 would otherwise ask for 640 × 640 000 pixels).
inline constexpr int kMaxViewEdge = 8192;
inline constexpr int kMinViewEdge = 16;

/// A view's picture size for `camera`: params.width (clamped to [16, kMaxViewEdge]) and params.height, or
/// without one the width over the camera's aspect ratio. When that height leaves [16, kMaxViewEdge] both
/// edges are scaled to bring it back, keeping the aspect ratio where the other edge allows; `clamped` says
/// the picture is not the size asked.
struct ViewSize {
  int width = 0;
  int height = 0;
  bool clamped = false;
};
ViewSize viewSize(const Camera& camera, const ViewParams& params);

/// Bytes one view takes while it is rendered and written (its radiance, the PNG's and the EXR's
/// buffers): the views are made one at a time, so the largest counts.
double viewBytes(const ViewSize& size);

/// Interior views for a scene that has no cameras of its own (y up, as in glTF), from default_cameras.cpp:
/// one per cell but "outside", named after it; without cells (or with only "outside"), one named
/// "overview" for the whole scene, preferring a spot with something overhead. Each eye stands at 1.6 m
/// (less under a low ceiling) above an upward-facing surface of its cell, found by casting rays down
/// columns over the cell's bounds (its `volume` when it has one), at least 0.3 m from any surface, not
/// inside a solid (its rays see front faces), and looks along the longest horizontal axis of the bounds,
/// the way that sees furthest, tilted down by 8.5°. A cell with no such floor gets a view from near one
/// lower corner of its bounds towards the opposite one.
std::vector<Camera> defaultCameras(const RayScene& rays, const Scene& scene, const CellGraph& cells);

/// An exposure that makes the area-weighted 90th percentile of radiance (B/π over valid texels) 0.8, so
/// lit walls read well and lights saturate. 1 for a black lightmap.
float viewExposure(const LightmapAtlas& atlas, std::span<const glm::vec3> lightmap);

/// Linear radiance (W/m²/sr) seen by `camera`, at viewSize(camera, params). Misses, back faces and
/// triangles outside the atlas are black. `lightmap` is per atlas texel with padding already dilated (see
/// dilate()). Rendered in bands of rows; past `deadline` no band starts and the picture comes back empty
/// (no pixels).
ImageRGB renderView(
    const RayScene& rays, const Scene& scene, const LightmapAtlas& atlas, std::span<const glm::vec3> lightmap,
    const Camera& camera, const ViewParams& params = {},
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

/// The cameras views are rendered from: the scene's own, or defaultCameras() when it has none.
std::vector<Camera> viewCameras(const RayScene& rays, const Scene& scene, const CellGraph& cells);

/// The views a call rendered: the NAMEs written, and the cameras' names it did not render because the
/// deadline came first.
struct RenderedViews {
  std::vector<std::string> written;
  std::vector<std::string> skipped;
};

/// Renders each of `cameras` and writes `view-NAME.exr` (linear radiance) and `view-NAME.png` (tone-mapped:
/// params.exposure, or else chosen from what that camera sees, its pixels' 90th percentile of radiance to
/// 0.8) through `out`; NAME is the camera name made file-safe and unique. A camera whose picture viewSize
/// clamps is named in one warning. Past `deadline` no view starts, one being rendered is dropped, and the
/// rest are skipped, said in one warning; the first `leastViews` cameras are rendered whatever the deadline
/// (a time-limited bake shows at least its first view of what it baked).
RenderedViews renderCameraViews(
    const RayScene& rays, const Scene& scene, std::span<const Camera> cameras, const LightmapAtlas& atlas,
    std::span<const glm::vec3> lightmap, OutputDir& out, Context& ctx, const ViewParams& params = {},
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    size_t leastViews = 0);

/// renderCameraViews() over viewCameras().
RenderedViews renderViews(
    const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
    std::span<const glm::vec3> lightmap, OutputDir& out, Context& ctx, const ViewParams& params = {},
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    size_t leastViews = 0);

}  // namespace cpgi
