// The light of an open scene's surroundings: a sky dome and a ground at infinity (Scene::sky) and the sun
// as a directional punctual light (Scene::lights, core/lights.h). One definition that every back end
// evaluates: the bake's first shot gathers it at every texel (radiosity/lightmap/sky_light.h), the
// path-traced reference picks it up where a path leaves the scene (radiosity/reference), so the two model
// exactly the same light. Y is up (design.md: scenes in metres, glTF's +Y up).
//
// Radiance, W/(m²·sr), grey (the same on R, G and B):
// - uniform sky:      L = Lz above the horizon, horizontal irradiance E = π Lz;
// - CIE overcast sky: L(θ) = Lz (1 + 2 cos θ)/3, θ from the zenith (Moon & Spencer 1942, CIE standard
//                     overcast), E = 7π Lz / 9;
// - ground (below the horizon): a diffuse plane of albedo ρ lit by the unoccluded sky and sun,
//                     L = ρ (E_sky + E_sun cos θ_sun) / π; none leaves it black.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace cpgi {

struct Scene;

struct Sky {
  enum class Kind { None, Uniform, CieOvercast };
  Kind kind = Kind::None;
  float zenithRadiance = 0.0f;  ///< Lz, W/(m²·sr); 0 with Kind::None
  float groundRadiance = 0.0f;  ///< L below the horizon, W/(m²·sr); 0 for no ground
  /// Directions per texel the bake's first shot gathers the sky from (stratified, cosine-weighted).
  int gatherRays = 256;

  /// Whether any light comes from the surroundings (sky or ground).
  bool lights() const { return zenithRadiance > 0.0f || groundRadiance > 0.0f; }
};

/// The radiance arriving from unit direction `towards` (pointing away from the scene, into the sky).
float skyRadiance(const Sky& sky, const glm::vec3& towards);

/// Horizontal irradiance (W/m²) from the sky dome alone, no ground, for zenith radiance `zenith`.
float horizontalIrradiance(Sky::Kind kind, float zenith);

/// What a user asks for (apps' --sky, --sky-irradiance, --sky-zenith, --sun, --ground).
struct SkyRequest {
  Sky::Kind kind = Sky::Kind::None;
  std::optional<float> horizontalIrradiance;  ///< W/m² on an unoccluded horizontal plane from the sky
  std::optional<float> zenithRadiance;        ///< W/(m²·sr); excludes horizontalIrradiance
  std::optional<glm::vec3> towardsSun;        ///< direction to the sun (any length > 0, above the horizon)
  float sunIrradiance = 0.0f;                 ///< W/m² on a plane facing the sun
  std::optional<float> groundAlbedo = 0.2f;   ///< in [0, 1]; nullopt: no ground (black below)
  int gatherRays = 256;
};

/// The sky of a request: kind and zenith radiance (from the horizontal irradiance when that is given;
/// default 15 W/m², about 10,000 lux at 683 lm/W, a bright overcast day), and the ground lit by it and the
/// sun. Throws InputError naming the parameter ("sky", "sky irradiance", "sun", "ground albedo") for
/// values out of range.
Sky makeSky(const SkyRequest& request);

/// Sets `scene.sky` to makeSky(request) and adds the sun, when asked, as a directional light named "sun"
/// (its irradiance on R, G and B alike).
void applySky(const SkyRequest& request, Scene& scene);

/// The name of a kind as the command line and report.json write it: "none", "uniform", "cie-overcast".
const char* skyKindName(Sky::Kind kind);
/// The kind of a name; nullopt for an unknown one.
std::optional<Sky::Kind> skyKindOf(const std::string& name);

}  // namespace cpgi
