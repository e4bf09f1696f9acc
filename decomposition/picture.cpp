#include "decomposition/picture.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace cpgi::decomp {
namespace {

const glm::vec3 kWall(0.08f), kOutside(1.0f), kVoid(0.3f), kPortalEdge(0.0f), kPortalCore(1.0f, 0.02f, 0.02f);

// Where the picture cuts: one horizontal section per storey, `kSectionHeight` above its floor (through
// doors and windows, under the lamps), so an upper floor never hides the one below.
constexpr double kSectionHeight = 1.2;  ///< metres above a storey's floor
constexpr double kStoreyGap = 1.5;      ///< metres between two cells' floors that make two storeys
constexpr int kElevationSamples = 96;   ///< voxels sampled along each elevation column, at most
constexpr int kTextPixel = 3;           ///< picture pixels a font pixel of the names and the scale bar
constexpr size_t kMaxLabel = 18;        ///< characters of a cell's name shown, at most

// A 3 × 5 pixel font for the picture's names and numbers (capitals; lower case drawn as capitals),
// each glyph five rows of three, '#' lit.
struct Glyph {
  char c;
  const char* rows;  ///< 15 characters, row by row from the top
};
constexpr Glyph kFont[] = {
    {'0', "####.##.##.####"}, {'1', ".#.##..#..#.###"}, {'2', "###..#####..###"}, {'3', "###..#.##..####"},
    {'4', "#.##.####..#..#"}, {'5', "####..###..####"}, {'6', "####..####.####"}, {'7', "###..#.#..#..#."},
    {'8', "####.#####.####"}, {'9', "####.####..####"}, {'A', ".#.#.####.##.#."}, {'B', "##.#.###.#.###."},
    {'C', ".###..#..#...##"}, {'D', "##.#.##.##.###."}, {'E', "####..##.#..###"}, {'F', "####..##.#..#.."},
    {'G', ".###..#.##.#.##"}, {'H', "#.##.####.##.##"}, {'I', "###.#..#..#.###"}, {'J', "..#..#..##.#.#."},
    {'K', "#.##.###.#.##.#"}, {'L', "#..#..#..#..###"}, {'M', "#.#######.##.##"}, {'N', "##.#.##.##.##.#"},
    {'O', ".#.#.##.##.#.#."}, {'P', "##.#.###.#..#.."}, {'Q', ".#.#.##.###..##"}, {'R', "##.#.###.#.##.#"},
    {'S', ".###...#...###."}, {'T', "###.#..#..#..#."}, {'U', "#.##.##.##.####"}, {'V', "#.##.##.##.#.#."},
    {'W', "#.##.#######.##"}, {'X', "#.##.#.#.#.##.#"}, {'Y', "#.##.#.#..#..#."}, {'Z', "###..#.#.#..###"},
    {'-', "......###......"}, {'.', ".............#."}, {'_', "............###"}, {':', "....#.....#...."},
    {'/', "..#..#.#.#..#.."}, {' ', "..............."}, {'?', "###..#.#.....#."},
};
constexpr int kGlyphWidth = 3, kGlyphHeight = 5;
constexpr bool everyGlyphWhole() {
  for (const Glyph& g : kFont)
    if (std::char_traits<char>::length(g.rows) != size_t(kGlyphWidth * kGlyphHeight)) return false;
  return true;
}
static_assert(everyGlyphWhole(), "a glyph of kFont is not 3 x 5");

const char* glyphRows(char c) {
  const char upper = char(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == upper) return g.rows;
  return glyphRows('?');
}

/// Text `px` pixels a font pixel, in `ink` on a box of `paper` one font pixel wider all round, its top left
/// at (x, y); clipped to [left, right) × [top, bottom).
struct TextBox {
  int left, top, right, bottom;
};
glm::ivec2 textSize(const std::string& text, int px) {
  return {(int(text.size()) * (kGlyphWidth + 1) + 1) * px, (kGlyphHeight + 2) * px};
}
void drawText(ImageRGB& img, glm::ivec2 at, const std::string& text, int px, glm::vec3 ink, glm::vec3 paper,
              const TextBox& clip) {
  const glm::ivec2 size = textSize(text, px);
  auto put = [&](int x, int y, glm::vec3 colour) {
    if (x >= clip.left && x < clip.right && y >= clip.top && y < clip.bottom) img.at(x, y) = colour;
  };
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) put(at.x + x, at.y + y, paper);
  for (size_t i = 0; i < text.size(); ++i) {
    const char* rows = glyphRows(text[i]);
    for (int r = 0; r < kGlyphHeight; ++r)
      for (int c = 0; c < kGlyphWidth; ++c)
        if (rows[r * kGlyphWidth + c] == '#')
          for (int y = 0; y < px; ++y)
            for (int x = 0; x < px; ++x)
              put(at.x + (int(i) * (kGlyphWidth + 1) + 1 + c) * px + x, at.y + (1 + r) * px + y, ink);
  }
}

