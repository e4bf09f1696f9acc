#include "core/html_report/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "core/html_report/embedded_web.h"  // generated: kViewerScript (viewer.js + three.js), kPageTemplate

namespace cpgi {
namespace {

using nlohmann::json;

std::string base64(const void* data, size_t size) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const uint8_t*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    uint32_t n = uint32_t(in[i]) << 16;
    if (i + 1 < size) n |= uint32_t(in[i + 1]) << 8;
    if (i + 2 < size) n |= uint32_t(in[i + 2]);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < size ? table[(n >> 6) & 63] : '=';
    out += i + 2 < size ? table[n & 63] : '=';
  }
  return out;
}

template <class T>
std::string base64(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

// Text placed inside <script>: "</" could close the element early. "<\/" means the same in JSON
// strings and in the script's string and regular-expression literals, the only places it can occur.
std::string escapeForScript(std::string text) {
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.replace(at, 2, "<\\/");
  return text;
}

// The page template with its markers filled in one pass, so a value can never be taken for a marker.
std::string fillTemplate(const std::string& page,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  size_t from = 0;
  while (true) {
    size_t at = std::string::npos;
    const std::pair<std::string, std::string>* hit = nullptr;
    for (const auto& v : values) {
      const size_t found = page.find(v.first, from);
      if (found < at) at = found, hit = &v;
    }
    if (!hit) break;
    out.append(page, from, at - from);
    out += hit->second;
    from = at + hit->first.size();
  }
  out.append(page, from, std::string::npos);
  return out;
}

json vec(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

json lightmapJson(const ReportLightmap& lm) {
  const size_t count = size_t(lm.width) * size_t(lm.height);
  if (lm.radiosity.size() != count || lm.area.size() != count ||
      (!lm.cellOfTexel.empty() && lm.cellOfTexel.size() != count) ||
      (!lm.error.empty() && lm.error.size() != count))
    throw std::invalid_argument("renderHtmlReport: lightmap arrays do not match its width × height");
  // Half floats, RGBA: what WebGL 2 filters linearly everywhere; A unused.
  std::vector<uint16_t> rgba(4 * count);
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 b = lm.radiosity[i];
    for (int k = 0; k < 3; ++k)
      rgba[4 * i + k] = uint16_t(glm::packHalf1x16(std::isfinite(b[k]) ? b[k] : 0.0f));
    rgba[4 * i + 3] = uint16_t(glm::packHalf1x16(1.0f));
  }
  json out = {{"width", lm.width}, {"height", lm.height}, {"rgb", base64(rgba)}, {"area", base64(lm.area)}};
  if (!lm.cellOfTexel.empty()) {
    std::vector<int16_t> cell(count);
    for (size_t i = 0; i < count; ++i)
      cell[i] = int16_t(std::clamp(lm.cellOfTexel[i], -1, int(std::numeric_limits<int16_t>::max())));
    out["cell"] = base64(cell);
  }
  if (!lm.error.empty()) out["error"] = base64(lm.error);
  return out;
}

// Per cell: its viewpoint, and what its texels hold (texels, area, Σ B·A over the mean of R, G, B).
json cellsJson(const HtmlReportInput& in) {
  json cells = json::array();
  if (!in.cells) return cells;
  const std::vector<CellViewpoint> views =
      in.scene ? cellViewpoints(*in.scene, *in.cells) : std::vector<CellViewpoint>(in.cells->cells.size());
  std::vector<size_t> texels(in.cells->cells.size(), 0);
  std::vector<double> area(texels.size(), 0.0), power(texels.size(), 0.0);
  if (in.lightmap)
    for (size_t i = 0; i < in.lightmap->cellOfTexel.size(); ++i) {
      const int c = in.lightmap->cellOfTexel[i];
      if (c < 0 || size_t(c) >= texels.size() || !(in.lightmap->area[i] > 0.0f)) continue;
      const glm::vec3 b = in.lightmap->radiosity[i];
      texels[c] += 1;
      area[c] += in.lightmap->area[i];
      power[c] += double(b.r + b.g + b.b) / 3.0 * in.lightmap->area[i];
    }
  for (size_t c = 0; c < in.cells->cells.size(); ++c) {
    json cell = {{"name", in.cells->cells[c].name}};
    if (views[c].valid) cell["eye"] = vec(views[c].eye), cell["look"] = vec(views[c].look);
    if (in.lightmap && !in.lightmap->cellOfTexel.empty())
      cell["texels"] = texels[c], cell["area_m2"] = area[c], cell["power_w"] = power[c];
    cells.push_back(cell);
  }
  return cells;
}

json portalsJson(const CellGraph* graph) {
  json portals = json::array();
  if (!graph) return portals;
  for (const PortalQuad& p : graph->portals) {
    const auto name = [&](int c) {
      return c >= 0 && size_t(c) < graph->cells.size() ? graph->cells[c].name : "";
    };
    portals.push_back(
        {{"name", p.name},
         {"cell_a", name(p.cellA)},
         {"cell_b", name(p.cellB)},
         {"corners", {vec(p.corners[0]), vec(p.corners[1]), vec(p.corners[2]), vec(p.corners[3])}}});
  }
  return portals;
}

}  // namespace

