#include "radiosity/lightmap/atlas.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <span>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/memory_limit.h"
#include "radiosity/lightmap/atlas_size.h"
#include "radiosity/lightmap/quad_grids.h"
#include "radiosity/lightmap/seam_gutters.h"

namespace cpgi {
namespace {

// A chart before packing: the patch it belongs to and its size in texels (without padding).
struct ChartSize {
  int patch;
  int w, h;
};

// Texels along an edge of `length` metres; the small slack keeps 4 m × 10 texel/m at 40, not 41.
int texelsAlong(float length, const AtlasParams& params) {
  const int n = static_cast<int>(std::ceil(length * params.density - 1e-3f));
  return std::clamp(n, params.minTexels, params.maxTexels);
}

std::string sizeOption(const AtlasParams& params) {
  return params.texelsPerQuad > 0 ? "texels per quad" : "texel density";
}

void checkParams(const AtlasParams& params) {
  if (params.texelsPerQuad < 0) throw InputError("texels per quad", "must be positive");
  if (params.texelsPerQuad == 0 && !(params.density > 0.0f && std::isfinite(params.density)))
    throw InputError("texel density", "must be a positive number of texels per metre");
  for (float d : params.triangleDensity)
    if (!(d > 0.0f && std::isfinite(d)))
      throw InputError("texel density", "a chart's density must be positive");
  if (params.minTexels < 1 || params.maxTexels < params.minTexels)
    throw InputError("atlas", "texel limits need 1 <= min <= max");
  if (params.padding < 0) throw InputError("atlas", "padding must not be negative");
  if (params.maxSize < 1) throw InputError("atlas", "maximum size must be positive");
}

// Loose triangles are laid out as the right triangle (0,0), (s,0), (0,s) of an s×s chart. The corner at
// (0,0) is the vertex with the largest angle (opposite the longest edge), which keeps the texels least
// sheared. Returns that vertex.
int triangleOrigin(const Triangle& t) {
  int corner = 0;
  float best = -1.0f;
  for (int i = 0; i < 3; ++i) {
    const float len = glm::length(t.p[(i + 1) % 3] - t.p[(i + 2) % 3]);
    if (len > best) best = len, corner = i;
  }
  return corner;
}

// Chart edge for a loose triangle: at least 2, since an s×s layout has s(s−1)/2 texel centres strictly
// inside the triangle and s = 1 would leave it without a single texel.
int triangleChartSide(const Triangle& t, const AtlasParams& params) {
  int s;
  if (params.texelsPerQuad > 0) {
    s = params.texelsPerQuad;
  } else {
    const int o = triangleOrigin(t);
    const float a = glm::length(t.p[(o + 1) % 3] - t.p[o]);
    const float b = glm::length(t.p[(o + 2) % 3] - t.p[o]);
    s = texelsAlong(std::max(a, b), params);
  }
  return std::max(s, 2);
}

// Shelf packing: charts sorted by height (tallest first), placed left to right on shelves of the width
// chosen below. Returns the atlas size; writes the chart origins into the patches.
glm::ivec2 packShelves(std::vector<ChartSize> charts, std::vector<Patch>& patches,
                       const AtlasParams& params) {
  const int pad = params.padding;
  std::stable_sort(charts.begin(), charts.end(),
                   [](const ChartSize& a, const ChartSize& b) { return a.h != b.h ? a.h > b.h : a.w > b.w; });
  double area = 0.0;
  int widest = 0;
  for (const ChartSize& c : charts) {
    area += double(c.w + 2 * pad) * double(c.h + 2 * pad);
    widest = std::max(widest, c.w + 2 * pad);
  }
  // A little wider than the square root: shelves waste space under their shorter charts.
  const int width = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area * 1.15))));
  int x = 0, y = 0, shelfHeight = 0;
  for (const ChartSize& c : charts) {
    const int cw = c.w + 2 * pad, ch = c.h + 2 * pad;
    if (x + cw > width) y += shelfHeight, x = 0, shelfHeight = 0;
    Patch& p = patches[c.patch];
    p.x = x + pad, p.y = y + pad, p.w = c.w, p.h = c.h;
    x += cw;
    shelfHeight = std::max(shelfHeight, ch);
  }
  return {width, y + shelfHeight};
}