/// The voxel layer of each storey's section: the cells' floors (the bottom of their empty voxels)
/// clustered by height, the outside left out; one layer at mid-height when there is no room.
std::vector<int> sectionLayers(const Decomposition& d) {
  const GridFrame& f = d.frame;
  std::vector<double> floors;
  for (size_t c = 0; c < d.cellStats.size(); ++c)
    if (int(c) != d.outsideCell && d.cellStats[c].voxels > 0 && d.enclosed)
      floors.push_back(d.cellStats[c].bounds.lo.y);
  std::sort(floors.begin(), floors.end());
  std::vector<int> layers;
  for (size_t k = 0; k < floors.size(); ++k) {
    if (k > 0 && floors[k] - floors[k - 1] < kStoreyGap) continue;  // one storey begins at its lowest floor
    const glm::ivec3 v = f.voxelOf(glm::vec3(0.0f, float(floors[k] + kSectionHeight), 0.0f));
    const int layer = std::clamp(v.y, 0, f.dims.y - 1);
    if (layers.empty() || layers.back() != layer) layers.push_back(layer);
  }
  if (layers.empty()) layers.push_back(f.dims.y / 2);
  return layers;
}

/// What one voxel shows: its cell's colour, walls dark, outside white, void (inside closed solids) grey.
/// The outside cell of a building is drawn white like unlabelled outside space; in an open scene (the
/// outside its only cell) the geometry shows over it.
glm::vec3 voxelColour(const Decomposition& d, size_t i) {
  const int cell = d.voxelCell[i];
  const Space space = d.space[i];
  if (space == Space::Solid) return kWall;
  if (cell >= 0 && !(d.enclosed && cell == d.outsideCell)) return cellColour(cell);
  return space == Space::Void ? kVoid : kOutside;
}

// A plan section: x to the right, z down the page, the voxel layer `y`.
void drawSection(const Decomposition& d, int y, int scale, glm::ivec2 corner, ImageRGB& img) {
  const GridFrame& f = d.frame;
  for (int z = 0; z < f.dims.z; ++z)
    for (int x = 0; x < f.dims.x; ++x) {
      const glm::vec3 colour = voxelColour(d, f.index(x, y, z));
      for (int py = 0; py < scale; ++py)
        for (int px = 0; px < scale; ++px)
          img.at(corner.x + x * scale + px, corner.y + z * scale + py) = colour;
    }
}

// The elevation: looking along −z, y up; each pixel the cell most of up to kElevationSamples voxels along
// its depth belong to (a sample, so that its cost does not grow with the depth of a large grid), solid
// where there is no cell in the column.
void drawElevation(const Decomposition& d, int scale, glm::ivec2 corner, ImageRGB& img) {
  const GridFrame& f = d.frame;
  const int step = std::max(1, f.dims.z / kElevationSamples);
  std::vector<int> counts(d.graph.cells.size() + 1, 0);
  std::vector<int> touched;
  for (int y = 0; y < f.dims.y; ++y)
    for (int x = 0; x < f.dims.x; ++x) {
      int outside = 0, solid = 0;
      bool voidSpace = false;
      for (int z = 0; z < f.dims.z; z += step) {
        const size_t i = f.index(x, y, z);
        const int cell = d.voxelCell[i];
        if (d.enclosed && cell >= 0 && cell == d.outsideCell)
          ++outside;
        else if (cell >= 0 && size_t(cell) < counts.size() && (d.enclosed || d.space[i] == Space::Outside)) {
          if (counts[size_t(cell)]++ == 0) touched.push_back(cell);
        }
        solid += d.space[i] == Space::Solid;
        voidSpace |= d.space[i] == Space::Void;
      }
      // Where the outside outweighs the solid (the ground around a house, not its walls) it shows white.
      const bool open = outside > solid;
      glm::vec3 colour = solid > 0 && !open ? kWall : voidSpace && !open ? kVoid : kOutside;
      int best = 0;
      for (int c : touched) {
        if (counts[size_t(c)] > best) best = counts[size_t(c)], colour = cellColour(c);
        counts[size_t(c)] = 0;
      }
      touched.clear();
      if (!d.enclosed && solid > 0) colour = kWall;  // an open scene: show its geometry over the one cell
      const int row = f.dims.y - 1 - y;
      for (int py = 0; py < scale; ++py)
        for (int px = 0; px < scale; ++px)
          img.at(corner.x + x * scale + px, corner.y + row * scale + py) = colour;
    }
}

