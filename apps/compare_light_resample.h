// compare-light across atlases (`--scene`): lightmap A, baked on an atlas of its own (another density, or
// one that follows the light), read at the texels of reference B as an engine reads A's baked.glb.
#pragma once

#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/scene.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi::cli {

/// B's atlas rebuilt from `scene` (read from `scenePath`) with the atlas options `bDir`/report.json records;
/// throws InputError naming the file when those options are not there (a bake at --density auto) or the
/// atlas does not give B's texel areas (`bArea`, bWidth × bHeight).
LightmapAtlas rebuildReferenceAtlas(const Scene& scene, const std::string& scenePath, const std::string& bDir,
                                    const std::vector<float>& bArea, int bWidth, int bHeight);

/// A's lightmap (`aImage`, from `aDir`/lightmap.exr) at each texel centre of B's atlas: B's atlas is
/// rebuilt from `scenePath` with the atlas options in `bDir`/report.json and must give B's texel areas
/// (`bArea`, its width × height); A's coordinates per triangle come from `aDir`/baked.glb, matched to
/// the scene's triangles by their corners, else (a bake on the automatic cells, which splits triangles on
/// its portal planes) the piece of A's that holds the texel's point. Throws InputError naming the file
/// when the scene does not give B's atlas or A's baked.glb lacks a surface B's texels lie on; with
/// `unreadTexels`, up to 1 % of B's valid texels may lie on none, marked there (1) and left 0. `load`:
/// how the scene is read, as B was made (a reference traced before faces were cut at their contacts, or
/// with --keep-contacts, needs cutContacts off to give B's atlas).
ImageRGB sampleOnReferenceAtlas(const std::string& scenePath, const std::string& aDir, const ImageRGB& aImage,
                                const std::string& bDir, const std::vector<float>& bArea, int bWidth,
                                int bHeight, std::vector<char>* unreadTexels = nullptr,
                                const LoadOptions& load = {});

}  // namespace cpgi::cli
