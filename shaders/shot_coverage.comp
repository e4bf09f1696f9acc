// How much of each region eye's hemisphere the item buffer shows covered by a receiver facing the eye,
// and how much open (nothing drawn there), weighted by the cosine of the shooter (the hemicube's delta
// form factors; the hemisphere buffer is Nusselt's analogue, so every pixel inside the disk weighs the
// same). Where no eye sees anything open, the region's form factors to everything sum to exactly the
// covered share, and the shot delivers that (gl_shot_backend.cpp): the receivers' analytic form factors
// from the whole region, each gated by one eye's visibility, do not sum to it when visibility and form
// factor vary together across the region (an eye drawn beside a column sees the column fill half its
// view, but the column gets only the region-wide form factor: seed3's room C floor shots delivered 22 %
// too little). Where an eye sees open space, one point's share of it is not the region's.
//
// Back faces next to the eye are left out, as the rim's gaps are (main()).
//
// A pixel in every 4 × 4 stands for its block: the covered share of a closed room's hemisphere is 1 at any
// sampling, and the uncovered parts (the back of a lamp seen from the ceiling, openings to nothing) span
// many pixels; the full resolution cost as much as the receive pass (seed3: 13 s of 44). One invocation
// per sampled column of one region's layer; the CPU adds the columns.
#include "common.glsl"
#define STRIDE 4
layout(local_size_x = 16) in;
layout(std430, binding = 0) readonly buffer Patches {
  PatchInfo patches[];
};
// (covered, open, total) weight: covered by a receiver facing the eye, open (showing nothing at all).
layout(std430, binding = 22) writeonly buffer Coverage {
  vec4 coverage[];
};

layout(binding = 0) uniform isampler2DArray uItems;
layout(binding = 1) uniform sampler2DArray uDistances;  // distance from the eye of what each pixel shows
uniform int uItemSize;  // hemisphere: edge of the square buffer; hemicube: edge of a face
uniform mat3 uToShooter;
uniform float uNearBack;  // m: a back face nearer the eye than this is left out (main())

// Weight of pixel (x, y) and its centre's direction in shooter coordinates (z up the normal).
float pixelWeight(int x, int y, out vec3 dir) {
  int n = uItemSize;
  float cx = (float(x) + 0.5) / float(n) * 2.0 - 1.0;
#ifdef HEMISPHERE
  float cy = (float(y) + 0.5) / float(n) * 2.0 - 1.0;
  float r2 = cx * cx + cy * cy;
  dir = vec3(cx, cy, sqrt(max(1.0 - r2, 0.0)));
  return r2 < 1.0 ? 1.0 : 0.0;
#else
  if (y < n) {
    float cy = (float(y) + 0.5) / float(n) * 2.0 - 1.0;
    dir = vec3(cx, cy, 1.0);
    float d = 1.0 + cx * cx + cy * cy;
    return 1.0 / (d * d);
  }
  // Side faces as in visibility.glsl: face-local (x, height above the shooter's plane, 1).
  int half_ = n / 2;
  int face = 1 + (y - n) / half_;
  float h = (float((y - n) % half_) + 0.5) / float(half_);
  vec3 f = vec3(cx, h, 1.0);
  dir = face == 1   ? vec3(f.z, f.x, f.y)
        : face == 2 ? vec3(-f.z, -f.x, f.y)
        : face == 3 ? vec3(-f.x, f.z, f.y)
                    : vec3(f.x, -f.z, f.y);
  float d = 1.0 + cx * cx + h * h;
  return h / (d * d);
#endif
}

void main() {
  int column = int(gl_GlobalInvocationID.x);
  int layer = int(gl_GlobalInvocationID.y);
  int n = uItemSize;
  int columns = (n + STRIDE - 1) / STRIDE;
  if (column >= columns) return;
  int x = min(column * STRIDE + STRIDE / 2, n - 1);
#ifdef HEMISPHERE
  int rows = n;
#else
  int rows = 3 * n;
#endif
  float covered = 0.0, open = 0.0, total = 0.0;
  for (int y = STRIDE / 2; y < rows; y += STRIDE) {
    vec3 dir;
    float w = pixelWeight(x, y, dir);
    int id = texelFetch(uItems, ivec3(x, y, layer), 0).r;
#ifdef HEMISPHERE
    // Near the rim (within 26° of the shooter's plane) a pixel showing nothing is taken for a gap, not
    // open space: an edge passing close to the eye is tessellated evenly along its length, not its
    // angle, so its image near the rim is a few long chords (seed1's closed rooms read 1–17 % open,
    // median 1 %; 0.1 % without that ring), which kept their shots' gathered, low totals.
    if (id == -1 && dot(dir.xy, dir.xy) > 0.81) continue;
#endif
    // A back face within a shooter texel of the eye: the eye's texel ends against it or lies in the gap
    // over it (a ceiling over a lamp's back 1 cm below). Its centre's view is not its light's: the texel
    // was lit through its open side and its light leaves that way, yet where a region lies mostly over
    // the lamp its power is all in the texels along the lamp's edges, each eye lands on one and sees the
    // back over half its view, and the shot delivered only what it saw covered (openings, hemisphere
    // buffer: 2.2 % of room A's ceiling shots lost at 0.5 m regions, 0.1 % with this rule).
    bool facing = id >= 0 && dot(uToShooter * patches[id].normal.xyz, dir) < 0.0;
    if (id >= 0 && !facing && texelFetch(uDistances, ivec3(x, y, layer), 0).r < uNearBack) continue;
    total += w;
    if (facing) covered += w;
    if (id == -1) open += w;
  }
  coverage[layer * columns + column] = vec4(covered, open, total, 0.0);
}