glm::vec2 atlasUV(const LightmapAtlas& atlas, float x, float y) {
  return {x / float(atlas.width), y / float(atlas.height)};
}

void fillQuad(LightmapAtlas& atlas, int patchIndex, const std::array<glm::vec3, 4>& corners,
              const Scene& scene) {
  Patch& p = atlas.patches[patchIndex];
  const Material& m = scene.materials[p.material];
  const glm::vec3 u = corners[1] - corners[0], v = corners[3] - corners[0];
  const float texelArea = p.area / float(p.w * p.h);
  p.origin = corners[0], p.texelU = u / float(p.w), p.texelV = v / float(p.h);
  for (int j = 0; j < p.h; ++j)
    for (int i = 0; i < p.w; ++i) {
      const size_t t = size_t(p.y + j) * atlas.width + (p.x + i);
      atlas.patch[t] = patchIndex;
      atlas.position[t] =
          corners[0] + (float(i) + 0.5f) / float(p.w) * u + (float(j) + 0.5f) / float(p.h) * v;
      atlas.normal[t] = p.normal;
      atlas.albedo[t] = m.albedo;
      atlas.emission[t] = m.emission;
      atlas.area[t] = texelArea;
    }
  // Every triangle corner is a tile corner, so its chart coordinates are whole multiples of a tile's
  // texels: project on the rectangle's edges and round.
  const float uu = glm::dot(u, u), vv = glm::dot(v, v);
  const glm::vec2 tile(float(p.w) / float(p.grid.x), float(p.h) / float(p.grid.y));
  for (int32_t tri : p.triangles) {
    const Triangle& t = scene.triangles[tri];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 d = t.p[k] - corners[0];
      const glm::vec2 at =
          glm::round(glm::vec2(glm::dot(d, u) / uu * float(p.grid.x), glm::dot(d, v) / vv * float(p.grid.y)));
      atlas.triangleUV[tri][k] = atlasUV(atlas, float(p.x) + at.x * tile.x, float(p.y) + at.y * tile.y);
    }
  }
}

void fillTriangle(LightmapAtlas& atlas, int patchIndex, uint32_t tri, const Scene& scene) {
  const Patch& p = atlas.patches[patchIndex];
  const Material& m = scene.materials[p.material];
  const Triangle& t = scene.triangles[tri];
  const int o = triangleOrigin(t);
  const glm::vec3 a = t.p[o], e1 = t.p[(o + 1) % 3] - a, e2 = t.p[(o + 2) % 3] - a;
  const int s = p.w;
  Patch& chart = atlas.patches[patchIndex];
  chart.origin = a, chart.texelU = e1 / float(s), chart.texelV = e2 / float(s);
  // Centre (i+½, j+½)/s is strictly inside when i + j + 1 < s: s(s−1)/2 valid texels.
  const int valid = s * (s - 1) / 2;
  const float texelArea = p.area / float(valid);
  for (int j = 0; j < s; ++j)
    for (int i = 0; i + j + 1 < s; ++i) {
      const size_t k = size_t(p.y + j) * atlas.width + (p.x + i);
      atlas.patch[k] = patchIndex;
      atlas.position[k] = a + (float(i) + 0.5f) / float(s) * e1 + (float(j) + 0.5f) / float(s) * e2;
      atlas.normal[k] = p.normal;
      atlas.albedo[k] = m.albedo;
      atlas.emission[k] = m.emission;
      atlas.area[k] = texelArea;
    }
  atlas.triangleUV[tri][o] = atlasUV(atlas, float(p.x), float(p.y));
  atlas.triangleUV[tri][(o + 1) % 3] = atlasUV(atlas, float(p.x + s), float(p.y));
  atlas.triangleUV[tri][(o + 2) % 3] = atlasUV(atlas, float(p.x), float(p.y + s));
}

// Texels of one tile of a grid along its u and v edges.
glm::ivec2 tileTexels(const QuadGrid& g, const AtlasParams& params) {
  if (params.texelsPerQuad > 0) return glm::ivec2(params.texelsPerQuad);
  return {texelsAlong(glm::length(g.corners[1] - g.corners[0]) / float(g.size.x), params),
          texelsAlong(glm::length(g.corners[3] - g.corners[0]) / float(g.size.y), params)};
}

