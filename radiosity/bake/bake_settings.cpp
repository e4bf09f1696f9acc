#include "radiosity/bake/bake_settings.h"

#include <optional>
#include <string>

#include "core/error.h"

// to_json / from_json of every settings struct a bake nests, in the namespace of each (found by ADL).
// from_json reads into the object it is given and keeps a field the JSON lacks, so that what a JSON leaves
// out keeps BakeSettings' default (its lamp rays and portals are not SolverParams' or CellSolveParams').
#define CPGI_JSON_READ(field)                                                    \
  if (const auto it = nlohmann_json_j.find(#field); it != nlohmann_json_j.end()) \
    it->get_to(nlohmann_json_t.field);
#define CPGI_JSON_FIELDS(Type, ...)                                                     \
  inline void to_json(nlohmann::json& nlohmann_json_j, const Type& nlohmann_json_t) {   \
    NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(NLOHMANN_JSON_TO, __VA_ARGS__))            \
  }                                                                                     \
  inline void from_json(const nlohmann::json& nlohmann_json_j, Type& nlohmann_json_t) { \
    NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(CPGI_JSON_READ, __VA_ARGS__))              \
  }

namespace cpgi {

const char* bakeMethodName(BakeMethod m) {
  return m == BakeMethod::Cells ? "cells" : "global";
}

const char* indirectSolverName(IndirectSolver s) {
  switch (s) {
    case IndirectSolver::Gpu:
      return "gpu";
    case IndirectSolver::Rays:
      return "rays";
    default:
      return "auto";
  }
}

const char* backendName(Backend b) {
  switch (b) {
    case Backend::Gl:
      return "gl";
    case Backend::Rays:
      return "rays";
    default:
      return "auto";
  }
}

// An unknown name is an error, not the first value (NLOHMANN_JSON_SERIALIZE_ENUM's fallback).
template <class Enum, size_t N>
void enumFromJson(const nlohmann::json& j, Enum& e, const std::pair<Enum, const char*> (&names)[N]) {
  for (const auto& [value, name] : names)
    if (j == name) {
      e = value;
      return;
    }
  throw InputError("bake settings", "unknown value " + j.dump());
}
#define CPGI_JSON_ENUM(Enum, ...)                                    \
  inline void to_json(nlohmann::json& j, const Enum& e) {            \
    static const std::pair<Enum, const char*> names[] = __VA_ARGS__; \
    for (const auto& [value, name] : names)                          \
      if (value == e) j = name;                                      \
  }                                                                  \
  inline void from_json(const nlohmann::json& j, Enum& e) {          \
    static const std::pair<Enum, const char*> names[] = __VA_ARGS__; \
    enumFromJson(j, e, names);                                       \
  }

CPGI_JSON_ENUM(BakeMethod, {{BakeMethod::Global, "global"}, {BakeMethod::Cells, "cells"}})
CPGI_JSON_ENUM(IndirectSolver,
               {{IndirectSolver::Auto, "auto"}, {IndirectSolver::Gpu, "gpu"}, {IndirectSolver::Rays, "rays"}})
CPGI_JSON_ENUM(Backend, {{Backend::Auto, "auto"}, {Backend::Gl, "gl"}, {Backend::Rays, "rays"}})
CPGI_JSON_ENUM(Visibility, {{Visibility::Hemisphere, "hemisphere"}, {Visibility::Hemicube, "hemicube"}})
CPGI_JSON_ENUM(PortalLight, {{PortalLight::Diffuse, "diffuse"},
                             {PortalLight::Directional, "directional"},
                             {PortalLight::Binned, "binned"}})
CPGI_JSON_ENUM(BoundaryMode, {{BoundaryMode::Coarse, "coarse"}, {BoundaryMode::Dark, "dark"}})
CPGI_JSON_ENUM(UvSource, {{UvSource::Own, "own"}, {UvSource::Scene, "scene"}, {UvSource::Auto, "auto"}})
CPGI_JSON_ENUM(Sky::Kind, {{Sky::Kind::None, "none"},
                           {Sky::Kind::Uniform, "uniform"},
                           {Sky::Kind::CieOvercast, "cie-overcast"}})

// An optional number or vector: null when unset.
template <class T>
nlohmann::json optionalJson(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
template <class T>
void readOptional(const nlohmann::json& j, const char* key, std::optional<T>& v) {
  const auto it = j.find(key);
  if (it == j.end()) return;
  if (it->is_null())
    v.reset();
  else
    v = it->get<T>();
}
std::optional<glm::vec3> vecOf(const std::optional<std::vector<float>>& v) {
  if (!v) return std::nullopt;
  if (v->size() != 3) throw InputError("bake settings", "a vector is not three numbers");
  return glm::vec3((*v)[0], (*v)[1], (*v)[2]);
}
std::optional<std::vector<float>> listOf(const std::optional<glm::vec3>& v) {
  if (!v) return std::nullopt;
  return std::vector<float>{v->x, v->y, v->z};
}

void to_json(nlohmann::json& j, const MaterialOverride& o) {
  j = {{"material", o.material},
       {"emission", optionalJson(listOf(o.emission))},
       {"albedo", optionalJson(listOf(o.albedo))}};
}
void from_json(const nlohmann::json& j, MaterialOverride& o) {
  o.material = j.at("material").get<std::string>();
  std::optional<std::vector<float>> emission = listOf(o.emission), albedo = listOf(o.albedo);
  readOptional(j, "emission", emission);
  readOptional(j, "albedo", albedo);
  o.emission = vecOf(emission), o.albedo = vecOf(albedo);
}

void to_json(nlohmann::json& j, const SkyRequest& s) {
  j = {{"kind", s.kind},
       {"horizontalIrradiance", optionalJson(s.horizontalIrradiance)},
       {"zenithRadiance", optionalJson(s.zenithRadiance)},
       {"towardsSun", optionalJson(listOf(s.towardsSun))},
       {"sunIrradiance", s.sunIrradiance},
       {"groundAlbedo", optionalJson(s.groundAlbedo)},
       {"gatherRays", s.gatherRays}};
}
void from_json(const nlohmann::json& j, SkyRequest& s) {
  if (j.contains("kind")) j.at("kind").get_to(s.kind);
  readOptional(j, "horizontalIrradiance", s.horizontalIrradiance);
  readOptional(j, "zenithRadiance", s.zenithRadiance);
  std::optional<std::vector<float>> sun = listOf(s.towardsSun);
  readOptional(j, "towardsSun", sun);
  s.towardsSun = vecOf(sun);
  if (j.contains("sunIrradiance")) j.at("sunIrradiance").get_to(s.sunIrradiance);
  readOptional(j, "groundAlbedo", s.groundAlbedo);
  if (j.contains("gatherRays")) j.at("gatherRays").get_to(s.gatherRays);
}

CPGI_JSON_FIELDS(LoadOptions, scale, strict, overrides, allowOutsideFiles, maxFileBytes, maxTriangles)
CPGI_JSON_FIELDS(AtlasParams, texelsPerQuad, density, minTexels, maxTexels, padding, maxSize, mergeTexels,
                 memoryLimit)
CPGI_JSON_FIELDS(LightDensityParams, minDensity, maxDensity, tolerance, floorShare)
CPGI_JSON_FIELDS(AutoDensityParams, pilotDensity, light, contacts, maxContactDensity, maxTexels)
CPGI_JSON_FIELDS(SolverParams, unshotFraction, maxShots, farField, regionSize, maxRegions, strongShotRegions,
                 strongShotFraction, visibility, itemBuffer, neighbourhood, jitteredEyes, lampRays,
                 cullItemBuffers, profilePasses, coverageRays, eyesPerRegion, strongEyesPerRegion,
                 clusterRadius)
// What a bake reads of CellSolveParams (BakeSettings::Cells::params); the rest is set by the bake.
CPGI_JSON_FIELDS(CellSolveParams, maxRounds, portals, lobeMinWidth, portalBinRays, portalDensityScale, jobs)
CPGI_JSON_FIELDS(ViewParams, width, height, supersample, exposure)
CPGI_JSON_FIELDS(BakeSettings::Input, scene, load, allowDark)
CPGI_JSON_FIELDS(BakeSettings::Atlas, params, densityAuto, autoDensity)
CPGI_JSON_FIELDS(BakeSettings::Solver, params, solveDensity, lampCoarsening, indirect, backend, ambient,
                 ambientShare)
CPGI_JSON_FIELDS(EngineOutputParams, keepHelpers, uv, directional, directionalRays, probes, probeSpacing)
CPGI_JSON_FIELDS(BakeSettings::Output, folder, views, engine)
CPGI_JSON_FIELDS(BakeSettings::Limits, timeLimit, maxMemory, refuseEndless)

namespace decomp {
CPGI_JSON_FIELDS(ClassifyParams, minComponentVolume)
CPGI_JSON_FIELDS(WatershedParams, levelStep)
CPGI_JSON_FIELDS(MergeParams, saddleRatio, minDepth, openingRatio, minCellVolume, minClosedPeak,
                 minClosedPeakVoxels, outsideSaddleRatio)
CPGI_JSON_FIELDS(BehindParams, backToFront, apartBackToFront)
CPGI_JSON_FIELDS(PortalMergeParams, maxAngleDegrees, maxGapVoxels, maxFill)
CPGI_JSON_FIELDS(PortalParams, marginVoxels, searchRange, extraRounds)
CPGI_JSON_FIELDS(AssignParams, sampleSpacing, maxSamplesPerEdge, maxSplitDepth, backSearch)
CPGI_JSON_FIELDS(DecomposeParams, voxelSize, minAutoVoxel, autoVoxelBudget, sealRadius, memoryLimit,
                 outsideMargin, classify, watershed, merge, behind, portals, portalMerge, assign, sourceName)
}  // namespace decomp

CPGI_JSON_FIELDS(BakeSettings::Cells, method, source, params, decompose, onlyCells, around, depth, boundary)
CPGI_JSON_FIELDS(BakeSettings, input, atlas, solver, cells, sky, output, limits)

nlohmann::json bakeSettingsJson(const BakeSettings& s) {
  return nlohmann::json(s);
}

BakeSettings bakeSettingsFromJson(const nlohmann::json& j) {
  if (!j.is_object()) throw InputError("bake settings", "not a JSON object");
  BakeSettings s;
  try {
    from_json(j, s);
  } catch (const nlohmann::json::exception& e) {
    throw InputError("bake settings", std::string("a field of the wrong type: ") + e.what());
  }
  return s;
}

}  // namespace cpgi
