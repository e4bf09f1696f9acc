// Flags every patch that owns at least one item-buffer pixel, and the shooter itself (whose residual
// is zeroed by the statistics pass). Later passes only touch flagged patches.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(binding = 0) uniform isampler2DArray uItems;
uniform int uLayers;  // the shooter's regions
layout(std430, binding = 2) buffer Visible { uint visible[]; };
uniform int uShooter;

void main() {
  ivec2 size = textureSize(uItems, 0).xy;
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u && uShooter >= 0) visible[uShooter] = 1u;
  if (i >= uint(size.x * size.y * uLayers)) return;
  int pixel = int(i) % (size.x * size.y), layer = int(i) / (size.x * size.y);
  int id = texelFetch(uItems, ivec3(pixel % size.x, pixel / size.x, layer), 0).r;
  if (id >= 0) visible[id] = 1u;
}