// Cuts a grid into sub-grids of at most params.mergeTexels texels along each edge.
std::vector<QuadGrid> splitToFit(const QuadGrid& g, const AtlasParams& params) {
  const glm::ivec2 tile = tileTexels(g, params);
  const glm::ivec2 most =
      params.mergeTexels > 0 ? glm::max(glm::ivec2(1), glm::ivec2(params.mergeTexels) / tile) : glm::ivec2(1);
  if (g.size.x <= most.x && g.size.y <= most.y) return {g};
  const glm::vec3 u = (g.corners[1] - g.corners[0]) / float(g.size.x),
                  v = (g.corners[3] - g.corners[0]) / float(g.size.y);
  std::vector<QuadGrid> parts;
  for (int j0 = 0; j0 < g.size.y; j0 += most.y)
    for (int i0 = 0; i0 < g.size.x; i0 += most.x) {
      QuadGrid part;
      part.size = {std::min(most.x, g.size.x - i0), std::min(most.y, g.size.y - j0)};
      for (int j = j0; j < j0 + part.size.y; ++j)
        for (int i = i0; i < i0 + part.size.x; ++i) part.quads.push_back(g.quads[size_t(j) * g.size.x + i]);
      const glm::vec3 o = g.corners[0] + float(i0) * u + float(j0) * v;
      const glm::vec3 pu = float(part.size.x) * u, pv = float(part.size.y) * v;
      part.corners = {o, o + pu, o + pu + pv, o + pv};
      parts.push_back(std::move(part));
    }
  return parts;
}

// The params of one chart: `density` the largest of its triangles' when they have their own.
AtlasParams chartParams(const AtlasParams& params, std::span<const int32_t> triangles) {
  AtlasParams p = params;
  p.triangleDensity.clear();
  if (params.texelsPerQuad > 0 || params.triangleDensity.empty()) return p;
  float most = 0.0f;
  for (int32_t t : triangles) most = std::max(most, params.triangleDensity[size_t(t)]);
  if (most > 0.0f) p.density = most;
  return p;
}

}  // namespace

int32_t texelTriangle(const Patch& p, int i, int j) {
  if (p.triangles.empty()) return -1;
  if (p.quads.size() <= 1) return p.triangles[0];
  const int gx = std::max(p.grid.x, 1), gy = std::max(p.grid.y, 1);
  const size_t q =
      size_t(std::min(j * gy / p.h, gy - 1)) * size_t(gx) + size_t(std::min(i * gx / p.w, gx - 1));
  return 2 * q < p.triangles.size() ? p.triangles[2 * q] : p.triangles[0];
}

size_t LightmapAtlas::validTexels() const {
  return static_cast<size_t>(std::count_if(patch.begin(), patch.end(), [](int32_t p) { return p >= 0; }));
}