std::vector<CellViewpoint> cellViewpoints(const Scene& scene, const CellGraph& graph) {
  constexpr float kEyeHeight = 1.6f, kFloorBand = 0.3f;
  std::vector<CellViewpoint> out(graph.cells.size());
  for (size_t c = 0; c < graph.cells.size(); ++c) {
    Bounds bounds;
    float floorY = std::numeric_limits<float>::max();
    for (uint32_t t : graph.cells[c].triangles) {
      if (t >= scene.triangles.size()) continue;
      const Triangle& tri = scene.triangles[t];
      for (const glm::vec3& p : tri.p) bounds.extend(p);
      if (tri.geometricNormal().y > 0.9f) floorY = std::min(floorY, tri.centroid().y);
    }
    if (bounds.empty() || floorY == std::numeric_limits<float>::max()) continue;
    // The lowest floor: up-facing triangles near floorY. Stand over the one nearest their area-weighted
    // middle, so that an L-shaped room still puts the eye above its own floor.
    glm::vec3 middle(0.0f);
    float total = 0.0f;
    for (uint32_t t : graph.cells[c].triangles) {
      if (t >= scene.triangles.size()) continue;
      const Triangle& tri = scene.triangles[t];
      if (tri.geometricNormal().y > 0.9f && tri.centroid().y < floorY + kFloorBand)
        middle += tri.centroid() * tri.area(), total += tri.area();
    }
    if (!(total > 0.0f)) continue;
    middle /= total;
    glm::vec3 stand = middle;
    float best = std::numeric_limits<float>::max();
    for (uint32_t t : graph.cells[c].triangles) {
      if (t >= scene.triangles.size()) continue;
      const Triangle& tri = scene.triangles[t];
      if (!(tri.geometricNormal().y > 0.9f && tri.centroid().y < floorY + kFloorBand)) continue;
      for (int k = 0; k <= 3; ++k) {  // the centroid and the corners pulled a little inwards
        const glm::vec3 p = k == 3 ? tri.centroid() : glm::mix(tri.p[k], tri.centroid(), 0.2f);
        const float d = glm::distance(glm::vec2(p.x, p.z), glm::vec2(middle.x, middle.z));
        if (d < best) best = d, stand = p;
      }
    }
    const float height = std::min(kEyeHeight, 0.6f * (bounds.hi.y - stand.y));
    CellViewpoint& v = out[c];
    v.valid = true;
    v.eye = stand + glm::vec3(0.0f, std::max(height, 0.1f), 0.0f);
    const glm::vec3 size = bounds.hi - bounds.lo;
    const glm::vec3 centre = (bounds.lo + bounds.hi) * 0.5f;
    // Look towards the farther wall along the longer horizontal extent, level.
    glm::vec3 dir = size.x >= size.z ? glm::vec3(v.eye.x < centre.x ? 1.0f : -1.0f, 0.0f, 0.0f)
                                     : glm::vec3(0.0f, 0.0f, v.eye.z < centre.z ? 1.0f : -1.0f);
    v.look = v.eye + dir;
  }
  return out;
}

std::string renderHtmlReport(const HtmlReportInput& in) {
  json data = {{"kind", in.kind}, {"title", in.title}, {"report", in.report}};
  data["cells"] = cellsJson(in);
  data["portals"] = portalsJson(in.cells);
  if (in.lightmap) data["lightmap"] = lightmapJson(*in.lightmap);
  return fillTemplate(
      embedded::kPageTemplate,
      {{"@CPGI_DATA@", escapeForScript(data.dump(-1, ' ', false, json::error_handler_t::replace))},
       {"@CPGI_GLB@", base64(in.glb.data(), in.glb.size())},
       {"@CPGI_SCRIPT@", escapeForScript(embedded::kViewerScript)}});
}

void writeHtmlReport(OutputDir& out, const HtmlReportInput& input) {
  writeFileAtomically(out.file("report.html"), renderHtmlReport(input));
}

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw SystemError(path + ": cannot read");
  return bytes.str();
}

}  // namespace cpgi
