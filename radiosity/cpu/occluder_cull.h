// Receivers an eye cannot see, found without a ray per receiver (issue 13: the interreflection by rays on a
// level of many rooms). On OpenArena's oa_dm4, 90 % of a shot's eye segments came back hidden: every
// receiver in front of a shooter costs its rays, seen or not. A cull must never drop a receiver an eye
// sees (one by the shot's coverage rays left rooms behind small openings 11–12 % dark), so this one is
// conservative: a tile of receiver texels is hidden from an eye when one ray towards the tile's centre
// hits a convex surface (a quad's or grid's rectangle, a triangle) that every line from the eye to the
// tile's bounding sphere crosses, with the whole sphere behind it (shaft culling with a single blocker,
// Haines & Wallace 1994). The first three surfaces along that ray are tried.
//
// On oa_dm4 (density 10, 500 shots) it leaves out 37 % of the eye segments, none of which a ray would have
// seen (70 M checked); most of the hidden segments are hidden by several surfaces together, which one
// blocker cannot show. Its tests cost more than they save in open rooms: the ray solver runs it only
// while it pays (ray_shot_engine.cpp, CullControl).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// Valid texels grouped by chart into tiles of at most `side` × `side`, each with the bounding sphere of
/// its texel centres lifted by `lift` along their normal (where the eyes' segments end).
struct ReceiverTiles {
  std::vector<glm::vec4> spheres;  ///< per tile: centre, radius
  std::vector<glm::vec3> normals;  ///< per tile: its chart's
  std::vector<uint32_t> counts;    ///< per tile: its texels
  std::vector<int32_t> patches;    ///< per tile: its chart
  std::vector<uint32_t> tileOf;    ///< per entry of `texels`: its tile
};
ReceiverTiles receiverTiles(const LightmapAtlas& atlas, std::span<const uint32_t> texels, float lift,
                            int side = 8);

/// The convex outline of the surface each scene triangle lies on, as far as the atlas knows it: a quad's
/// or merged grid's rectangle, else the triangle.
class ConvexOccluders {
 public:
  static constexpr int kBlockersTried = 3;

  ConvexOccluders(const Scene& scene, const LightmapAtlas& atlas);

  /// Whether every segment from `eye` to a point of `sphere` (centre, radius) ending `margin` short of it
  /// is blocked by the first surface a ray from the eye towards its centre meets. False when unsure.
  bool hides(const RayScene& rays, const glm::vec3& eye, const glm::vec4& sphere, float margin) const;
  /// The same for every one of `eyes` (a region's, a metre or two apart), by one surface: the candidates
  /// are found from the first eye alone, so a group costs the rays of one eye. False when unsure or empty.
  bool hidesFromEvery(const RayScene& rays, std::span<const glm::vec3> eyes, const glm::vec4& sphere,
                      float margin) const;

 private:
  /// Whether triangle `triangle`'s outline blocks every segment of hides()'s question.
  bool blocks(int32_t triangle, const glm::vec3& eye, const glm::vec3& axis, float distance,
              const glm::vec4& sphere, float margin) const;

  struct Outline {
    std::vector<glm::vec3> corners;  ///< convex, counter-clockwise about `normal`
    glm::vec3 normal{0.0f};
  };
  std::vector<Outline> outlines_;   ///< per patch, then one per loose scene triangle the atlas lacks
  std::vector<int32_t> outlineOf_;  ///< per scene triangle
};

}  // namespace cpgi
