// `cpgi info SCENE [--json] [loading options]`: what the loader sees in a scene, and what is wrong with it.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/cell_json.h"
#include "core/lights.h"
#include "core/quads.h"
#include "core/scene_io.h"

namespace cpgi::cli {
namespace {

struct InfoOptions {
  std::string scene;
  bool json = false;
  LoadOptions load;  ///< --strict, --allow-outside-files, --emit, --albedo
  InfoOptions() {
    // info counts the file as written; the faces cut where solids run through them are the bake's
    // (core/contact_cuts.h), said in its report.
    load.cutContacts = false;
  }
};

std::string fmt(const char* format, double a, double b = 0, double c = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}
std::string triple(const glm::vec3& v, const char* unit = "") {
  return fmt("%.4g %.4g %.4g", v.x, v.y, v.z) + unit;
}

// The summary, computed once and printed either as JSON or as text.
nlohmann::json summarise(const LoadedScene& loaded) {
  using nlohmann::json;
  const Scene& s = loaded.scene;
  const QuadSet quads = findQuads(s);
  json materials = json::array();
  for (const Material& m : s.materials)
    materials.push_back({{"name", m.name}, {"albedo", toJson(m.albedo)}, {"emission", toJson(m.emission)}});

  // Emitters: per emissive material, its triangles, area and power (W = W/m² × m²).
  std::vector<size_t> count(s.materials.size(), 0);
  std::vector<double> area(s.materials.size(), 0.0);
  for (const Triangle& t : s.triangles)
    if (t.material < s.materials.size()) ++count[t.material], area[t.material] += t.area();
  json emitters = json::array();
  for (size_t m = 0; m < s.materials.size(); ++m)
    if (s.materials[m].isEmitter() && count[m] > 0)
      emitters.push_back({{"material", s.materials[m].name},
                          {"triangles", count[m]},
                          {"area_m2", area[m]},
                          {"power_w", toJson(s.materials[m].emission * float(area[m]))}});

  // Punctual lights in cpgi's units (W/sr, or W/m² for directional) and, for point and spot, their power.
  json lights = json::array();
  for (const PunctualLight& l : s.lights) {
    const char* kind = l.kind == PunctualLight::Kind::Point  ? "point"
                       : l.kind == PunctualLight::Kind::Spot ? "spot"
                                                             : "directional";
    json j = {{"name", l.name}, {"type", kind}, {"direction", toJson(l.direction)}};
    if (l.kind == PunctualLight::Kind::Directional) {
      j["irradiance_w_m2"] = toJson(l.intensity);
    } else {
      j["position"] = toJson(l.position);
      j["intensity_w_sr"] = toJson(l.intensity);
      j["power_w"] = toJson(glm::vec3(punctualPower(l)));
    }
    if (l.kind == PunctualLight::Kind::Spot) j["cone_rad"] = {l.innerCone, l.outerCone};
    lights.push_back(j);
  }

  json cameras = json::array();
  for (const Camera& c : s.cameras)
    cameras.push_back({{"name", c.name},
                       {"position", toJson(c.position)},
                       {"forward", toJson(c.forward)},
                       {"up", toJson(c.up)},
                       {"yfov", c.yfov},
                       {"aspect", c.aspect}});
  const Bounds b = s.bounds();
  const json graph = cellGraphToJson(s, loaded.cells);
  return {{"triangles", s.triangles.size()},
          {"quads", quads.quads.size()},
          {"loose_triangles", quads.looseTriangles()},
          {"materials", materials},
          {"emitters", emitters},
          {"emitted_power", toJson(s.emittedPower())},
          {"lights", lights},
          {"bounds", {{"min", toJson(b.lo)}, {"max", toJson(b.hi)}, {"size", toJson(b.size())}}},
          {"cameras", cameras},
          {"cells", graph["cells"]},
          {"portals", graph["portals"]},
          {"adjacency", graph["adjacency"]},
          {"warnings", loaded.warnings}};
}

glm::vec3 vec(const nlohmann::json& j) {
  return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

void printText(const std::string& path, const nlohmann::json& info) {
  std::ostream& out = std::cout;
  out << path << "\n";
  out << "  triangles      " << info["triangles"].get<size_t>() << " (" << info["quads"].get<size_t>()
      << " quads, " << info["loose_triangles"].get<size_t>() << " loose triangles)\n";
  out << "  materials      " << info["materials"].size() << "\n";
  out << "  emitters       " << info["emitters"].size();
  for (const auto& e : info["emitters"])
    out << "\n    " << e["material"].get<std::string>() << ": " << e["triangles"].get<size_t>()
        << " triangles, " << fmt("%.4g m², ", e["area_m2"].get<double>()) << triple(vec(e["power_w"]), " W");
  out << "\n  emitted power  " << triple(vec(info["emitted_power"]), " W (RGB)");
  out << "\n  lights         " << info["lights"].size();
  for (const auto& l : info["lights"]) {
    out << "\n    " << l["name"].get<std::string>() << ": " << l["type"].get<std::string>();
    if (l.contains("power_w"))
      out << " at " << triple(vec(l["position"])) << ", " << triple(vec(l["power_w"]), " W");
    else
      out << ", " << triple(vec(l["irradiance_w_m2"]), " W/m²");
  }
  out << "\n";
  out << "  bounds         " << triple(vec(info["bounds"]["min"])) << "  to  "
      << triple(vec(info["bounds"]["max"])) << "  (size " << triple(vec(info["bounds"]["size"]), " m")
      << ")\n";
  out << "  cameras        " << info["cameras"].size();
  for (const auto& c : info["cameras"])
    out << "\n    " << c["name"].get<std::string>() << " at " << triple(vec(c["position"])) << " looking "
        << triple(vec(c["forward"])) << fmt(", yfov %.3g rad", c["yfov"].get<double>());
  out << "\n  cells          " << info["cells"].size();
  for (const auto& c : info["cells"])
    out << "\n    " << c["name"].get<std::string>() << ": " << c["triangles"].get<size_t>() << " triangles, "
        << fmt("%.4g m²", c["area_m2"].get<double>());
  out << "\n  portals        " << info["portals"].size();
  for (const auto& p : info["portals"])
    out << "\n    " << p["name"].get<std::string>() << ": " << fmt("%.4g m² at ", p["area_m2"].get<double>())
        << triple(vec(p["centre"])) << ", normal " << triple(vec(p["normal"]));
  out << "\n";
}

}  // namespace

void addInfoCommand(CLI::App& app, CommandFn& selected) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub =
      app.add_subcommand("info", "Describe a scene: triangles, quads, materials, emitters, cameras, cells");
  sub->add_option("scene", options->scene, "Scene file (.glb, .gltf or .obj)")->required();
  sub->add_flag("--json", options->json, "Print JSON instead of text")->group("Output");
  addLoadOptions(*sub, options->load);
  sub->remove_option(sub->get_option(flagOf("keep contacts")));  // info never cuts (InfoOptions)
  sub->callback([options, &selected] {
    selected = [options] {
      const LoadedScene loaded = loadScene(options->scene, options->load);
      const nlohmann::json info = summarise(loaded);
      if (options->json) {
        std::cout << info.dump(2) << "\n";
      } else {
        printLoaderWarnings(options->scene, loaded.warnings);
        printText(options->scene, info);
      }
      return 0;
    };
  });
}

}  // namespace cpgi::cli
