// The user's settings of a progressive solve, whichever backend shoots it (radiosity/solve/shot_engine.h).
#pragma once

#include "radiosity/lightmap/shot_settings.h"

namespace cpgi {

enum class Visibility {
  Hemisphere,  ///< the thesis's one-pass hemispherical item buffer (curved-edge error on coarse meshes)
  Hemicube,    ///< five perspective faces: straight edges stay straight
};

inline const char* visibilityName(Visibility v) {
  return v == Visibility::Hemisphere ? "hemisphere" : "hemicube";
}

/// The user's settings of a solve (the CLI binds them to flags, apps/options.cpp): the shared ones (stop,
/// regions, pieces; shot_settings.h), then each backend's own, which the other leaves unread: the item
/// buffers' (radiosity/gpu/) and the rays' (radiosity/cpu/).
struct SolverParams : ShotSettings {
  Visibility visibility = Visibility::Hemicube;
  /// Hemisphere: the buffer's edge in pixels. Hemicube: twice a face's edge (faces of N/2, so both modes
  /// hold about N² pixels). In [16, GL_MAX_TEXTURE_SIZE], even.
  int itemBuffer = 512;
  /// Item-buffer neighbourhood radius for the visibility test: 0 → the receiver's own pixel, with the
  /// plane test of shaders/visibility.glsl (right on average at silhouettes); 1 → also the thesis's
  /// 3×3 (a texel within a pixel of a silhouette counts as lit: +15 % in a room lit through doors).
  int neighbourhood = 0;
  /// Each shot draws every visibility region's eye at a texel with probability ∝ its unshot power (a
  /// low-discrepancy draw per shot), so that visibility from a region is right on average over its power.
  /// Off: the fixed eye of shooter_layout.h, chosen clear of nearby occluders, which sees more than most of
  /// the region does (a lamp under a ceiling: the ceiling's shots delivered 1.1–1.2× their power).
  bool jitteredEyes = true;
  /// > 0: the lamps (patches whose material emits) shoot first on the CPU, by this many shadow rays per
  /// texel and lamp, 16× in penumbrae (radiosity/lightmap/lamp_light.h), and not through item buffers. 0:
  /// item buffers, as every other shot. A multiple of 4.
  int lampRays = 0;
  /// Hemicube: each shot lists per face the triangles that may show in it (shaders/item_cull.comp) and
  /// draws only those, bit-identical to drawing every triangle into every face (off: that), which on
  /// llvmpipe took 1.8× as long (bench/RESULTS.md, "Item buffers drawn indexed and culled").
  bool cullItemBuffers = true;
  /// Wait for the GPU after every pass and record per-pass times in the Context ("solve: receive", ...).
  /// Costs some speed on a real GPU; on llvmpipe the passes run synchronously anyway.
  bool profilePasses = false;

  /// Rays: cosine-distributed rays per region eye measuring what it sees covered (the item buffer's
  /// coverage).
  int coverageRays = 1024;
  /// Rays: eyes per region for the receivers far from it (RayShotParams::eyesPerRegion). On seed3 at
  /// --density auto, per cell A / B / C over three draws: 1 eye 1.16 / 3.77 / 3.22 % in 2.4 s, 2 eyes
  /// 0.99 / 3.47 / 3.16 % in 3.6 s, 4 eyes 0.94 / 3.36 / 3.03 % in 5.2 s (item buffers: 1.94 / 4.02 /
  /// 3.59 % in 14.7 s).
  int eyesPerRegion = 2;
  /// Rays: eyes per region in the strong shots (strongShotFraction), which carry most of the light through
  /// openings. 2 → 4, mean of 2–3 eye draws, worst room and CPU: seed3 C 3.16 → 3.01 % (+11 % CPU),
  /// openings C 5.47 → 5.01 % (+13 %), seed1 B 2.26 → 1.89 % (+24 %).
  int strongEyesPerRegion = 4;
  /// Rays: small coplanar patches within this radius (m) of each other shoot together, seen from one set
  /// of eyes (radiosity/cpu/shooter_clusters.h); 0: every patch alone. Half of regionSize: a cluster is
  /// no wider than a visibility region of a large patch, which one set of eyes serves.
  float clusterRadius = 0.5f;
};

}  // namespace cpgi
