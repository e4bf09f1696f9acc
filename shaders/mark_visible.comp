// Flags every patch that owns at least one item-buffer pixel, and the shooter itself (whose residual
// is zeroed by the statistics pass). Later passes only touch flagged patches.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(binding = 0) uniform isampler2D uItems;
layout(std430, binding = 2) buffer Visible { uint visible[]; };
uniform int uShooter;

void main() {
  ivec2 size = textureSize(uItems, 0);
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u && uShooter >= 0) visible[uShooter] = 1u;
  if (i >= uint(size.x * size.y)) return;
  int id = texelFetch(uItems, ivec2(int(i) % size.x, int(i) / size.x), 0).r;
  if (id >= 0) visible[id] = 1u;
}