void disk(ImageRGB& img, int cx, int cy, int r, glm::vec3 colour, int top, int bottom) {
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x)
      if (x >= 0 && x < img.width && y >= top && y < bottom &&
          (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
        img.at(x, y) = colour;
}

void line(ImageRGB& img, glm::vec2 a, glm::vec2 b, int r, glm::vec3 colour, int top, int bottom) {
  const int steps = std::max(1, int(std::ceil(glm::length(b - a))));
  for (int s = 0; s <= steps; ++s) {
    const glm::vec2 p = glm::mix(a, b, float(s) / float(steps));
    disk(img, int(std::lround(p.x)), int(std::lround(p.y)), r, colour, top, bottom);
  }
}

/// Draws the portals as black lines with a red core; `across` and `down` are the grid axes shown, `flip`
/// puts the down axis up the page. `keep` chooses the portals of this panel.
template <typename Keep>
void drawPortals(const Decomposition& d, int across, int down, bool flip, int scale, glm::ivec2 corner,
                 ImageRGB& img, Keep keep) {
  const GridFrame& f = d.frame;
  const int top = corner.y, bottom = corner.y + f.dims[down] * scale;
  auto toPixel = [&](const glm::vec3& p) {
    const glm::dvec3 q = (glm::dvec3(p) - f.origin) / f.voxel + 0.5;  // voxel units, cube corners at integers
    double row = q[down];
    if (flip) row = f.dims[down] - row;
    return glm::vec2(float(corner.x + q[across] * scale), float(top + row * scale));
  };
  const int thick = std::max(1, scale / 2 + 1);
  for (int pass = 0; pass < 2; ++pass)
    for (const PortalQuad& q : d.graph.portals)
      if (keep(q))
        for (int e = 0; e < 4; ++e)
          line(img, toPixel(q.corners[size_t(e)]), toPixel(q.corners[size_t((e + 1) % 4)]),
               pass == 0 ? thick + 1 : std::max(0, thick - 1), pass == 0 ? kPortalEdge : kPortalCore, top,
               bottom);
}

/// Each cell's name over the section layer `y`, on the cell's voxel nearest the middle of its voxels
/// there; cells with under a square metre in the layer get none, and so does a building's outside (white).
void labelSection(const Decomposition& d, int y, int scale, glm::ivec2 corner, ImageRGB& img) {
  const GridFrame& f = d.frame;
  struct Spot {
    glm::dvec2 sum{0.0};
    int voxels = 0;
    glm::ivec2 best{-1};
    double bestDistance = 1e300;
  };
  std::vector<Spot> spots(d.graph.cells.size());
  auto cellAt = [&](int x, int z) {
    const int cell = d.voxelCell[f.index(x, y, z)];
    const bool shown = cell >= 0 && size_t(cell) < spots.size() && !(d.enclosed && cell == d.outsideCell);
    return shown ? cell : -1;
  };
  for (int z = 0; z < f.dims.z; ++z)
    for (int x = 0; x < f.dims.x; ++x)
      if (const int cell = cellAt(x, z); cell >= 0)
        spots[size_t(cell)].sum += glm::dvec2(x, z), ++spots[size_t(cell)].voxels;
  for (int z = 0; z < f.dims.z; ++z)
    for (int x = 0; x < f.dims.x; ++x)
      if (const int cell = cellAt(x, z); cell >= 0) {
        Spot& s = spots[size_t(cell)];
        const double distance = glm::length(glm::dvec2(x, z) - s.sum / double(s.voxels));
        if (distance < s.bestDistance) s.bestDistance = distance, s.best = {x, z};
      }
  const TextBox clip{corner.x, corner.y, corner.x + f.dims.x * scale, corner.y + f.dims.z * scale};
  const int minVoxels = std::max(1, int(std::ceil(1.0 / (f.voxel * f.voxel))));
  for (size_t c = 0; c < spots.size(); ++c) {
    if (spots[c].voxels < minVoxels) continue;
    const std::string name = d.graph.cells[c].name.substr(0, kMaxLabel);
    const glm::ivec2 size = textSize(name, kTextPixel);
    const glm::ivec2 centre = corner + spots[c].best * scale + scale / 2;
    const glm::ivec2 at =
        glm::clamp(centre - size / 2, glm::ivec2(clip.left, clip.top),
                   glm::max(glm::ivec2(clip.left, clip.top), glm::ivec2(clip.right, clip.bottom) - size));
    drawText(img, at, name, kTextPixel, kWall, glm::vec3(0.92f), clip);
  }
}

/// A bar of a round length (1, 2 or 5 × 10^k metres, about a fifth of the panel) in the panel's bottom
/// left corner, its length written beside it.
void drawScaleBar(ImageRGB& img, double voxel, int scale, const TextBox& panel) {
  const double pixelsPerMetre = double(scale) / voxel;
  const double wanted = double(panel.right - panel.left) / 5.0 / pixelsPerMetre;
  const double base = std::pow(10.0, std::floor(std::log10(std::max(wanted, 1e-3))));
  const double metres = 5.0 * base <= wanted ? 5.0 * base : 2.0 * base <= wanted ? 2.0 * base : base;
  const int length = int(std::lround(metres * pixelsPerMetre));
  char text[32];
  std::snprintf(text, sizeof text, metres >= 1.0 ? "%.0f m" : "%.1f m", metres);
  const glm::ivec2 label = textSize(text, kTextPixel);
  const int height = label.y, x0 = panel.left + 6, y0 = panel.bottom - 6 - height;
  if (x0 + length + label.x + 6 > panel.right || y0 < panel.top) return;  // no room in a tiny panel
  for (int y = y0; y < y0 + height; ++y)
    for (int x = x0; x < x0 + length + 4; ++x) img.at(x, y) = glm::vec3(0.92f);
  for (int y = y0 + height / 2 - 2; y < y0 + height / 2 + 2; ++y)
    for (int x = x0 + 2; x < x0 + 2 + length; ++x) img.at(x, y) = kWall;
  for (int y = y0 + 2; y < y0 + height - 2; ++y)  // the ends
    for (const int x : {x0 + 2, x0 + 1 + length}) img.at(x, y) = kWall;
  drawText(img, {x0 + length + 4, y0}, text, kTextPixel, kWall, glm::vec3(0.92f), panel);
}

}  // namespace