namespace {

// The triangles to chart: `subset` (sorted, without repeats) or every scene triangle.
std::vector<uint32_t> chosenTriangles(const std::vector<uint32_t>& subset, size_t triangleCount) {
  std::vector<uint32_t> chosen = subset;
  if (chosen.empty()) {
    chosen.resize(triangleCount);
    std::iota(chosen.begin(), chosen.end(), 0u);
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  for (uint32_t t : chosen)
    if (t >= triangleCount)
      throw InputError("atlas", "triangle subset refers to a triangle past the scene's end");
  return chosen;
}

// Charts are capped at maxTexels per edge: a density beyond what the longest edge can take there gets
// fewer texels per metre on the largest patches (--density 1e9 was clamped silently). Said when they get
// less than half of it.
void warnCappedDensity(const Scene& scene, const std::vector<uint32_t>& chosen, const AtlasParams& params,
                       Context& ctx) {
  if (params.texelsPerQuad != 0) return;
  float longest = 0.0f;
  for (uint32_t t : chosen)
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, glm::length(scene.triangles[t].p[(i + 1) % 3] - scene.triangles[t].p[i]));
  float density = params.density;
  for (float d : params.triangleDensity) density = std::max(density, d);
  const double wanted = std::ceil(double(longest) * density - 1e-3);
  if (wanted > 2.0 * params.maxTexels) {
    std::ostringstream s;
    s << "atlas: --density " << density << " asks for " << wanted << " texels along a " << longest
      << " m edge; charts are capped at " << params.maxTexels
      << " texels per edge, so the largest patches get fewer texels per metre";
    ctx.warn(s.str());
  }
}

// The atlas's patches before packing: whole quads as grids (a grid's chart placed where its first quad's
// triangle comes), every other triangle a chart of its own.
struct ChartLayout {
  std::vector<Patch> patches;
  std::vector<ChartSize> charts;
  std::vector<std::array<glm::vec3, 4>> corners;  // per patch (unused for loose triangles)
  size_t degenerate = 0;                          // zero-area triangles left out
};

// The quad grids of the chosen whole quads: quads at different densities are different grids (the float's
// bits: densities are compared exactly).
std::vector<QuadGrid> chosenGrids(const Scene& scene, const QuadSet& quads, const AtlasParams& params,
                                  const std::vector<char>& wholeQuad) {
  int maxQuads = 1;
  if (params.mergeTexels > 0)
    maxQuads = std::max(
        1, params.mergeTexels / (params.texelsPerQuad > 0 ? params.texelsPerQuad : params.minTexels));
  std::vector<uint32_t> densityGroup;
  if (params.texelsPerQuad == 0 && !params.triangleDensity.empty()) {
    densityGroup.resize(quads.quads.size());
    for (size_t qi = 0; qi < quads.quads.size(); ++qi) {
      const auto& qt = quads.quads[qi].triangles;
      densityGroup[qi] =
          std::bit_cast<uint32_t>(std::max(params.triangleDensity[qt[0]], params.triangleDensity[qt[1]]));
    }
  }
  return findQuadGrids(quads, wholeQuad, scene, maxQuads, densityGroup.empty() ? nullptr : &densityGroup);
}

// One chart per piece of `grid` that fits a chart (splitToFit).
void chartGrid(const QuadSet& quads, const QuadGrid& grid, const AtlasParams& params, const Patch& base,
               std::vector<char>& quadDone, ChartLayout& out) {
  std::vector<int32_t> gridTriangles;
  for (uint32_t q : grid.quads)
    for (uint32_t qt : quads.quads[q].triangles) gridTriangles.push_back(int32_t(qt));
  const AtlasParams gridParams = chartParams(params, gridTriangles);
  for (const QuadGrid& g : splitToFit(grid, gridParams)) {
    Patch gp = base;
    gp.quad = int(g.quads.front());
    gp.grid = g.size;
    for (uint32_t q : g.quads) {
      gp.quads.push_back(int32_t(q));
      for (uint32_t qt : quads.quads[q].triangles) gp.triangles.push_back(int32_t(qt));
      quadDone[q] = 1;
    }
    const Quad& first = quads.quads[g.quads.front()];
    gp.normal = first.normal;
    gp.area = first.area() * float(g.quads.size());
    const glm::ivec2 tile = tileTexels(g, gridParams);
    out.charts.push_back({int(out.patches.size()), tile.x * g.size.x, tile.y * g.size.y});
    out.corners.push_back(g.corners);
    out.patches.push_back(std::move(gp));
  }
}

ChartLayout layOutCharts(const Scene& scene, const QuadSet& quads, const AtlasParams& params,
                         const std::vector<uint32_t>& chosen) {
  std::vector<char> inSubset(scene.triangles.size(), 0);
  for (uint32_t t : chosen) inSubset[t] = 1;
  std::vector<char> wholeQuad(quads.quads.size(), 0);
  for (size_t qi = 0; qi < quads.quads.size(); ++qi)
    wholeQuad[qi] = inSubset[quads.quads[qi].triangles[0]] && inSubset[quads.quads[qi].triangles[1]];
  const std::vector<QuadGrid> grids = chosenGrids(scene, quads, params, wholeQuad);
  std::vector<int> gridOfQuad(quads.quads.size(), -1);
  for (size_t g = 0; g < grids.size(); ++g) gridOfQuad[grids[g].quads.front()] = int(g);
  std::vector<char> quadDone(quads.quads.size(), 0);
  ChartLayout out;
  for (uint32_t tri : chosen) {
    const Triangle& t = scene.triangles[tri];
    if (t.material >= scene.materials.size())
      throw InputError("atlas", "triangle refers to a missing material");
    const int32_t qi = tri < quads.quadOfTriangle.size() ? quads.quadOfTriangle[tri] : -1;
    Patch p;
    p.material = t.material;
    if (qi >= 0 && wholeQuad[qi]) {
      if (quadDone[qi]) continue;
      quadDone[qi] = 1;
      if (gridOfQuad[qi] >= 0) chartGrid(quads, grids[gridOfQuad[qi]], params, p, quadDone, out);
      continue;  // else charted when the grid's first quad comes
    }
    if (!(t.area() > 0.0f)) {
      ++out.degenerate;
      continue;
    }
    p.triangles = {int32_t(tri)};
    p.normal = t.geometricNormal();
    p.area = t.area();
    const int32_t only[1] = {int32_t(tri)};
    const int side = triangleChartSide(t, chartParams(params, only));
    out.charts.push_back({int(out.patches.size()), side, side});
    out.corners.push_back({});
    out.patches.push_back(p);
  }
  return out;
}

}  // namespace

