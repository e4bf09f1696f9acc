// apps/options.h in-process: flags bind to the libraries' fields, enums parse by name, a library error
// naming a parameter prints with its flag, and `--around`'s point parses.
#include "apps/options.h"

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace cpgi::cli {
namespace {

// Parses `args` (without the program name) with `add`'s options; returns false on a CLI11 error.
template <class Add>
bool parse(const std::string& args, Add add) {
  CLI::App app;
  add(app);
  try {
    app.parse(args, false);
  } catch (const CLI::ParseError&) {
    return false;
  }
  return true;
}

TEST(Options, FlagsSetTheLibrariesFields) {
  SolverParams solver;
  CellSolveParams cells;
  decomp::DecomposeParams decompose;
  AtlasParams atlas;
  ASSERT_TRUE(
      parse("--visibility hemisphere --portals directional --voxel 0.2 --seal 0.1 --density 4 "
            "--item-buffer 256 --jobs 2",
            [&](CLI::App& app) {
              addSolverOptions(app, solver);
              addCellOptions(app, cells);
              addDecomposeOptions(app, decompose);
              addAtlasOptions(app, atlas);
            }));
  EXPECT_EQ(solver.visibility, Visibility::Hemisphere);
  EXPECT_EQ(solver.itemBuffer, 256);
  EXPECT_EQ(cells.portals, PortalLight::Directional);
  EXPECT_EQ(cells.jobs, 2);
  EXPECT_DOUBLE_EQ(decompose.voxelSize, 0.2);
  EXPECT_DOUBLE_EQ(decompose.sealRadius, 0.1);
  EXPECT_FLOAT_EQ(atlas.density, 4.0f);
  CellSolveParams binned;
  ASSERT_TRUE(
      parse("--portals binned --portal-rays 512", [&](CLI::App& app) { addCellOptions(app, binned); }));
  EXPECT_EQ(binned.portals, PortalLight::Binned);
  EXPECT_EQ(binned.portalBinRays, 512);
  EXPECT_FALSE(parse("--portal-rays 8", [&](CLI::App& app) { addCellOptions(app, binned); }));
  ASSERT_TRUE(parse("--portal-scale 3", [&](CLI::App& app) { addCellOptions(app, binned); }));
  EXPECT_FLOAT_EQ(binned.portalDensityScale, 3.0f);
  EXPECT_FALSE(parse("--portal-scale 0.5", [&](CLI::App& app) { addCellOptions(app, binned); }));
  SolverParams other;
  EXPECT_FALSE(parse("--visibility cube", [&](CLI::App& app) { addSolverOptions(app, other); }));
  CellSolveParams spot;
  EXPECT_FALSE(parse("--portals spot", [&](CLI::App& app) { addCellOptions(app, spot); }));
}

// Every numeric flag of the table refuses what is not a finite number, in one line naming the flag.
TEST(Options, EveryNumericFlagRefusesNonFiniteNumbers) {
  SolverParams solver;
  CellSolveParams cells;
  decomp::DecomposeParams decompose;
  AtlasParams atlas;
  int spp = 0;
  auto addAll = [&](CLI::App& app) {
    addSolverOptions(app, solver);
    addCellOptions(app, cells);
    addDecomposeOptions(app, decompose);
    addAtlasOptions(app, atlas);
    addSppOption(app, spp);
  };
  CLI::App all;
  addAll(all);
  const std::set<std::string> words = {"--visibility", "--portals"};  // take names, not numbers
  size_t numeric = 0;
  for (const CLI::Option* option : all.get_options()) {
    const std::string name = option->get_name();
    if (option->get_expected_min() < 1 || words.count(name) || name == "--help") continue;
    ++numeric;
    for (const char* bad : {"nan", "inf", "-inf", "1e999", "NaN"}) {
      CLI::App app;
      addAll(app);
      std::string message = "accepted";
      try {
        app.parse(name + " " + bad, false);
      } catch (const CLI::ParseError& e) {
        message = e.what();
      }
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_NE(message.find(name), std::string::npos) << name << " " << bad << ": " << message;
    }
  }
  EXPECT_GE(numeric, 20u);
}

// Out of range, named with the range; NaN never slips through a range check.
TEST(Options, RangesSayTheRange) {
  decomp::DecomposeParams decompose;
  CLI::App app;
  addDecomposeOptions(app, decompose);
  try {
    app.parse("--saddle-ratio 1.5", false);
    ADD_FAILURE() << "accepted";
  } catch (const CLI::ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("--saddle-ratio: must be in [0, 1], got 1.5"), std::string::npos)
        << e.what();
  }
}

TEST(Options, LibraryErrorsNameTheFlag) {
  EXPECT_EQ(userMessage(InputError("voxel size", "must be in (0, 10] metres")),
            "--voxel: must be in (0, 10] metres");
  EXPECT_EQ(userMessage(InputError("s.glb", "1 duplicate triangle; without `strict` they are dropped")),
            "s.glb: 1 duplicate triangle; without --strict they are dropped");
  EXPECT_EQ(userMessage(InputError("s.glb", "`not a parameter` stays")), "s.glb: `not a parameter` stays");
  EXPECT_EQ(flagOf("item buffer"), "--item-buffer");
  EXPECT_EQ(flagOf("scenes/house.glb"), "scenes/house.glb");
}

TEST(Options, ViewSizeSetsBothSidesOrIsRefused) {
  ViewParams views;
  ASSERT_TRUE(parse("--view-size 320x200", [&](CLI::App& app) { addViewOptions(app, views); }));
  EXPECT_EQ(views.width, 320);
  EXPECT_EQ(views.height, 200);
  ViewParams multiplied;
  ASSERT_TRUE(parse("--view-size 1920×1080", [&](CLI::App& app) { addViewOptions(app, multiplied); }));
  EXPECT_EQ(multiplied.width, 1920);
  EXPECT_EQ(multiplied.height, 1080);
  ViewParams untouched;
  ASSERT_TRUE(parse("", [&](CLI::App& app) { addViewOptions(app, untouched); }));
  EXPECT_EQ(untouched.width, ViewParams{}.width);
  EXPECT_EQ(untouched.height, 0);  // from the camera's aspect
  for (const char* bad : {"15x200", "320", "320x200x3", "axb", "320x9000", "320x200px"}) {
    ViewParams refused;
    EXPECT_FALSE(parse(std::string("--view-size ") + bad, [&](CLI::App& app) {
      addViewOptions(app, refused);
    })) << bad;
    EXPECT_EQ(refused.width, ViewParams{}.width) << bad;
    EXPECT_EQ(refused.height, 0) << bad;
  }
  EXPECT_EQ(flagOf("view size"), "--view-size");
  EXPECT_EQ(flagOf("report folder"), "--report");
}

TEST(CellSelection, ParsePoint) {
  EXPECT_EQ(parsePoint("1,-2.5, 3e1", "--around"), glm::vec3(1.0f, -2.5f, 30.0f));
  for (const char* bad : {"", "1,2", "1,2,3,4", "1,x,3", "1,2,3m", "1,nan,3", "1,,3"})
    EXPECT_THROW(parsePoint(bad, "--around"), InputError) << bad;
}

}  // namespace
}  // namespace cpgi::cli

