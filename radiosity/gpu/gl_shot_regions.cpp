// The GL engine's visibility regions (gl_shot_backend.h): how each shooter is cut into regions, one eye
// (item buffer) each, for the weak and the strong shots; and the region table with its residual pyramids'
// levels that the shot's compute passes read (shaders/common.glsl, Region).
#include <algorithm>

#include "radiosity/gpu/gl_shot_backend.h"

namespace cpgi::gl_engine {

// The region table (common.glsl, Region) of one shooter; fills levelNodes_ (nodes per level over all
// regions) and returns the highest level.
int GlShotBackend::uploadRegions(const ShooterLayout& l, const Patch& p, int replicas) {
  std::vector<GpuRegion> table(l.rects.size());
  int levels = 1;
  for (size_t r = 0; r < table.size(); ++r) {
    const glm::ivec4 c = l.rects[r];
    table[r].rect = glm::ivec4(p.x + c.x, p.y + c.y, p.x + c.z, p.y + c.w);
    table[r].top.x = topLevel(glm::ivec2(c.z - c.x, c.w - c.y));
    levels = std::max(levels, table[r].top.x);
  }
  int32_t offset = 0;
  std::fill(levelNodes_.begin(), levelNodes_.end(), 0);
  for (int k = 1; k <= levels; ++k)
    for (GpuRegion& g : table) {
      if (k > g.top.x) continue;
      const glm::ivec2 d = levelDims(glm::ivec2(g.rect.z - g.rect.x, g.rect.w - g.rect.y), k);
      g.levelOffset[k] = offset;
      offset += d.x * d.y;
      levelNodes_[k] += size_t(d.x) * d.y;
    }
  // Replica i of region r is entry i × regions + r, with r's rectangle and pyramid.
  const size_t base = table.size();
  for (int i = 1; i < replicas; ++i)
    for (size_t r = 0; r < base; ++r) table.push_back(table[r]);
  glNamedBufferSubData(regions_.get(), 0, GLsizeiptr(table.size() * sizeof(GpuRegion)), table.data());
  topNode_.clear();
  for (const GpuRegion& g : table) topNode_.push_back(g.levelOffset[g.top.x]);
  return levels;
}

glm::ivec2 GlShotBackend::levelDims(glm::ivec2 size, int k) {
  return (size + ((1 << k) - 1)) >> k;
}

int GlShotBackend::topLevel(glm::ivec2 size) {
  int k = 1;
  while (glm::any(glm::greaterThan(levelDims(size, k), glm::ivec2(1)))) ++k;
  return k;
}

// Nodes the largest shooter's pyramids need (levels 1 and up, all regions); of the patches flagged in
// `only` when given.
size_t GlShotBackend::maxPyramidNodes(const std::vector<uint8_t>* only) const {
  size_t most = 0;
  const std::vector<ShooterLayout> all = allLayouts();
  for (size_t i = 0; i < all.size(); ++i) {
    if (only && !(*only)[i % layouts_.size()]) continue;
    const ShooterLayout& l = all[i];
    size_t n = 0;
    for (const glm::ivec4& c : l.rects) {
      const glm::ivec2 size(c.z - c.x, c.w - c.y);
      for (int k = 1, top = topLevel(size); k <= top; ++k)
        n += size_t(levelDims(size, k).x) * levelDims(size, k).y;
    }
    most = std::max(most, n);
  }
  return std::max<size_t>(most, 1);
}

// The weak shots' regions: half the settings' size, twice their count per edge (within kMaxRegions). A
// region's eye decides for the whole region whether a receiver sees it, and gives it the region's whole
// unoccluded light. A receiver behind a door sees only a ceiling's or a wall's far part through it (the
// wall above the door hides the near part), where the form factor is smallest, so the region's whole
// light overstates what passes: a 4 m × 3 m ceiling shooting into the room behind a door delivered
// 1.057 of the exact transfer at 2 × 2 regions, 1.004 at 4 × 4 (DoorTransfer), and plan 4's rooms
// behind three and four doors came out +12 % and +22 %. The rays engine gates a receiver near a region
// piece by piece instead (ray_shot.cpp, nearRays), which item buffers cannot.
LayoutParams GlShotBackend::weakLayout() const {
  return LayoutParams{0.5f * params_.regionSize, std::min(2 * params_.maxRegions, kMaxRegions)};
}

std::vector<ShooterLayout> GlShotBackend::allLayouts() const {
  std::vector<ShooterLayout> all = layouts_;
  all.insert(all.end(), strongLayouts_.begin(), strongLayouts_.end());
  all.insert(all.end(), strongReflectorLayouts_.begin(), strongReflectorLayouts_.end());
  return all;
}

// Strong shots at strongShotRegions per edge whatever the shooter's size (within its texels): a small lamp
// still gets several eyes, so with drawn eyes (jitteredEyes) its light through a narrow door, or out of a
// housing, is a stratified estimate rather than one texel's view. Where the settings ask for as many as
// --regions, the settings' own layout.
LayoutParams GlShotBackend::strongLayout() const {
  return strongRegions() != params_.maxRegions ? LayoutParams{1e-3f, strongRegions()}
                                               : LayoutParams{params_.regionSize, params_.maxRegions};
}

// A reflector's strong shot: as the weak shots, half the settings' region size at twice their count per
// edge (up to kMaxStrongRegions), where that gives more regions than strongLayout. Such a shot carries a
// lit room's light into its neighbours, and a receiver behind a door sees only part of a region through
// it, the part farthest from the door where the form factor is smallest, yet gets the region's whole
// light from its eye: with strongLayout's 4 per edge of a 5 m floor, plan 4's R2 floor's first shot gave
// R8 1.4x its exact transfer and R2's shots over a solve 1.11x (1.06x and 1.02x at this layout; a
// 6 m x 4.5 m ceiling into the room behind its door 1.040 -> 0.996, DoorTransfer). Lamps keep strongLayout:
// their shots' replicas and edge resampling (receive.comp) are per region.
LayoutParams GlShotBackend::strongReflectorLayout() const {
  return LayoutParams{0.5f * params_.regionSize, std::min(2 * strongRegions(), kMaxStrongRegions)};
}

const ShooterLayout& GlShotBackend::layoutOf(int patch, bool strong, bool lamp) const {
  if (!strong) return layouts_[size_t(patch)];
  return lamp ? strongLayouts_[size_t(patch)] : strongReflectorLayouts_[size_t(patch)];
}

// The most eyes a shot draws: the item buffers' layers. A lamp's strong shot replicates its regions up to
// strongRegions() squared (shootGl).
int GlShotBackend::mostEyes() const {
  int most = strongRegions() * strongRegions();
  for (const ShooterLayout& l : allLayouts()) most = std::max(most, l.regions.x * l.regions.y);
  return std::min(most, kMaxEyes);
}

}  // namespace cpgi::gl_engine
