// The atlas's per-texel data, row-major like the atlas (index = y × width + x), in shader storage
// buffers: the same memory reads as rgba32f images on a GPU, read back with one call, and on llvmpipe a
// trivial read-add-write pass costs 29 ns/texel this way against 49 ns with imageLoad/imageStore
// (bench/pass_probe.cpp, 2048², 2 loaded cores).
layout(std430, binding = 9) buffer PosArea { vec4 posArea[]; };          // position (m), area (m²)
layout(std430, binding = 10) buffer NormalPatch { vec4 normalPatch[]; };  // unit normal, patch ID (-1: padding)
layout(std430, binding = 11) buffer Albedo { vec4 albedo[]; };
layout(std430, binding = 12) buffer Radiosity { vec4 radiosity[]; };      // W/m²
layout(std430, binding = 13) buffer Residual { vec4 residual[]; };        // unshot W/m²
layout(std430, binding = 14) buffer Incident { vec4 incident[]; };        // irradiance received, W/m²
uniform int uAtlasWidth;
int texel(ivec2 t) { return t.y * uAtlasWidth + t.x; }
