// A normal-mapped wall under the directional lightmap (issue 48 item 4): how close the light an engine
// puts on bumps comes to a tracer of the bumps, with the plain irradiance lightmap (which ignores them)
// and with the L1 SH lightmap (bake --directional).
//
// The bumps are an egg-crate height field, h = A sin(2πs/λ) sin(2πt/λ) along the wall's horizontal and
// vertical axes, slopes up to `slope`; a normal map tilts the shading normal and moves no geometry, so the
// truth at a point x with bumped normal n is E(x, n) = ∫ L(x, ω) max(0, n·ω) dω over the light arriving
// above the wall: a dense gather (16 384 directions and 2 048 lamp samples per point) over the same baked
// radiosity the lightmaps hold, so that what is measured is how each lightmap carries the bumps, not the
// solve's own error. Against it, per point: plain E(x) (the irradiance lightmap, bilinear), linear
// max(0, V·n) and Ramamoorthi–Hanrahan's SH evaluation of the directional lightmap (bilinear
// coefficients).
//
// With SPP given, the same sample's points are also traced by `cpgi reference`'s path tracer (a white
// point with the bumped normal, ρ = 1, so its B is E(x, n); one-sided walls are black from behind, so it
// too takes only the light arriving above the wall): the error of each estimate against the reference's
// render of the bumps, which holds the solve's own error too, and at the flat normal beside it (where
// plain and directional agree) to show how much of it is the solve's.
//
// Usage: cpgi_directional_bumps [seed1|seed2|seed3] [OUT.png] [RAYS per texel of the directional gather]
//                               [SPP of the reference] [signed: the SH gutters without dilate()'s clamp]
// Prints the relative RMSE of each against the truth over every wall texel of a random sample and over
// one wall's picture, and writes the picture: plain | directional | truth, radiance at one exposure.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include <tbb/parallel_for.h>

#include "core/image_io.h"
#include "radiosity/bake/bake.h"
#include "radiosity/lightmap/directional_lightmap.h"
#include "radiosity/lightmap/engine_lightmap.h"
#include "radiosity/lightmap/lightmap_sampling.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "radiosity/reference/reference_tracer.h"
#include "scenes/seed_scenes.h"

using namespace cpgi;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kWavelength = 0.3f;  // m: no multiple of a texel or pixel, so samples do not alias
constexpr float kSlope = 0.6f;       // the largest slope of the height field (31°)

// The bumped normal at wall point x (normal n, horizontal tangent t, up u).
glm::vec3 bumpedNormal(const glm::vec3& x, const glm::vec3& n) {
  const glm::vec3 u(0, 1, 0), t = glm::normalize(glm::cross(u, n));
  const float s = glm::dot(x, t), v = x.y, k = 2.0f * kPi / kWavelength, a = kSlope / k;
  const float dhds = a * k * std::cos(k * s) * std::sin(k * v),
              dhdv = a * k * std::sin(k * s) * std::cos(k * v);
  return glm::normalize(n - dhds * t - dhdv * u);
}

struct Maps {
  const LightmapAtlas& atlas;
  std::vector<glm::vec3> e;                  // dilated irradiance
  std::array<std::vector<glm::vec3>, 4> sh;  // dilated coefficients
};

// The three estimates at atlas coordinates uv with bumped normal n: plain, linear (V·n), SH (R&H).
std::array<glm::vec3, 3> estimates(const Maps& m, glm::vec2 uv, const glm::vec3& n) {
  std::array<glm::vec3, 4> c;
  for (size_t k = 0; k < 4; ++k) c[k] = sampleBilinear(m.atlas.width, m.atlas.height, m.sh[k], uv);
  glm::vec3 linear;
  for (int ch = 0; ch < 3; ++ch) linear[ch] = std::max(0.0f, glm::dot(shIrradianceVector(c, ch), n));
  return {sampleBilinear(m.atlas.width, m.atlas.height, m.e, uv), linear,
          glm::max(shIrradiance(c, n), glm::vec3(0.0f))};
}

glm::vec3 truth(const BakedRadiance& baked, const glm::vec3& x, const glm::vec3& ns, const glm::vec3& n,
                uint64_t seed, const GatherParams& dense = {16384, 2048}) {
  static thread_local std::vector<ArrivalSample> samples;
  baked.gather(x, ns, seed, dense, samples);
  glm::vec3 e(0.0f);
  for (const ArrivalSample& a : samples) e += a.light * std::max(0.0f, glm::dot(n, a.towards));
  return e;
}

struct Errors {
  std::array<double, 3> err2{};
  double ref2 = 0.0;
  void add(const std::array<glm::vec3, 3>& est, const glm::vec3& ref) {
    for (size_t k = 0; k < 3; ++k) err2[k] += glm::dot(est[k] - ref, est[k] - ref);
    ref2 += glm::dot(ref, ref);
  }
  void print(const char* what) const {
    std::printf("%s: relative RMSE plain %.4f, directional V.n %.4f, directional SH (R&H) %.4f\n", what,
                std::sqrt(err2[0] / ref2), std::sqrt(err2[1] / ref2), std::sqrt(err2[2] / ref2));
  }
};