AtlasSize measureAtlas(const Scene& scene, const QuadSet& quads, const AtlasParams& params) {
  checkParams(params);
  const size_t triangleCount = scene.triangles.size();
  if (!params.triangleDensity.empty() && params.triangleDensity.size() != triangleCount)
    throw InputError("texel density", "per-triangle densities must be one per scene triangle");
  ChartLayout layout = layOutCharts(scene, quads, params, chosenTriangles({}, triangleCount));
  const glm::ivec2 size = packShelves(layout.charts, layout.patches, params);
  AtlasSize measured{std::max(size.x, 1), std::max(size.y, 1), 0};
  // fillQuad fills a quad chart's every texel, fillTriangle the s(s−1)/2 inside its triangle.
  for (const Patch& p : layout.patches)
    measured.validTexels += p.quad >= 0 ? size_t(p.w) * size_t(p.h) : size_t(p.w) * size_t(p.w - 1) / 2;
  return measured;
}

LightmapAtlas buildAtlas(const Scene& scene, const QuadSet& quads, const AtlasParams& params, Context& ctx,
                         const std::vector<uint32_t>& subset,
                         std::chrono::steady_clock::time_point deadline) {
  const auto started = std::chrono::steady_clock::now();
  checkParams(params);
  const size_t triangleCount = scene.triangles.size();
  if (!params.triangleDensity.empty() && params.triangleDensity.size() != triangleCount)
    throw InputError("texel density", "per-triangle densities must be one per scene triangle");
  const std::vector<uint32_t> chosen = chosenTriangles(subset, triangleCount);
  warnCappedDensity(scene, chosen, params, ctx);
  ChartLayout layout = layOutCharts(scene, quads, params, chosen);
  if (layout.degenerate > 0) {
    // A bake lays its atlas out several times (density pilot, solve, output) on one context: the same
    // triangles are left out each time, and a game map printed the line five times.
    const std::string line =
        "atlas: " + std::to_string(layout.degenerate) + " zero-area triangle(s) left out of the lightmap";
    if (std::find(ctx.warnings().begin(), ctx.warnings().end(), line) == ctx.warnings().end()) ctx.warn(line);
  }

  LightmapAtlas atlas;
  atlas.patches = std::move(layout.patches);
  const glm::ivec2 size = packShelves(layout.charts, atlas.patches, params);
  if (size.x > params.maxSize || size.y > params.maxSize)
    throw InputError(sizeOption(params), "the lightmap atlas would be " + std::to_string(size.x) + "x" +
                                             std::to_string(size.y) + " texels, over the limit of " +
                                             std::to_string(params.maxSize) + "; lower the resolution");
  requireMemory(double(size.x) * double(size.y) * kBakeBytesPerTexel, params.memoryLimit, sizeOption(params),
                "the lightmap atlas of " + std::to_string(size.x) + "x" + std::to_string(size.y) + " texels",
                "lower the resolution or raise `maximum memory`");
  atlas.width = std::max(size.x, 1);
  atlas.height = std::max(size.y, 1);
  atlas.sizeParameter = sizeOption(params);
  atlas.padding = params.padding;
  const size_t n = atlas.texelCount();
  atlas.patch.assign(n, -1);
  atlas.position.assign(n, glm::vec3(0.0f));
  atlas.normal.assign(n, glm::vec3(0.0f));
  atlas.albedo.assign(n, glm::vec3(0.0f));
  atlas.emission.assign(n, glm::vec3(0.0f));
  atlas.area.assign(n, 0.0f);
  atlas.triangleUV.assign(triangleCount, {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)});
  // The clock is read after every chart: at a few per cent of a core a fixed count of texels between
  // looks was tens of seconds.
  const auto fillStart = std::chrono::steady_clock::now();
  const double chartSeconds = std::chrono::duration<double>(fillStart - started).count();
  size_t filled = 0;
  const auto stopped = [&] {
    const double fill = std::chrono::duration<double>(std::chrono::steady_clock::now() - fillStart).count();
    return AtlasLayoutStopped(filled, n, atlas.patches.size(), chartSeconds, fill);
  };
  for (size_t i = 0; i < atlas.patches.size(); ++i) {
    if (std::chrono::steady_clock::now() >= deadline) throw stopped();
    const Patch& p = atlas.patches[i];
    if (p.quad >= 0)
      fillQuad(atlas, int(i), layout.corners[i], scene);
    else
      fillTriangle(atlas, int(i), uint32_t(p.triangles[0]), scene);
    filled += size_t(p.w) * size_t(p.h);
  }
  try {
    atlas.gutter = seamGutters(atlas, scene, params.padding, deadline);
  } catch (const AtlasLayoutStopped&) {
    throw stopped();  // with the fill's figures, the gutters' seconds in its rate
  }
  return atlas;
}

