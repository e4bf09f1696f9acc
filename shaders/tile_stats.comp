// Per-tile energy sums (PatchStats of one 8×8 tile): Σ residual × area, Σ irradiance × area and
// Σ (1 − ρ) irradiance × area, so that the per-patch statistics add up tiles instead of rereading a
// whole chart in one work group (a merged wall of a million texels would run on one core). One
// invocation per tile, texels in a fixed order: runs agree to the bit, and no barrier (llvmpipe runs
// shaders with barriers as coroutines, much slower).
//
// Runs over tiles [uFirstTile, uEndTile): all of them at the start, then after each shot those of the
// patches that received (visible[]) and the shooter's, whose residual is zeroed here (its energy has
// just been shot; the receivers read it until the gather pass is over).
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
layout(std430, binding = 2) readonly buffer Visible { uint visible[]; };
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };
layout(std430, binding = 16) buffer TileStats { PatchStats tileStats[]; };
uniform uint uFirstTile, uEndTile;
uniform int uShooter;
uniform bool uOnlyVisible;

void main() {
  uint i = uFirstTile + gl_GlobalInvocationID.x;
  if (i >= uEndTile) return;
  ivec4 tile = tiles[i];
  if (uOnlyVisible && visible[tile.z] == 0u) return;
  ivec4 chart = patches[tile.z].rect;
  ivec2 end = min(tile.xy + 8, chart.xy + chart.zw);
  vec3 unshot = vec3(0.0), got = vec3(0.0), absorbed = vec3(0.0);
  for (int y = tile.y; y < end.y; ++y)
    for (int x = tile.x; x < end.x; ++x) {
      int t = texel(ivec2(x, y));
      if (int(normalPatch[t].w) != tile.z) continue;
      if (tile.z == uShooter) residual[t] = vec4(0.0);
      float a = posArea[t].w;
      vec3 inc = incident[t].rgb;
      unshot += residual[t].rgb * a;
      got += inc * a;
      absorbed += (vec3(1.0) - albedo[t].rgb) * inc * a;
    }
  tileStats[i].unshot = vec4(unshot, 0.0);
  tileStats[i].incident = vec4(got, 0.0);
  tileStats[i].absorbed = vec4(absorbed, 0.0);
}
