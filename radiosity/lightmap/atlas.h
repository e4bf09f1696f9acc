// The lightmap atlas: every patch (a recognised quad, or a loose triangle) gets a chart of texels; each
// texel is a sub-patch of the radiosity solution (thesis ch. 6: "each texel is a sub-patch"). Charts are
// packed into one atlas with padding so bilinear sampling shows no seams.
//
// Texel semantics, shared by the GPU solver, the reference path tracer and the metrics:
//  - a valid texel (patch >= 0) stands for the part of its patch whose parameter square it covers;
//    its sample point is the centre of that part, `area` is that part's area in m² (Σ over a patch's
//    texels = the patch's area); buildAtlas leaves it there even inside another solid;
//  - quads: texel (i, j) of a w×h chart sits at corners[0] + (i+½)/w·(c1−c0) + (j+½)/h·(c3−c0); a grid
//    of equal coplanar quads is one chart over the merged rectangle (radiosity/lightmap/quad_grids.h), each
//    quad keeping the texels it would have alone;
//  - loose triangles: a right-triangle layout in a square chart; texels whose centre lies inside the
//    triangle are valid, each with area = triangle area / valid texel count;
//  - padding texels (patch == -1) get no light of their own: dilation copies their nearest valid
//    neighbour's value after solving, for sampling only; they carry area 0 and never count in metrics.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"

namespace cpgi {

struct AtlasParams {
  /// > 0: the thesis's mode, N×N texels per quad whatever its size (loose triangles get N×N charts too).
  int texelsPerQuad = 0;
  /// With texelsPerQuad == 0: texels per metre along each edge of a patch.
  float density = 10.0f;
  int minTexels = 2;    ///< per chart edge, so a thin ledge still has a texel across it
  int maxTexels = 256;  ///< per chart edge, so a huge floor does not take the whole atlas
  int padding = 1;      ///< texels of gutter around each chart, filled by dilation
  int maxSize = 8192;   ///< atlas edge limit in texels; exceeded → InputError naming the option
  /// Merge grids of equal coplanar quads into one chart (one shooter) up to this many texels along an
  /// edge; 0: a chart per quad, as the thesis does.
  int mergeTexels = 1024;
  /// With texelsPerQuad == 0: per scene triangle, the texels per metre of the chart that holds it (a
  /// merged grid takes its quads' largest), for an atlas whose resolution follows where the light varies
  /// (radiosity/solve/two_level_solve.h). Empty: `density` everywhere.
  std::vector<float> triangleDensity = {};
  /// Bytes a bake may take for this atlas (kBakeBytesPerTexel per texel), checked right after packing,
  /// before any per-texel array: InputError naming the size option when passed. 0: no limit.
  uint64_t memoryLimit = 0;
  /// Keep each output texel's light on its side of a solid its face runs through (a reveal through a
  /// pane, a wall through a slab): two levels interpolate it only from coarse texels it sees (mapAtlas's
  /// rays); false: from its bilinear taps whatever lies between.
  bool keepLightOnItsSideOfSolids = true;
};

/// What one atlas texel costs through a bake: the atlas's arrays (56 bytes), the solver's seven RGBA32F
/// buffers (112) and their upload copies (80), emission lobes and arrivals (32), the read-back and the
/// output images (~120).
inline constexpr double kBakeBytesPerTexel = 400.0;

struct Patch {
  int quad = -1;               ///< the (first) quad in the QuadSet, or -1 for a loose triangle
  std::vector<int32_t> quads;  ///< a merged grid's quads, row-major (grid.y rows of grid.x); one quad: itself
  glm::ivec2 grid{1, 1};  ///< quads along the chart's x and y; each covers (w/grid.x) × (h/grid.y) texels
  std::vector<int32_t> triangles;  ///< scene triangles: two per quad in `quads` order, or the loose one
  uint32_t material = 0;
  glm::vec3 normal{0.0f};
  float area = 0.0f;               ///< m²
  int x = 0, y = 0, w = 0, h = 0;  ///< the chart in atlas texels (without padding)
  /// World-space parametrisation of the chart: texel (i, j) covers the parallelogram
  /// origin + [i, i+1]·texelU + [j, j+1]·texelV (its centre is the sample point when valid).
  glm::vec3 origin{0.0f}, texelU{0.0f}, texelV{0.0f};
};

/// Up to four atlas texels and their weights, a value interpolated between texel centres.
struct BilinearTaps {
  std::array<int64_t, 4> texel{};
  std::array<double, 4> weight{};
  int count = 0;
};

/// A gutter texel that takes its value from the chart its surface goes on in
/// (radiosity/lightmap/seam_gutters.h).
struct GutterTap {
  size_t texel = 0;
  BilinearTaps from;
};

struct LightmapAtlas {
  int width = 0, height = 0;
  /// The parameter that set the resolution ("texels per quad" or "texel density"), for the messages of
  /// the limits checked later (the GPU's buffer sizes).
  std::string sizeParameter = "texel density";
  int padding = 1;  ///< texels of gutter around every chart (AtlasParams::padding), charts never sharing one
  std::vector<Patch> patches;