std::vector<float> emissiveMask(const LightmapAtlas& atlas) {
  std::vector<float> mask(atlas.texelCount(), 0.0f);
  for (size_t i = 0; i < mask.size(); ++i)
    if (atlas.patch[i] >= 0 && glm::any(glm::greaterThan(atlas.emission[i], glm::vec3(0.0f)))) mask[i] = 1.0f;
  return mask;
}

void dilate(const LightmapAtlas& atlas, std::vector<glm::vec3>& values, int radius, DilatedValues kind) {
  if (values.size() != atlas.texelCount())
    throw std::invalid_argument("dilate: values must have one entry per atlas texel");
  const int w = atlas.width, h = atlas.height;
  // Reads only valid texels, so the result does not depend on the order padding is visited in.
  const std::vector<glm::vec3> source = values;
  std::vector<uint8_t> filled(atlas.texelCount(), 0);
  for (const GutterTap& g : atlas.gutter) {
    glm::dvec3 sum(0.0);
    for (int k = 0; k < g.from.count; ++k)
      sum += g.from.weight[size_t(k)] * glm::dvec3(source[size_t(g.from.texel[size_t(k)])]);
    // Extrapolated at an edge: light never below 0.
    values[g.texel] =
        kind == DilatedValues::Light ? glm::max(glm::vec3(sum), glm::vec3(0.0f)) : glm::vec3(sum);
    filled[g.texel] = 1;
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t t = size_t(y) * w + x;
      if (atlas.patch[t] >= 0 || filled[t]) continue;
      int best = INT32_MAX;
      size_t from = t;
      for (int dy = -radius; dy <= radius; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= h) continue;
        for (int dx = -radius; dx <= radius; ++dx) {
          const int xx = x + dx;
          if (xx < 0 || xx >= w) continue;
          const size_t s = size_t(yy) * w + xx;
          const int d = dx * dx + dy * dy;
          if (atlas.patch[s] >= 0 && d < best) best = d, from = s;
        }
      }
      values[t] = from != t ? source[from] : glm::vec3(0.0f);
    }
}

}  // namespace cpgi
