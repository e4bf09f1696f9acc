// BakeSettings ↔ JSON (what a cell-job plan keeps): every field survives the round trip, a JSON that
// leaves fields out keeps BakeSettings' own defaults (not those of the structs it nests), and a wrong value
// is an InputError.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "radiosity/bake/bake_settings.h"

namespace cpgi {
namespace {

// Every field set to something other than its default.
BakeSettings everyFieldChanged() {
  BakeSettings s;
  s.input.scene = "rooms/a b.glb";
  s.input.load.strict = true;
  s.input.load.scale = 0.0254;
  s.input.load.overrides = {{"lamp", glm::vec3(1, 2, 3), std::nullopt},
                            {"wall", std::nullopt, glm::vec3(0.5f)}};
  s.input.load.allowOutsideFiles = true;
  s.input.load.maxFileBytes = 12345;
  s.input.load.maxTriangles = 678;
  s.input.allowDark = true;
  AtlasParams& a = s.atlas.params;
  a.texelsPerQuad = 7, a.density = 12.5f, a.minTexels = 3, a.maxTexels = 99, a.padding = 2, a.maxSize = 4096;
  a.mergeTexels = 17, a.memoryLimit = 1 << 20;
  s.atlas.densityAuto = false;
  AutoDensityParams& d = s.atlas.autoDensity;
  d.pilotDensity = 11, d.light = {5, 41, 0.02f, 0.06f}, d.contacts = false, d.maxContactDensity = 21;
  d.maxTexels = 123456;
  SolverParams& p = s.solver.params;
  p.unshotFraction = 0.003, p.maxShots = 77, p.farField = 3, p.regionSize = 0.7f, p.maxRegions = 3;
  p.strongShotRegions = 2, p.strongShotFraction = 0.01, p.visibility = Visibility::Hemisphere;
  p.itemBuffer = 256, p.neighbourhood = 1, p.jitteredEyes = false, p.lampRays = 16, p.cullItemBuffers = false;
  p.profilePasses = true;
  p.coverageRays = 256, p.eyesPerRegion = 3, p.strongEyesPerRegion = 5, p.clusterRadius = 0.25f;
  s.solver.solveDensity = 2.5f, s.solver.lampCoarsening = 3, s.solver.indirect = IndirectSolver::Rays;
  s.solver.backend = Backend::Rays;
  s.solver.ambient = false, s.solver.ambientShare = 0.25;
  s.cells.method = BakeMethod::Cells, s.cells.source = "auto";
  CellSolveParams& c = s.cells.params;
  c.maxRounds = 9, c.portals = PortalLight::Directional, c.lobeMinWidth = 0.3f, c.portalBinRays = 128,
  c.portalDensityScale = 3.0f, c.jobs = 2;
  decomp::DecomposeParams& q = s.cells.decompose;
  q.voxelSize = 0.08, q.minAutoVoxel = 0.04, q.autoVoxelBudget = 1e6, q.sealRadius = 0.1, q.memoryLimit = 99;
  q.outsideMargin = 1.5, q.classify.minComponentVolume = 0.2, q.watershed.levelStep = 0.25;
  q.merge.saddleRatio = 0.5, q.merge.minDepth = 0.3, q.merge.openingRatio = 0.7, q.merge.minCellVolume = 2.0;
  q.merge.minClosedPeak = 0.4, q.merge.minClosedPeakVoxels = 2.0, q.merge.outsideSaddleRatio = 0.8;
  q.behind.backToFront = 2.0, q.behind.apartBackToFront = 0.5;
  q.portalMerge = {30.0f, 3.0f, 2.0f};
  q.portals = {0.7, 0.9f, 3}, q.assign = {1.5, 6, 3, 0.4}, q.sourceName = "house";
  s.cells.onlyCells = "A,B", s.cells.around = "1,2,3", s.cells.depth = 2,
  s.cells.boundary = BoundaryMode::Dark;
  s.sky.kind = Sky::Kind::CieOvercast, s.sky.horizontalIrradiance = 20.0f, s.sky.zenithRadiance = 4.0f;
  s.sky.towardsSun = glm::vec3(0, 1, 1);
  s.sky.sunIrradiance = 300, s.sky.groundAlbedo = std::nullopt, s.sky.gatherRays = 64;
  s.output.folder = "out", s.output.views = {320, 200, 3, 1.5f};
  s.output.engine = {true, UvSource::Scene, true, 64, true, 0.5f};
  s.limits = {60.0, uint64_t(1) << 33, false};
  return s;
}

// Field by field (not through JSON, so that a field the JSON forgets fails here).
void expectSame(const BakeSettings& a, const BakeSettings& b) {
  EXPECT_EQ(a.input.scene, b.input.scene);
  EXPECT_EQ(a.input.load.strict, b.input.load.strict);
  EXPECT_EQ(a.input.load.scale, b.input.load.scale);
  ASSERT_EQ(a.input.load.overrides.size(), b.input.load.overrides.size());
  for (size_t i = 0; i < a.input.load.overrides.size(); ++i) {
    EXPECT_EQ(a.input.load.overrides[i].material, b.input.load.overrides[i].material);
    EXPECT_EQ(a.input.load.overrides[i].emission, b.input.load.overrides[i].emission);
    EXPECT_EQ(a.input.load.overrides[i].albedo, b.input.load.overrides[i].albedo);
  }
  EXPECT_EQ(a.input.load.allowOutsideFiles, b.input.load.allowOutsideFiles);
  EXPECT_EQ(a.input.load.maxFileBytes, b.input.load.maxFileBytes);
  EXPECT_EQ(a.input.load.maxTriangles, b.input.load.maxTriangles);
  EXPECT_EQ(a.input.allowDark, b.input.allowDark);
  const AtlasParams &x = a.atlas.params, &y = b.atlas.params;
  EXPECT_EQ(x.texelsPerQuad, y.texelsPerQuad);
  EXPECT_EQ(x.density, y.density);
  EXPECT_EQ(x.minTexels, y.minTexels);
  EXPECT_EQ(x.maxTexels, y.maxTexels);
  EXPECT_EQ(x.padding, y.padding);
  EXPECT_EQ(x.maxSize, y.maxSize);
  EXPECT_EQ(x.mergeTexels, y.mergeTexels);
  EXPECT_EQ(x.memoryLimit, y.memoryLimit);
  EXPECT_EQ(a.atlas.densityAuto, b.atlas.densityAuto);
  const AutoDensityParams &d = a.atlas.autoDensity, &e = b.atlas.autoDensity;
  EXPECT_EQ(d.pilotDensity, e.pilotDensity);
  EXPECT_EQ(d.contacts, e.contacts);
  EXPECT_EQ(d.maxContactDensity, e.maxContactDensity);
  EXPECT_EQ(d.maxTexels, e.maxTexels);
  EXPECT_EQ(d.light.minDensity, e.light.minDensity);
  EXPECT_EQ(d.light.maxDensity, e.light.maxDensity);
  EXPECT_EQ(d.light.tolerance, e.light.tolerance);
  EXPECT_EQ(d.light.floorShare, e.light.floorShare);
  const SolverParams &p = a.solver.params, &q = b.solver.params;
  EXPECT_EQ(p.unshotFraction, q.unshotFraction);
  EXPECT_EQ(p.maxShots, q.maxShots);
  EXPECT_EQ(p.farField, q.farField);
  EXPECT_EQ(p.regionSize, q.regionSize);
  EXPECT_EQ(p.maxRegions, q.maxRegions);
  EXPECT_EQ(p.strongShotRegions, q.strongShotRegions);
  EXPECT_EQ(p.strongShotFraction, q.strongShotFraction);
  EXPECT_EQ(p.visibility, q.visibility);
  EXPECT_EQ(p.itemBuffer, q.itemBuffer);
  EXPECT_EQ(p.neighbourhood, q.neighbourhood);
  EXPECT_EQ(p.jitteredEyes, q.jitteredEyes);
  EXPECT_EQ(p.lampRays, q.lampRays);
  EXPECT_EQ(p.cullItemBuffers, q.cullItemBuffers);
  EXPECT_EQ(p.profilePasses, q.profilePasses);
  EXPECT_EQ(p.coverageRays, q.coverageRays);
  EXPECT_EQ(p.eyesPerRegion, q.eyesPerRegion);
  EXPECT_EQ(p.strongEyesPerRegion, q.strongEyesPerRegion);
  EXPECT_EQ(a.solver.solveDensity, b.solver.solveDensity);
  EXPECT_EQ(a.solver.lampCoarsening, b.solver.lampCoarsening);
  EXPECT_EQ(a.solver.indirect, b.solver.indirect);
  EXPECT_EQ(a.solver.backend, b.solver.backend);
  EXPECT_EQ(a.solver.ambient, b.solver.ambient);
  EXPECT_EQ(a.solver.ambientShare, b.solver.ambientShare);
  EXPECT_EQ(a.cells.method, b.cells.method);
  EXPECT_EQ(a.cells.source, b.cells.source);
  const CellSolveParams &c = a.cells.params, &k = b.cells.params;
  EXPECT_EQ(c.maxRounds, k.maxRounds);
  EXPECT_EQ(c.portals, k.portals);
  EXPECT_EQ(c.lobeMinWidth, k.lobeMinWidth);
  EXPECT_EQ(c.portalBinRays, k.portalBinRays);
  EXPECT_EQ(c.portalDensityScale, k.portalDensityScale);
  EXPECT_EQ(c.jobs, k.jobs);
  const decomp::DecomposeParams &u = a.cells.decompose, &v = b.cells.decompose;
  EXPECT_EQ(u.voxelSize, v.voxelSize);
  EXPECT_EQ(u.minAutoVoxel, v.minAutoVoxel);
  EXPECT_EQ(u.autoVoxelBudget, v.autoVoxelBudget);
  EXPECT_EQ(u.sealRadius, v.sealRadius);
  EXPECT_EQ(u.memoryLimit, v.memoryLimit);
  EXPECT_EQ(u.outsideMargin, v.outsideMargin);
  EXPECT_EQ(u.classify.minComponentVolume, v.classify.minComponentVolume);
  EXPECT_EQ(u.watershed.levelStep, v.watershed.levelStep);
  EXPECT_EQ(u.merge.saddleRatio, v.merge.saddleRatio);
  EXPECT_EQ(u.merge.minDepth, v.merge.minDepth);
  EXPECT_EQ(u.merge.openingRatio, v.merge.openingRatio);
  EXPECT_EQ(u.merge.minCellVolume, v.merge.minCellVolume);
  EXPECT_EQ(u.merge.minClosedPeak, v.merge.minClosedPeak);
  EXPECT_EQ(u.merge.minClosedPeakVoxels, v.merge.minClosedPeakVoxels);
  EXPECT_EQ(u.merge.outsideSaddleRatio, v.merge.outsideSaddleRatio);
  EXPECT_EQ(u.behind.backToFront, v.behind.backToFront);
  EXPECT_EQ(u.behind.apartBackToFront, v.behind.apartBackToFront);
  EXPECT_EQ(u.portalMerge.maxAngleDegrees, v.portalMerge.maxAngleDegrees);
  EXPECT_EQ(u.portalMerge.maxGapVoxels, v.portalMerge.maxGapVoxels);
  EXPECT_EQ(u.portalMerge.maxFill, v.portalMerge.maxFill);
  EXPECT_EQ(u.portals.marginVoxels, v.portals.marginVoxels);
  EXPECT_EQ(u.portals.searchRange, v.portals.searchRange);
  EXPECT_EQ(u.portals.extraRounds, v.portals.extraRounds);
  EXPECT_EQ(u.assign.sampleSpacing, v.assign.sampleSpacing);
  EXPECT_EQ(u.assign.maxSamplesPerEdge, v.assign.maxSamplesPerEdge);
  EXPECT_EQ(u.assign.maxSplitDepth, v.assign.maxSplitDepth);
  EXPECT_EQ(u.assign.backSearch, v.assign.backSearch);
  EXPECT_EQ(u.sourceName, v.sourceName);
  EXPECT_EQ(a.cells.onlyCells, b.cells.onlyCells);
  EXPECT_EQ(a.cells.around, b.cells.around);
  EXPECT_EQ(a.cells.depth, b.cells.depth);
  EXPECT_EQ(a.cells.boundary, b.cells.boundary);
  EXPECT_EQ(a.sky.kind, b.sky.kind);
  EXPECT_EQ(a.sky.horizontalIrradiance, b.sky.horizontalIrradiance);
  EXPECT_EQ(a.sky.zenithRadiance, b.sky.zenithRadiance);
  EXPECT_EQ(a.sky.towardsSun, b.sky.towardsSun);
  EXPECT_EQ(a.sky.sunIrradiance, b.sky.sunIrradiance);
  EXPECT_EQ(a.sky.groundAlbedo, b.sky.groundAlbedo);
  EXPECT_EQ(a.sky.gatherRays, b.sky.gatherRays);
  EXPECT_EQ(a.output.folder, b.output.folder);
  EXPECT_EQ(a.output.views.width, b.output.views.width);
  EXPECT_EQ(a.output.views.height, b.output.views.height);
  EXPECT_EQ(a.output.views.supersample, b.output.views.supersample);
  EXPECT_EQ(a.output.views.exposure, b.output.views.exposure);
  EXPECT_EQ(a.output.engine.keepHelpers, b.output.engine.keepHelpers);
  EXPECT_EQ(a.output.engine.uv, b.output.engine.uv);
  EXPECT_EQ(a.output.engine.directional, b.output.engine.directional);
  EXPECT_EQ(a.output.engine.directionalRays, b.output.engine.directionalRays);
  EXPECT_EQ(a.output.engine.probes, b.output.engine.probes);
  EXPECT_EQ(a.output.engine.probeSpacing, b.output.engine.probeSpacing);
  EXPECT_EQ(a.limits.timeLimit, b.limits.timeLimit);
  EXPECT_EQ(a.limits.maxMemory, b.limits.maxMemory);
  EXPECT_EQ(a.limits.refuseEndless, b.limits.refuseEndless);
}

TEST(BakeSettingsJson, EveryFieldSurvivesTheRoundTrip) {
  const BakeSettings changed = everyFieldChanged();
  const nlohmann::json j = bakeSettingsJson(changed);
  // Through text, as plan.json holds it.
  const BakeSettings back = bakeSettingsFromJson(nlohmann::json::parse(j.dump()));
  expectSame(back, changed);
  EXPECT_EQ(bakeSettingsJson(back), j);
  // The fixture changes every field: no leaf of the JSON is the default's.
  const nlohmann::json defaults = bakeSettingsJson(BakeSettings{}).flatten(), flat = j.flatten();
  for (const auto& [path, value] : defaults.items())
    if (flat.contains(path)) {
      EXPECT_NE(flat[path], value) << path;
    }
}

TEST(BakeSettingsJson, DefaultsAreTheBakesAndSurviveTooWithUnsetOptionals) {
  const BakeSettings d;
  EXPECT_EQ(d.solver.params.lampRays, kBakeLampRays);
  EXPECT_EQ(d.cells.params.portals, PortalLight::Binned);
  EXPECT_EQ(d.cells.method, BakeMethod::Global);
  EXPECT_TRUE(d.atlas.densityAuto);
  EXPECT_EQ(d.solver.solveDensity, kAutoSolveDensity);
  EXPECT_EQ(d.sky.groundAlbedo, 0.2f);
  expectSame(bakeSettingsFromJson(bakeSettingsJson(d)), d);
}

TEST(BakeSettingsJson, MissingFieldsKeepTheBakesDefaultsNotTheNestedStructs) {
  // SolverParams' own lamp rays are 0 and CellSolveParams' portals diffuse; a bake's are 64 and binned.
  const BakeSettings s = bakeSettingsFromJson(
      {{"solver", {{"params", {{"itemBuffer", 128}}}}}, {"cells", {{"params", {{"jobs", 3}}}}}});
  EXPECT_EQ(s.solver.params.itemBuffer, 128);
  EXPECT_EQ(s.solver.params.lampRays, kBakeLampRays);
  EXPECT_EQ(s.cells.params.jobs, 3);
  EXPECT_EQ(s.cells.params.portals, kBakePortalLight);
  expectSame(bakeSettingsFromJson(nlohmann::json::object()), BakeSettings{});
}

TEST(BakeSettingsJson, WrongTypesAndUnknownNamesAreInputErrors) {
  EXPECT_THROW(bakeSettingsFromJson(nlohmann::json::array()), InputError);
  EXPECT_THROW(bakeSettingsFromJson({{"solver", {{"params", {{"itemBuffer", "large"}}}}}}), InputError);
  EXPECT_THROW(bakeSettingsFromJson({{"cells", {{"method", "rooms"}}}}), InputError);
  EXPECT_THROW(bakeSettingsFromJson({{"sky", {{"towardsSun", {1, 2}}}}}), InputError);
}

}  // namespace
}  // namespace cpgi
