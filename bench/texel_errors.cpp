// Where a bake's error lies: every texel a reference traced, with its position, normal, cell, distance to
// its chart's edge, the bake's and the reference's radiosity (R + G + B, then per channel), its chart's
// material and the reference's noise, as CSV
// for a script to group (by cell, by distance to an edge, by surface). The atlas is rebuilt from the scene
// with the reference's atlas options, so that texel positions come without a glTF reader; a bake on an
// atlas of its own (`--density auto`) is read at the reference's texel centres as compare-light --scene
// reads it (bilinear, through its baked.glb).
//
//   cpgi_texel_errors SCENE BAKE_DIR REFERENCE_DIR (--density D | --texels-per-quad N) [--keep-contacts]
//     > texels.csv
// --keep-contacts: the scene read with its faces whole, as a reference traced before the contact cuts was.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "apps/compare_light_resample.h"
#include "core/image_io.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"

namespace {

const std::vector<float>* channel(const std::vector<cpgi::ExrChannel>& channels, const std::string& name) {
  for (const cpgi::ExrChannel& c : channels)
    if (c.name == name) return &c.values;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6 && !(argc == 7 && std::string(argv[6]) == "--keep-contacts")) {
    std::fprintf(stderr,
                 "usage: %s SCENE BAKE_DIR REFERENCE_DIR (--density D | --texels-per-quad N) "
                 "[--keep-contacts]\n",
                 argv[0]);
    return 1;
  }
  using namespace cpgi;
  try {
    LoadOptions load;
    load.cutContacts = argc != 7;
    const LoadedScene loaded = loadScene(argv[1], load);
    AtlasParams params;
    if (std::string(argv[4]) == "--density")
      params.density = std::stof(argv[5]);
    else
      params.texelsPerQuad = std::stoi(argv[5]);
    Context ctx;
    const LightmapAtlas atlas = buildAtlas(loaded.scene, findQuads(loaded.scene), params, ctx);
    std::vector<ExrChannel> bakeChannels, refChannels;
    ImageRGB bake = readExr(std::string(argv[2]) + "/lightmap.exr", &bakeChannels);
    const ImageRGB ref = readExr(std::string(argv[3]) + "/lightmap.exr", &refChannels);
    if (bake.width != ref.width || bake.height != ref.height)
      bake = cli::sampleOnReferenceAtlas(argv[1], argv[2], bake, argv[3], atlas.area, atlas.width,
                                         atlas.height, nullptr, load);
    if (ref.width != atlas.width || ref.height != atlas.height) {
      std::fprintf(stderr, "the lightmaps are not of this atlas (%dx%d)\n", atlas.width, atlas.height);
      return 1;
    }
    const std::vector<float>* weight = channel(refChannels, "sample_weight");
    const std::vector<float>* sigma = channel(refChannels, "stderr");
    const std::vector<float>* cell = channel(refChannels, "cell");
    const std::vector<float>* emissive = channel(refChannels, "emissive");
    std::printf(
        "x,y,z,nx,ny,nz,area,cell,emissive,edge,patch,bake,ref,sigma,weight,material,"
        "bake_r,bake_g,bake_b,ref_r,ref_g,ref_b\n");
    for (const Patch& p : atlas.patches)
      for (int j = 0; j < p.h; ++j)
        for (int i = 0; i < p.w; ++i) {
          const size_t t = size_t(p.y + j) * size_t(atlas.width) + size_t(p.x + i);
          if (atlas.patch[t] < 0 || &atlas.patches[size_t(atlas.patch[t])] != &p) continue;
          const float w = weight ? (*weight)[t] : 1.0f;
          if (!(w > 0.0f)) continue;
          const int edge = std::min(std::min(i, p.w - 1 - i), std::min(j, p.h - 1 - j));
          const glm::vec3 x = atlas.position[t], n = atlas.normal[t];
          const glm::vec3 b = bake.pixels[t], r = ref.pixels[t];
          std::printf(
              "%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%.6g,%g,%g,%d,%d,%.6g,%.6g,%.4g,%.4g,%u,%.6g,%.6g,%.6g,"
              "%.6g,%.6g,%.6g\n",
              x.x, x.y, x.z, n.x, n.y, n.z, atlas.area[t], cell ? (*cell)[t] : -1.0f,
              emissive ? (*emissive)[t] : 0.0f, edge, atlas.patch[t], b.r + b.g + b.b, r.r + r.g + r.b,
              sigma ? (*sigma)[t] : 0.0f, w, p.material, b.r, b.g, b.b, r.r, r.g, r.b);
        }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
