// Default cameras for scenes that bring none: one per cell, standing in the cell's empty space at eye
// height above a floor of that cell, found with Embree rays rather than from bounding boxes (a scene's
// bounds centre lands under a game level, and terrain pulls a house's bounds floor down).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <tbb/parallel_for.h>

#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/views.h"

namespace cpgi {
namespace {

constexpr float kEyeHeight = 1.6f;      ///< metres above the floor
constexpr float kHeadroom = 0.35f;      ///< metres kept between the eye and a low ceiling
constexpr float kMinEyeHeight = 0.5f;   ///< lower than this the space is a crawl space, not a room
constexpr float kWallClearance = 0.3f;  ///< metres from the eye to the nearest surface, horizontally
constexpr float kTilt = 0.15f;          ///< the view looks down by atan(0.15) ≈ 8.5° to show the floor
constexpr float kFar = std::numeric_limits<float>::infinity();

Camera lookAt(const std::string& name, glm::vec3 eye, glm::vec3 target) {
  Camera cam;
  cam.name = name;
  cam.position = eye;
  cam.forward = glm::normalize(target - eye);
  const glm::vec3 worldUp(0.0f, 1.0f, 0.0f);
  cam.up = glm::normalize(worldUp - cam.forward * glm::dot(cam.forward, worldUp));
  cam.yfov = glm::radians(65.0f);
  cam.aspect = 4.0f / 3.0f;
  return cam;
}

/// Looking horizontally along `direction`, tilted down a little.
Camera lookAlong(const std::string& name, glm::vec3 eye, glm::vec3 direction) {
  return lookAt(name, eye, eye + direction - glm::vec3(0.0f, kTilt, 0.0f));
}

/// Where one camera is wanted: a cell, or the whole scene.
struct Region {
  std::string name;
  Bounds bounds;                                   ///< the eye stays strictly inside (x, z) and below hi.y
  const std::vector<int>* triangleCell = nullptr;  ///< per triangle; null: every floor counts
  int cell = -1;                                   ///< the floor under the eye must be this cell's
  bool preferRoofed = false;  ///< whole scene: an eye in a room beats one under a roof or the sky
};

/// What one ray sees: the distance to the first surface (kFar for none) and whether it saw its back.
struct Look {
  float distance = kFar;
  bool backFace = false;
};

Look look(const RayScene& rays, const Scene& scene, glm::vec3 from, glm::vec3 direction) {
  const RayScene::Hit hit = rays.intersect(from, direction);
  if (!hit) return {};
  return {hit.t, glm::dot(scene.triangles[size_t(hit.triangle)].geometricNormal(), direction) > 0.0f};
}

struct Spot {
  glm::vec3 eye{0.0f};
  glm::vec3 direction{0.0f};
  float score = -kFar;
};

/// How much of the room a camera at `eye` looking along `direction` (horizontal) sees: the mean distance
/// (up to `extent`) of a fan of rays across its field of view, counting only rays that end on a surface of
/// the region's own cell. A ray through a door sees the next room, which is not what a camera named after
/// this one is for: counted as far, an eye just in front of a door looking through it won (every seed
/// room's camera once showed the room next door); looking out of the building scores nothing.
float openView(const RayScene& rays, const Region& region, glm::vec3 eye, glm::vec3 direction, float extent) {
  const glm::vec3 side = glm::normalize(glm::cross(direction, glm::vec3(0.0f, 1.0f, 0.0f)));
  float sum = 0.0f;
  int n = 0;
  for (const float across : {-0.45f, -0.22f, 0.0f, 0.22f, 0.45f})
    for (const float up : {-0.27f, 0.0f, 0.18f}) {
      const glm::vec3 ray = glm::normalize(direction + across * side + glm::vec3(0.0f, up, 0.0f));
      const RayScene::Hit hit = rays.intersect(eye, ray);
      const bool own =
          hit && (!region.triangleCell || (*region.triangleCell)[size_t(hit.triangle)] == region.cell);
      sum += own ? std::min(hit.t, extent) : 0.0f;  // the sky and the next room show nothing of this one
      ++n;
    }
  return sum / float(n);
}

/// The eye above the floor point `floor`, if there is room for a person there, with its view direction
/// along ±`axis` (whichever sees more, openView) and a score: how much it sees plus how far it keeps from
/// the nearest surface.
std::optional<Spot> standAt(const RayScene& rays, const Scene& scene, const Region& region, glm::vec3 floor,
                            glm::vec3 axis, float extent) {
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const Look above = look(rays, scene, floor + 1e-3f * up, up);
  if (above.backFace) return std::nullopt;  // under the floor of something solid
  const float height = std::min(kEyeHeight, above.distance - kHeadroom);
  if (height < kMinEyeHeight) return std::nullopt;
  const glm::vec3 eye = floor + height * up;
  const Bounds& b = region.bounds;
  if (!(eye.x > b.lo.x && eye.x < b.hi.x && eye.z > b.lo.z && eye.z < b.hi.z && eye.y < b.hi.y))
    return std::nullopt;

  // Sixteen horizontal rays: an eye inside a wall or a closed object sees back faces all round; an eye in
  // a room sees front faces (a few back faces are allowed for scenes with carelessly wound triangles), and
  // something in every direction.
  float nearest = above.distance - height;
  int backFaces = 0, open = 0;
  for (int k = 0; k < 16; ++k) {
    const float a = float(k) * 0.125f * 3.14159265f;
    const Look l = look(rays, scene, eye, {std::cos(a), 0.0f, std::sin(a)});
    nearest = std::min(nearest, l.distance);
    backFaces += l.backFace;
    open += l.distance == kFar;
  }
  if (backFaces > 4 || nearest < kWallClearance) return std::nullopt;
  // For the whole scene, a room (roofed, closed all round) beats a porch (roofed), which beats the open.
  const float indoors = !region.preferRoofed || above.distance == kFar ? 0.0f : open == 0 ? 2e4f : 1e4f;

  Spot spot;
  for (const float sign : {1.0f, -1.0f}) {
    const glm::vec3 direction = sign * axis;
    const float score =
        openView(rays, region, eye, direction, extent) + 0.5f * std::min(nearest, 1.5f) + indoors;
    if (score > spot.score) spot = {eye, direction, score};
  }
  return spot;
}

/// Scans columns over the region's bounds from above; every upward-facing surface of the region met on the
/// way down is a floor candidate.
std::optional<Camera> placeCamera(const RayScene& rays, const Scene& scene, const Region& region) {
  const Bounds& b = region.bounds;
  const glm::vec3 size = b.size();
  if (b.empty() || size.x <= 0.0f || size.z <= 0.0f) return std::nullopt;
  const glm::vec3 axis = size.x >= size.z ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  const float extent = std::max(size.x, size.z);
  const float step = std::max(0.1f, extent / 16.0f);
  const int nx = std::clamp(int(std::ceil(size.x / step)), 3, 24);
  const int nz = std::clamp(int(std::ceil(size.z / step)), 3, 24);
  const glm::vec3 down(0.0f, -1.0f, 0.0f);
  const float top = b.hi.y + 0.01f * (1.0f + glm::length(size));

  Spot best;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j) {
      const glm::vec3 origin(b.lo.x + (float(i) + 0.5f) / float(nx) * size.x, top,
                             b.lo.z + (float(j) + 0.5f) / float(nz) * size.z);
      float tnear = 0.0f;
      for (int k = 0; k < 64; ++k) {  // every surface down the column, a storey at a time
        const RayScene::Hit hit = rays.intersect(origin, down, tnear);
        if (!hit) break;
        tnear = hit.t + 1e-3f;
        const glm::vec3 floor = origin + hit.t * down;
        if (floor.y < b.lo.y - 0.5f) break;
        const glm::vec3 n = scene.triangles[size_t(hit.triangle)].geometricNormal();
        if (n.y < 0.7f) continue;  // a wall, a ceiling or a steep slope
        if (region.triangleCell && (*region.triangleCell)[size_t(hit.triangle)] != region.cell) continue;
        if (const std::optional<Spot> spot = standAt(rays, scene, region, floor, axis, extent))
          if (spot->score > best.score) best = *spot;
      }
    }
  if (best.score == -kFar) return std::nullopt;
  return lookAlong(region.name, best.eye, best.direction);
}

/// The old rule, for a region where no floor has room for an eye (a cell with no upward surface): from
/// near one lower corner of its bounds towards the opposite one.
Camera cornerView(const std::string& name, const Bounds& b) {
  const glm::vec3 size = b.size();
  const float eyeHeight = std::min(kEyeHeight, 0.55f * size.y);
  const glm::vec3 eye(b.lo.x + 0.15f * size.x, b.lo.y + eyeHeight, b.lo.z + 0.15f * size.z);
  const glm::vec3 target(b.hi.x - 0.1f * size.x, b.lo.y + 0.4f * size.y, b.hi.z - 0.1f * size.z);
  return lookAt(name, eye, target);
}

}  // namespace