// A wall point of the sample: where, its wall's normal, its bumped normal, and the three estimates there
// and at the flat normal.
struct WallPoint {
  glm::vec3 x, flat, bumped;
  std::array<glm::vec3, 3> est, estFlat;
};

// Every wall texel's chart point (a sample of `count`), four bumped normals over its footprint each; the
// points are left in `points`.
Errors sampledWalls(const Maps& m, const BakedRadiance& baked, size_t count, std::vector<WallPoint>& points) {
  std::vector<size_t> walls;
  for (size_t i = 0; i < m.atlas.texelCount(); ++i)
    if (m.atlas.patch[i] >= 0 && std::abs(m.atlas.normal[i].y) < 0.1f &&
        m.atlas.emission[i] == glm::vec3(0.0f))
      walls.push_back(i);
  std::mt19937 rng(7);
  std::shuffle(walls.begin(), walls.end(), rng);
  walls.resize(std::min(count, walls.size()));
  std::vector<std::array<std::array<glm::vec3, 3>, 4>> est(walls.size());
  std::vector<std::array<glm::vec3, 4>> ref(walls.size()), again(walls.size());
  points.assign(4 * walls.size(), {});
  tbb::parallel_for(size_t(0), walls.size(), [&](size_t w) {
    const size_t i = walls[w];
    const Patch& p = m.atlas.patches[size_t(m.atlas.patch[i])];
    const int tx = int(i % size_t(m.atlas.width)), ty = int(i / size_t(m.atlas.width));
    for (int q = 0; q < 4; ++q) {
      const float a = float(tx - p.x) + 0.25f + 0.5f * float(q & 1),
                  b = float(ty - p.y) + 0.25f + 0.5f * float(q >> 1);
      const glm::vec3 x = p.origin + a * p.texelU + b * p.texelV, n = bumpedNormal(x, m.atlas.normal[i]);
      const glm::vec2 uv((float(p.x) + a) / float(m.atlas.width), (float(p.y) + b) / float(m.atlas.height));
      est[w][size_t(q)] = estimates(m, uv, n);
      points[4 * w + size_t(q)] = {x, m.atlas.normal[i], n, est[w][size_t(q)],
                                   estimates(m, uv, m.atlas.normal[i])};
      ref[w][size_t(q)] = truth(baked, x, m.atlas.normal[i], n, 1000003ull * i + uint64_t(q));
      again[w][size_t(q)] = truth(baked, x, m.atlas.normal[i], n, 1000003ull * i + uint64_t(q) + 17);
    }
  });
  Errors e;
  double noise2 = 0.0;
  for (size_t w = 0; w < walls.size(); ++w)
    for (size_t q = 0; q < 4; ++q) {
      e.add(est[w][q], ref[w][q]);
      const glm::vec3 d = again[w][q] - ref[w][q];
      noise2 += 0.5 * glm::dot(d, d);
    }
  std::printf("%zu wall texels, 4 bumped normals each; the truth's own noise (two seeds): %.4f\n",
              walls.size(), std::sqrt(noise2 / e.ref2));
  return e;
}

// The largest wall patch at 4 × 4 pixels a texel (the truth by 4 096 directions and 1 024 lamp samples):
// plain | directional (V·n) | truth, radiance ρE/π.
Errors wallPicture(const Maps& m, const BakedRadiance& baked, const std::string& path) {
  size_t best = 0;
  float largest = 0.0f;
  for (size_t k = 0; k < m.atlas.patches.size(); ++k) {
    const Patch& p = m.atlas.patches[k];
    if (std::abs(p.normal.y) < 0.1f && p.area > largest) best = k, largest = p.area;
  }
  const Patch& p = m.atlas.patches[best];
  constexpr int kScale = 4;
  const int w = p.w * kScale, h = p.h * kScale;
  std::vector<std::array<glm::vec3, 3>> px(size_t(w) * h);
  std::vector<glm::vec3> ref(px.size());
  const glm::vec3 rho = m.atlas.albedo[size_t(p.y) * m.atlas.width + p.x];
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float a = (float(x) + 0.5f) / kScale, b = (float(y) + 0.5f) / kScale;
      const glm::vec3 at = p.origin + a * p.texelU + b * p.texelV, n = bumpedNormal(at, p.normal);
      const glm::vec2 uv((float(p.x) + a) / float(m.atlas.width), (float(p.y) + b) / float(m.atlas.height));
      px[size_t(y) * w + x] = estimates(m, uv, n);
      ref[size_t(y) * w + x] = truth(baked, at, p.normal, n, 7919ull * uint64_t(y * w + x), {4096, 1024});
    }
  });
  Errors e;
  ImageRGB image{3 * w + 8, h, std::vector<glm::vec3>(size_t(3 * w + 8) * h, glm::vec3(0.0f))};
  double mean = 0.0;
  for (size_t i = 0; i < px.size(); ++i) e.add(px[i], ref[i]), mean += ref[i].g;
  mean /= double(px.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      image.pixels[size_t(y) * image.width + x] = px[i][0] * rho / kPi;
      image.pixels[size_t(y) * image.width + w + 4 + x] = px[i][1] * rho / kPi;
      image.pixels[size_t(y) * image.width + 2 * w + 8 + x - 4] = ref[i] * rho / kPi;
    }
  writePng(path, image, float(0.5 * kPi / (mean * rho.g)));
  std::printf("wall picture: patch %zu, %.2f m², normal %.2f %.2f %.2f at %.2f %.2f %.2f, %d × %d px, %s\n",
              best, p.area, p.normal.x, p.normal.y, p.normal.z, p.origin.x, p.origin.y, p.origin.z, w, h,
              path.c_str());
  return e;
}