namespace cpgi::cli {
namespace {

TEST(Options, NearestNameForgivesWhatAUserMistypes) {
  const std::vector<std::string> names = {"--density", "--density-tolerance", "--voxel", "--seal", "-o",
                                          "--output"};
  EXPECT_EQ(nearestName("--densty", names), "--density");                 // a letter left out
  EXPECT_EQ(nearestName("--desnity", names), "--density");                // two swapped
  EXPECT_EQ(nearestName("--VOXLE", names), "--voxel");                    // case, a swap
  EXPECT_EQ(nearestName("--density-tol", names), "--density-tolerance");  // the only one it begins
  EXPECT_EQ(nearestName("--bananas", names), "");
  EXPECT_EQ(nearestName("genrate", {"info", "generate", "bake"}), "generate");
}

TEST(Options, UnknownNameMessageNamesTheCommandAndTheNearestOption) {
  CLI::App app;
  CLI::App* bake = app.add_subcommand("bake");
  AtlasParams atlas;
  bool densityAuto = true;
  addAtlasOptions(*bake, atlas, {}, &densityAuto);
  bake->add_option("scene");
  EXPECT_EQ(unknownNameMessage(app, {"bake", "s.glb", "--densty", "5"}),
            "bake: --densty is not an option; did you mean --density?");
  EXPECT_EQ(unknownNameMessage(app, {"bake", "s.glb", "--densty=5"}),
            "bake: --densty is not an option; did you mean --density?");
  EXPECT_EQ(unknownNameMessage(app, {"bkae", "s.glb"}), "bkae is not a command; did you mean bake?");
  // Every name known (the error is another): nothing to say; values that start with '-' are no names.
  EXPECT_EQ(unknownNameMessage(app, {"bake", "s.glb", "--density", "-4"}), "");
  EXPECT_EQ(unknownNameMessage(app, {"bake", "--", "--densty"}), "");
}

TEST(Options, WrapWordsKeepsLinesWithinTheWidth) {
  const std::vector<std::string> lines = wrapWords("one two three four five six\n  indented line", 12);
  for (const std::string& line : lines) EXPECT_LE(line.size(), 12u) << line;
  EXPECT_EQ(lines, (std::vector<std::string>{"one two", "three four", "five six", "  indented", "line"}));
  EXPECT_EQ(wrapWords("  a   b", 12).front(), "  a   b");  // a line that fits stays as written
  EXPECT_EQ(wrapWords("averyveryverylongword x", 5).front(), "averyveryverylongword");
}

// The groups of --help: each add*Options files its flags under its topic, the group before restored.
TEST(Options, OptionsFallUnderTheirTopics) {
  CLI::App app;
  AtlasParams atlas;
  SolverParams solver;
  SkyRequest sky;
  LoadOptions load;
  addAtlasOptions(app, atlas);
  addSolverOptions(app, solver);
  addSkyOptions(app, sky, true);
  addLoadOptions(app, load);
  app.add_flag("--mine");
  EXPECT_EQ(app.get_option("--density")->get_group(), "Atlas");
  EXPECT_EQ(app.get_option("--max-memory")->get_group(), "Limits");
  EXPECT_EQ(app.get_option("--unshot")->get_group(), "Solver");
  EXPECT_EQ(app.get_option("--sun")->get_group(), "Sky");
  EXPECT_EQ(app.get_option("--scale")->get_group(), "Input");
  EXPECT_EQ(app.get_option("--mine")->get_group(), "Options");
  app.formatter(groupedHelpFormatter());
  const std::string help = app.help();
  EXPECT_LT(help.find("\nInput:"), help.find("\nAtlas:"));
  EXPECT_LT(help.find("\nSky:"), help.find("\nLimits:"));
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) EXPECT_LE(line.size(), kHelpColumns) << line;
}

}  // namespace
}  // namespace cpgi::cli
