// Declarations shared by the solver's compute passes. The layout of every buffer is mirrored in
// radiosity/gpu_solver.cpp (GpuPatch, GpuStats, GpuBlock, GpuSelection).
#define PI 3.14159265358979

struct PatchInfo {
  ivec4 rect;      // chart x, y, w, h in atlas texels
};

struct PatchStats {
  vec4 unshot;     // Σ residual × area (rgb), W
  vec4 incident;   // Σ irradiance × area (rgb), W
  vec4 absorbed;   // Σ (1 − ρ) irradiance × area (rgb), W
};

// One piece of the shooter. blocks[0 .. regions) are its visibility regions (each with its own item
// buffer), blocks[regions ..) its texel blocks, every block inside one region.
struct Block {
  vec4 centreArea;      // area-weighted centre (m), area (m²)
  vec4 radiosityRadius; // mean unshot radiosity (rgb, W/m²), bounding radius around the centre (m)
  ivec4 rect;           // texel rectangle x0, y0, x1, y1 (exclusive)
  ivec4 region;         // x: the region a block lies in (regions: their own index)
  vec4 lobe;            // directional emission of the piece (directional.glsl), 0 = Lambertian
};

// A work list filled by atomic appends: `count` entries, then the indirect dispatch arguments.
#define WORK_LIST_WIDTH 32768u
