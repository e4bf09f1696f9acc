// Declarations shared by the solver's compute passes. The layout of every buffer is mirrored in
// radiosity/gpu/gl_shot_backend.h (GpuPatch, GpuStats, GpuNode, GpuRegion, GpuSelection).
#define PI 3.14159265358979

struct PatchInfo {
  ivec4 rect;      // chart x, y, w, h in atlas texels
  ivec4 tiles;     // x: its first 8×8 tile, y: how many
  vec4 origin;     // texel (i, j) of the chart samples origin + (i + ½) texelU + (j + ½) texelV (m)
  vec4 texelU, texelV;
  vec4 normal;
};

struct PatchStats {
  vec4 unshot;     // Σ residual × area (rgb), W
  vec4 incident;   // Σ irradiance × area (rgb), W
  vec4 absorbed;   // Σ (1 − ρ) irradiance × area (rgb), W
};

// The shooter's residual pyramid (shooter_pyramid.comp): per visibility region, levels k >= 1 of nodes
// covering 2^k × 2^k texels from the region's corner (clipped to the region); level 0 is the texels.
struct Node {
  vec4 centreArea;      // area-weighted centre (m), area (m²; 0: no texel of the shooter)
  vec4 radiosityRadius; // mean unshot radiosity (rgb, W/m²), bounding radius around the centre (m)
  // Where its unshot power lies, in texels from its region's corner along texelU and texelV: the mean
  // (xy) and the variance (zw) of the power over its texels (each texel uniform over its square); by
  // area where it holds no power.
  vec4 moments;
};

// Entries (regions and their replicas, one eye each) of a shot: gl_shot_backend.h's kMaxEyes.
#define MAX_REGIONS 64
#define MAX_LEVELS 14
// Per region: its texel rectangle in the atlas (x0, y0, x1, y1, exclusive), its top level (1×1 nodes),
// and where each level's nodes start in the node buffer (row-major within a level).
struct Region {
  ivec4 rect;
  ivec4 top;  // x: the top level
  int levelOffset[MAX_LEVELS + 2];
};
layout(std430, binding = 6) readonly buffer Regions { Region regions[]; };

ivec2 levelDims(ivec4 rect, int k) { return ((rect.zw - rect.xy) + ((1 << k) - 1)) >> k; }

// A work list filled by atomic appends: `count` entries, then the indirect dispatch arguments.
#define WORK_LIST_WIDTH 32768u
