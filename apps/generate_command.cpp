// `cpgi generate NAME -o FILE`: writes one of the built-in scenes (the seed scenes of design.md §4 and the
// stability scenes of §6) with its hand-made cells, portals and cameras, as glTF that Blender and every
// cpgi command read back.
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "apps/commands.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "scenes/random_plans.h"
#include "scenes/stability_scenes.h"

namespace cpgi::cli {
namespace {

struct GenerateOptions {
  std::string name;
  std::string output;
  bool noCells = false;      ///< the raw model, as a user would bring it
  bool volumesOnly = false;  ///< the rooms as cellvolume: meshes alone, as an IFC export gives them
  RandomPlanOptions plan;    ///< name "plan": a random floor plan (scenes/random_plans.h)
};

int runGenerate(const GenerateOptions& o) {
  const std::string ext = std::filesystem::path(o.output).extension().string();
  if (ext != ".glb" && ext != ".gltf") throw InputError(o.output, "output must end in .glb or .gltf");
  SeedScene scene;
  try {
    scene = o.name == "plan" ? makeRandomPlan(o.plan) : makeBuiltinScene(o.name);
  } catch (const std::invalid_argument&) {
    std::string known;
    for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
    throw InputError(o.name, "unknown built-in scene (known: " + known + ", plan)");
  }
  const auto parent = std::filesystem::path(o.output).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw InputError(o.output, "cannot create its folder: " + ec.message());
  GltfWriteOptions options;
  if (o.noCells) scene.cells = CellGraph{};
  if (o.volumesOnly) {
    CellGraph volumes;
    for (const Cell& c : scene.cells.cells)
      if (!c.volume.empty()) volumes.cells.push_back(Cell{c.name, {}, c.volume});
    if (volumes.cells.empty()) throw InputError(o.name, "has no room volumes to write (--volumes-only)");
    scene.cells = std::move(volumes);
  }
  options.cells = &scene.cells;
  writeGltf(o.output, scene.scene, options);
  std::cout << o.output << ": " << o.name << ", " << scene.scene.triangles.size() << " triangles, "
            << scene.cells.cells.size() << " cells, " << scene.cells.portals.size() << " portals\n";
  return 0;
}

}  // namespace

void addGenerateCommand(CLI::App& app, CommandFn& selected) {
  auto options = std::make_shared<GenerateOptions>();
  std::string names;
  for (const std::string& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
  names += ", plan (a random floor plan: --seed, --rooms)";
  CLI::App* sub = app.add_subcommand("generate", "Write a built-in scene as glTF, with its hand-made cells");
  sub->add_option("name", options->name, names)->required();
  sub->add_option("-o,--output", options->output, "Output .glb or .gltf")->required()->group("Output");
  sub->add_flag("--no-cells", options->noCells,
                "Leave out the hand-made cells and portals: the raw model, as a user would bring it");
  sub->add_flag("--volumes-only", options->volumesOnly,
                "Give the rooms only as cellvolume: meshes (no cell: or portal: nodes), as an IFC export's "
                "rooms come; the buildings have them")
      ->excludes("--no-cells");
  sub->add_option("--seed", options->plan.seed, "With plan: the plan's seed; each gives another plan")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 53));
  sub->add_option("--rooms", options->plan.rooms,
                  "With plan: the number of rooms, 3-12 (default: from the seed)")
      ->check(CLI::Range(3, 12));
  sub->callback([&selected, options, sub] {
    if (options->name != "plan" && (sub->count("--seed") > 0 || sub->count("--rooms") > 0))
      throw CLI::ValidationError("--seed, --rooms", "only with the scene name plan");
    selected = [options] { return runGenerate(*options); };
  });
}

}  // namespace cpgi::cli
