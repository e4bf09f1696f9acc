#include "decomposition/picture.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace cpgi::decomp {
namespace {

const glm::vec3 kWall(0.08f), kOutside(1.0f), kVoid(0.3f), kPortalEdge(0.0f), kPortalCore(1.0f, 0.02f, 0.02f);

// One view: `across` and `up` are the grid axes shown left→right and top→bottom; `depth` is summed over.
struct View {
  int across, down, depth;
  bool flipDown;  // elevation: y grows up the page
};

void drawView(const Decomposition& d, const View& v, int scale, int top, ImageRGB& img) {
  const GridFrame& f = d.frame;
  std::unordered_map<int, int> counts;
  for (int a = 0; a < f.dims[v.across]; ++a)
    for (int b = 0; b < f.dims[v.down]; ++b) {
      counts.clear();
      bool solid = false, voidSpace = false;
      int outside = 0, solidCount = 0;
      for (int k = 0; k < f.dims[v.depth]; ++k) {
        glm::ivec3 c;
        c[v.across] = a, c[v.down] = b, c[v.depth] = k;
        const size_t i = f.index(c);
        const int cell = d.voxelCell[i];
        // The outside cell of a building is drawn white like unlabelled outside space, below its rooms.
        if (d.enclosed && cell >= 0 && cell == d.outsideCell)
          ++outside;
        else if (cell >= 0 && (d.enclosed || d.space[i] == Space::Outside))
          ++counts[cell];
        solid |= d.space[i] == Space::Solid;
        solidCount += d.space[i] == Space::Solid;
        voidSpace |= d.space[i] == Space::Void;
      }
      // Where the outside outweighs the solid (the ground around a house, not its walls) it shows white.
      const bool open = outside > solidCount;
      glm::vec3 colour = solid && !open ? kWall : voidSpace && !open ? kVoid : kOutside;
      int best = 0;
      for (const auto& [cell, n] : counts)
        if (n > best) best = n, colour = cellColour(cell);
      if (!d.enclosed && solid) colour = kWall;  // an open scene: show its geometry over the one cell
      const int row = v.flipDown ? f.dims[v.down] - 1 - b : b;
      for (int py = 0; py < scale; ++py)
        for (int px = 0; px < scale; ++px) img.at(a * scale + px, top + row * scale + py) = colour;
    }
}

void disk(ImageRGB& img, int cx, int cy, int r, glm::vec3 colour, int top, int bottom) {
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x)
      if (x >= 0 && x < img.width && y >= top && y < bottom && (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
        img.at(x, y) = colour;
}

void line(ImageRGB& img, glm::vec2 a, glm::vec2 b, int r, glm::vec3 colour, int top, int bottom) {
  const int steps = std::max(1, int(std::ceil(glm::length(b - a))));
  for (int s = 0; s <= steps; ++s) {
    const glm::vec2 p = glm::mix(a, b, float(s) / float(steps));
    disk(img, int(std::lround(p.x)), int(std::lround(p.y)), r, colour, top, bottom);
  }
}

void drawPortals(const Decomposition& d, const View& v, int scale, int top, ImageRGB& img) {
  const GridFrame& f = d.frame;
  const int bottom = top + f.dims[v.down] * scale;
  auto toPixel = [&](const glm::vec3& p) {
    const glm::dvec3 q = (glm::dvec3(p) - f.origin) / f.voxel + 0.5;  // voxel units, cube corners at integers
    double down = q[v.down];
    if (v.flipDown) down = f.dims[v.down] - down;
    return glm::vec2(float(q[v.across] * scale), float(top + down * scale));
  };
  const int thick = std::max(1, scale / 2 + 1);
  for (int pass = 0; pass < 2; ++pass)
    for (const PortalQuad& q : d.graph.portals)
      for (int e = 0; e < 4; ++e)
        line(img, toPixel(q.corners[size_t(e)]), toPixel(q.corners[size_t((e + 1) % 4)]),
             pass == 0 ? thick + 1 : std::max(0, thick - 1), pass == 0 ? kPortalEdge : kPortalCore, top, bottom);
}

}  // namespace

glm::vec3 cellColour(int c) {
  const float hue = std::fmod(0.11f + 0.61803398875f * float(c), 1.0f);
  // HSV with s = 0.55, v = 0.95, to linear (approximately: square the sRGB-ish value).
  const float s = 0.55f, val = 0.95f;
  const float hh = hue * 6.0f;
  const int sector = int(hh) % 6;
  const float frac = hh - std::floor(hh);
  const float p = val * (1 - s), q = val * (1 - s * frac), t = val * (1 - s * (1 - frac));
  glm::vec3 rgb;
  switch (sector) {
    case 0: rgb = {val, t, p}; break;
    case 1: rgb = {q, val, p}; break;
    case 2: rgb = {p, val, t}; break;
    case 3: rgb = {p, q, val}; break;
    case 4: rgb = {t, p, val}; break;
    default: rgb = {val, p, q}; break;
  }
  return rgb * rgb;
}

ImageRGB drawDecomposition(const Decomposition& d, const PictureParams& params) {
  const GridFrame& f = d.frame;
  const int longest = std::max(f.dims.x, f.dims.z);
  const int scale = std::max(1, params.targetWidth / std::max(1, longest));
  const View plan{0, 2, 1, false}, elevation{0, 1, 2, true};
  const int gap = 8;
  ImageRGB img;
  img.width = f.dims.x * scale;
  img.height = (f.dims.z + f.dims.y) * scale + gap;
  img.pixels.assign(size_t(img.width) * size_t(img.height), glm::vec3(0.6f));
  drawView(d, plan, scale, 0, img);
  drawPortals(d, plan, scale, 0, img);
  const int top = f.dims.z * scale + gap;
  drawView(d, elevation, scale, top, img);
  drawPortals(d, elevation, scale, top, img);
  return img;
}

}  // namespace cpgi::decomp