ImageRGB drawDecomposition(const Decomposition& d, const PictureParams& params) {
  const GridFrame& f = d.frame;
  const int longest = std::max(f.dims.x, f.dims.z);
  const int scale = std::max(1, params.targetWidth / std::max(1, longest));
  const std::vector<int> layers = sectionLayers(d);
  // One row: a plan per storey, then the elevation (no panel left empty below a row of plans).
  const int gap = 8, panel = f.dims.x * scale, n = int(layers.size());
  ImageRGB img;
  img.width = (n + 1) * panel + n * gap;
  img.height = std::max(f.dims.z, f.dims.y) * scale;
  img.pixels.assign(size_t(img.width) * size_t(img.height), glm::vec3(0.6f));
  for (int k = 0; k < n; ++k) {
    const glm::ivec2 corner(k * (panel + gap), 0);
    drawSection(d, layers[size_t(k)], scale, corner, img);
    // A door or window crossing the section; a hole in a floor (a stair) in the storey above it.
    const double y = f.origin.y + f.voxel * layers[size_t(k)];
    const double below = k > 0 ? f.origin.y + f.voxel * layers[size_t(k - 1)] : -1e30;
    drawPortals(d, 0, 2, false, scale, corner, img, [&](const PortalQuad& q) {
      float lo = q.corners[0].y, hi = lo;
      for (const glm::vec3& c : q.corners) lo = std::min(lo, c.y), hi = std::max(hi, c.y);
      if (std::abs(q.normal.y) > 0.7f) return q.centre().y < y && q.centre().y >= below;
      return lo <= y && hi >= y;
    });
    labelSection(d, layers[size_t(k)], scale, corner, img);
    const TextBox box{corner.x, 0, corner.x + panel, f.dims.z * scale};
    drawText(img, {corner.x + 4, 4}, "storey " + std::to_string(k + 1), kTextPixel, glm::vec3(1.0f), kWall,
             box);
    drawScaleBar(img, f.voxel, scale, box);
  }
  const glm::ivec2 elevation(n * (panel + gap), 0);
  drawElevation(d, scale, elevation, img);
  drawPortals(d, 0, 1, true, scale, elevation, img, [](const PortalQuad&) { return true; });
  const TextBox box{elevation.x, 0, elevation.x + panel, f.dims.y * scale};
  drawText(img, {elevation.x + 4, 4}, "elevation", kTextPixel, glm::vec3(1.0f), kWall, box);
  drawScaleBar(img, f.voxel, scale, box);
  return img;
}

}  // namespace cpgi::decomp
