// One shot of progressive radiosity on the CPU (issue 13 item 3): the GPU solver's shot (gl_shot_engine.h,
// shaders/receive.comp) with Embree rays where it draws item buffers. A shooter patch is cut into the same
// visibility regions (shooter_layout.h); each region's eye is a texel drawn by unshot power; a receiver
// texel gathers a region's light when a ray from that eye reaches its centre, through the region's pieces
// (blocks of texels taken whole when far, texels, then 4×4 sub-disks when near). Rays from one eye to every
// receiver replace an item buffer per eye: on llvmpipe the buffers and the receive pass were ~40 of the
// ~48 s of seed3's interreflection (bench/RESULTS.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/cpu/occluder_cull.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"

namespace cpgi {

/// What stays the same over a solve's shots: the atlas's valid texels, which patch each scene triangle
/// belongs to (what a coverage ray hit), the rays.
struct RayShotScene {
  const Scene& scene;
  const LightmapAtlas& atlas;
  const RayScene& rays;
  std::vector<uint32_t> texels;                    ///< valid texels, row-major
  std::vector<int32_t> trianglePatch;              ///< per scene triangle, its patch or -1
  std::vector<std::vector<uint32_t>> patchTexels;  ///< per patch, its valid texels
  float offset = 0.0f;                             ///< ray ends lifted off their surfaces by this (m)
  ReceiverTiles tiles;                             ///< the receivers by tiles of a chart, for the cull
  ConvexOccluders occluders;

  RayShotScene(const Scene& scene, const LightmapAtlas& atlas, const RayScene& rays);
};

struct RayShotParams {
  float farField = 2.0f;    ///< a piece counts whole beyond this many of its radii (SolverParams::farField)
  int coverageRays = 1024;  ///< per region: cosine-distributed rays measuring what its eyes see covered
  /// Eyes per region, drawn by power and stratified; a receiver gathers the region's light times the share
  /// of them that see it.
  int eyesPerRegion = 2;
  /// Eye sets per region along each axis of the receivers' texel grid: the region's eyes are drawn
  /// eyeSetsPerEdge² times as many, stratified by power, and a receiver texel looks from the set its place
  /// in a eyeSetsPerEdge × eyeSetsPerEdge tile of the atlas names (interleaved sampling, Keller & Heidrich
  /// 2001), so each receiver still tests eyesPerRegion eyes but a room's texels together test all of them.
  /// With every receiver on the same eyes, a room lit through doors took the visibility of two points of each
  /// region for its mean: plan 4's room three doors from the lamp read 1.067 / 1.071 / 1.130 of the
  /// reference over three eye sequences. 1: one set, every receiver on the same eyes.
  int eyeSetsPerEdge = 2;
  /// A receiver near a region (nearer than farField × its radius) sees each of its pieces by its own ray
  /// rather than through the region's eyes.
  bool nearRays = true;
  /// Leave out an eye's segments to a tile of receivers that one surface hides whole (occluder_cull.h).
  bool cull = true;
  /// Per patch (empty: none), non-zero for an opening (a cell's portal, ShotShape::openingPatches): its
  /// receiver texels are seen through openingPoints² points over their texel, each with its share of
  /// the light, rather than through their centre alone (ray_shot.cpp).
  std::span<const uint8_t> openings = {};
  /// Points per edge of an opening's receiver texel (ShotShape::openingPoints).
  int openingPoints = 4;
  /// A region whose bounding radius is under this (m) is seen from one eye: on a furnished house's books
  /// and handles the eyes fell within a coarse texel of each other, each costing a ray per receiver.
  float oneEyeRadius = 0.25f;
};

/// How the shooters emit where they are not Lambertian (the cells' directional and binned portals,
/// radiosity/solve/shot_shape.h): per atlas texel a lobe (radiosity/solve/emission_lobes.h; zero:
/// Lambertian; binnedLobe(slot): by the bins of `bins`' slot, radiosity/solve/emission_bins.h). Empty
/// `lobes`: every shooter Lambertian, the plain shot. `arrivals`: also note the direction moments of what
/// each receiver gathers (RayShotGain::arrivals), for directional portals.
struct ShooterEmission {
  std::span<const glm::vec4> lobes;
  std::span<const float> bins;
  bool arrivals = false;
};

/// What one shot gave: per valid texel (RayShotScene::texels order), the irradiance it gathered
/// (W/m²) before any scaling, and what the eyes saw.
struct RayShotGain {
  std::vector<glm::vec3> irradiance;
  double gathered = 0.0;  ///< Σ irradiance × area, R + G + B
  double covered = 0.0;   ///< power-weighted share of the eyes' hemispheres showing a receiver facing them
  double open = 0.0;      ///< ... showing nothing at all
  size_t cullTests = 0;   ///< eye–tile pairs the cull tested (each one to three rays)
  size_t cullSaved = 0;   ///< eye segments it left out
  /// With ShooterEmission::arrivals, per valid texel the arrival moments of what it gathered
  /// (arrivalMoment, weighted by the gathered irradiance before any scaling); else empty.
  std::vector<glm::vec4> arrivals;
};

/// A patch of a shot and its visibility regions.
struct ShotMember {
  int patch = -1;
  const ShooterLayout* layout = nullptr;
};

/// Shoots the unshot radiosity `residual` of several patches at once: a cluster of small coplanar patches
/// (shooter_clusters.h). Each patch's regions give their pieces' form factors as in a shot of its own, but
/// the receivers see them all through one set of eyes (RayShotParams::eyesPerRegion per receiver, in
/// eyeSetsPerEdge² sets; one when the cluster is narrower than oneEyeRadius), drawn by power over every
/// texel of the cluster: a cluster costs a receiver what one region does. The first member's normal and
/// frame are the shot's. One member: the shot below.
RayShotGain shootByRays(const RayShotScene& s, std::span<const ShotMember> members,
                        std::span<const glm::vec3> residual, uint32_t shotNumber, const RayShotParams& params,
                        const ShooterEmission& emission = {});

/// Shoots patch `shooter`'s unshot radiosity `residual` (per atlas texel) with the regions of `layout`,
/// eyes drawn by the shot's number `shotNumber`, its texels emitting as `emission` says. Receivers are
/// every valid texel of the other patches.
RayShotGain shootByRays(const RayShotScene& s, int shooter, const ShooterLayout& layout,
                        std::span<const glm::vec3> residual, uint32_t shotNumber, const RayShotParams& params,
                        const ShooterEmission& emission = {});

}  // namespace cpgi