// The sample's points against the reference path tracer at `spp`: each estimate at the bumped normal, and
// at the flat normal (where the three agree but for the SH evaluation), with the reference's own noise.
void againstReference(const Scene& scene, const std::vector<WallPoint>& points, int spp, Context& ctx) {
  std::vector<SamplePoint> bumped, flat;
  for (const WallPoint& p : points) {
    bumped.push_back({p.x, p.bumped, glm::vec3(1.0f), glm::vec3(0.0f)});
    flat.push_back({p.x, p.flat, glm::vec3(1.0f), glm::vec3(0.0f)});
  }
  ReferenceParams params;
  params.spp = spp;
  params.texelMean = false;
  const ReferenceResult refBumped = traceReference(scene, bumped, params, ctx),
                        refFlat = traceReference(scene, flat, params, ctx);
  Errors atBumps, atFlat, flatAgainstPlain;
  double noise2 = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    atBumps.add(points[i].est, refBumped.radiosity[i]);
    atFlat.add(points[i].estFlat, refFlat.radiosity[i]);
    flatAgainstPlain.add(points[i].estFlat, points[i].estFlat[0]);
    noise2 += glm::dot(refBumped.standardError[i], refBumped.standardError[i]);
  }
  std::printf("reference path tracer, %d paths a point, its own noise %.4f\n", refBumped.spp,
              std::sqrt(noise2 / atBumps.ref2));
  atBumps.print("against the reference, bumped normals");
  atFlat.print("against the reference, the walls' flat normals");
  flatAgainstPlain.print("at the flat normals, against the plain lightmap");
}

// The coefficients' gutters filled as dilate() fills them but without its clamp at 0: an SH coefficient
// is signed (L1 of a wall facing −x is negative), and a gutter clamped at 0 turns its irradiance vector.
void dilateSigned(const LightmapAtlas& atlas, std::vector<glm::vec3>& values) {
  const std::vector<glm::vec3> source = values;
  dilate(atlas, values);
  for (const GutterTap& g : atlas.gutter) {
    glm::vec3 sum(0.0f);
    for (int k = 0; k < g.from.count; ++k)
      sum += float(g.from.weight[size_t(k)]) * source[size_t(g.from.texel[size_t(k)])];
    values[g.texel] = sum;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "seed1";
  const std::string png = argc > 2 ? argv[2] : "directional_bumps.png";
  const int level = name == "seed3" ? 3 : name == "seed2" ? 2 : 1;
  const SeedScene seed = makeSeedScene(level);
  Context ctx;
  BakeSettings s;
  const BakeResult r = bake(seed.scene, seed.cells, s, ctx);
  const std::vector<glm::vec3> e = irradianceFromRadiosity(r.atlas, r.radiosity);
  GatherParams gather;
  if (argc > 3) gather.rays = std::stoi(argv[3]);
  DirectionalLightmap map = gatherDirectionalLightmap(seed.scene, r.atlas, r.radiosity, e, gather, ctx);
  std::printf("%s: %zu texels, directional gather %.2f s, %.1f M rays\n", name.c_str(), map.texels,
              map.seconds, double(map.rays) * 1e-6);
  Maps m{r.atlas, e, std::move(map.sh)};
  dilate(r.atlas, m.e);
  // "signed" after the reference's SPP: the coefficients' gutters without the clamp at 0 that the written
  // lightmap_sh_*.exr have.
  const bool signedGutters = argc > 5 && std::string(argv[5]) == "signed";
  for (auto& c : m.sh) signedGutters ? dilateSigned(r.atlas, c) : dilate(r.atlas, c);
  const RayScene rays(seed.scene);
  const BakedRadiance baked(seed.scene, rays, r.atlas, r.radiosity);
  std::vector<WallPoint> points;
  sampledWalls(m, baked, 400, points).print("wall texels");
  if (argc > 4) againstReference(seed.scene, points, std::stoi(argv[4]), ctx);
  wallPicture(m, baked, png).print("wall picture");
  return 0;
}