std::vector<Camera> defaultCameras(const RayScene& rays, const Scene& scene, const CellGraph& cells) {
  const std::vector<int> triangleCell = cells.cellOfTriangle(scene.triangles.size());
  // One camera per room, placed side by side (a building of a hundred rooms spent a quarter of a second
  // here on one core): each is placed by rays alone, and they are kept in the cells' order.
  std::vector<std::optional<Camera>> placed(cells.cells.size());
  tbb::parallel_for(size_t(0), cells.cells.size(), [&](size_t c) {
    const Cell& cell = cells.cells[c];
    if (cell.name == "outside") return;  // the rooms are what a bake of an interior is for
    Region region{.name = cell.name, .bounds = {}, .triangleCell = &triangleCell, .cell = int(c)};
    // The cell's own volume bounds its empty space exactly; its surfaces' bounds include wall thickness.
    for (const Triangle& t : cell.volume)
      for (const glm::vec3& p : t.p) region.bounds.extend(p);
    if (region.bounds.empty())
      for (uint32_t t : cell.triangles)
        if (t < scene.triangles.size())
          for (const glm::vec3& p : scene.triangles[t].p) region.bounds.extend(p);
    if (region.bounds.empty()) return;
    const std::optional<Camera> cam = placeCamera(rays, scene, region);
    placed[c] = cam ? *cam : cornerView(cell.name, region.bounds);
  });
  std::vector<Camera> cameras;
  for (std::optional<Camera>& cam : placed)
    if (cam) cameras.push_back(std::move(*cam));
  if (!cameras.empty()) return cameras;

  Region whole{.name = "overview",
               .bounds = scene.bounds(),
               .triangleCell = nullptr,
               .cell = -1,
               .preferRoofed = true};
  if (whole.bounds.empty()) return cameras;
  const std::optional<Camera> cam = placeCamera(rays, scene, whole);
  cameras.push_back(cam ? *cam : cornerView(whole.name, whole.bounds));
  return cameras;
}

}  // namespace cpgi