  // Per texel, row-major, width × height.
  std::vector<int32_t> patch;       ///< owning patch, -1 for padding/unused
  std::vector<glm::vec3> position;  ///< world-space sample point (metres)
  std::vector<glm::vec3> normal;    ///< unit
  std::vector<glm::vec3> albedo;
  std::vector<glm::vec3> emission;  ///< W/m²
  std::vector<float> area;          ///< m²; 0 for padding

  /// Per scene triangle, the atlas coordinates (in [0,1]², v down the rows) of its three corners;
  /// triangles not in the atlas (e.g. outside the cell being baked) get all zeros.
  std::vector<std::array<glm::vec2, 3>> triangleUV;

  /// The gutter texels dilate() fills from a neighbouring chart of their surface, not from their own.
  std::vector<GutterTap> gutter;

  size_t texelCount() const { return static_cast<size_t>(width) * height; }
  size_t validTexels() const;
};

/// The scene triangle under texel (i, j) of chart `p` (chart coordinates, 0 ≤ i < w, 0 ≤ j < h): the first
/// of its quad's two in a merged grid (row-major, each quad w/grid.x × h/grid.y texels), else the chart's.
int32_t texelTriangle(const Patch& p, int i, int j);

/// Thrown by buildAtlas when its deadline passes while it lays out an atlas: how far it came and the wall
/// seconds it took, from which a caller prices a coarser layout (its charts again, and its texels at the rate
/// they were filled here) before starting one.
struct AtlasLayoutStopped : std::runtime_error {
  size_t filledTexels = 0, texels = 0;  ///< texels of the charts filled (and gutters made), of width × height
  size_t charts = 0;                    ///< the atlas's charts
  double chartSeconds = 0.0;            ///< laying out and packing the charts, before the fill
  double fillSeconds = 0.0;             ///< filling `filledTexels` and making their gutters
  AtlasLayoutStopped(size_t filled, size_t all, size_t charts = 0, double chartSeconds = 0.0,
                     double fillSeconds = 0.0)
      : std::runtime_error("atlas: the deadline came during the layout"),
        filledTexels(filled),
        texels(all),
        charts(charts),
        chartSeconds(chartSeconds),
        fillSeconds(fillSeconds) {}
};

/// Lays out and fills the atlas for the given scene triangles (all when `subset` is empty).
/// Deterministic: the same scene and params give the same atlas. Past `deadline`, looked at by the clock
/// after every chart filled and before each chart's gutters (a fixed count of texels between looks was
/// 10-50 s of wall at 2 % of a core), throws AtlasLayoutStopped, however small the atlas.
LightmapAtlas buildAtlas(
    const Scene& scene, const QuadSet& quads, const AtlasParams& params, Context& ctx,
    const std::vector<uint32_t>& subset = {},
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

/// What dilate() fills gutters with: light, which a gutter extrapolated past a chart's edge keeps at 0 or
/// more, or a signed quantity (a spherical-harmonic coefficient of the light's direction), extrapolated
/// as it is: clamped at 0, the SH maps' gutters turned the light's direction at chart edges.
enum class DilatedValues { Light, Signed };

/// Fills padding texels so that bilinear lookups at chart edges don't pull in black: those of
/// `atlas.gutter` with the neighbouring chart's light at their point, the others with the value of their
/// nearest valid texel (within `radius` texels).
void dilate(const LightmapAtlas& atlas, std::vector<glm::vec3>& values, int radius = 2,
            DilatedValues kind = DilatedValues::Light);

/// Per texel, 1 where its patch emits (in any channel) and 0 elsewhere, padding included: the lamps, which
/// lightmap.exr marks as "emissive" and the error figures without lamps leave out (their B ≈ E outweighs
/// every lit wall in Σ a|R|²).
std::vector<float> emissiveMask(const LightmapAtlas& atlas);

}  // namespace cpgi
