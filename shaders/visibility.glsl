// Item-buffer lookup of a receiver point, with the same projection the item buffer was drawn with.
// A receiver is visible when its patch ID appears in the (2r+1)² neighbourhood of its pixel (the thesis
// tests 3×3 to hide rasterisation differences along edges).
uniform int uItemSize;       // hemisphere: edge of the square buffer; hemicube: edge of a face
uniform int uNeighbourhood;  // r: 1 → 3×3

layout(binding = 0) uniform isampler2DArray uItems;  // one layer per shooter region

bool findIn(ivec2 p, ivec2 lo, ivec2 hi, int id, int layer) {
  if (texelFetch(uItems, ivec3(clamp(p, lo, hi), layer), 0).r == id) return true;  // the usual case first
  for (int dy = -uNeighbourhood; dy <= uNeighbourhood; ++dy)
    for (int dx = -uNeighbourhood; dx <= uNeighbourhood; ++dx) {
      if (dx == 0 && dy == 0) continue;  // tried first
      ivec2 q = clamp(p + ivec2(dx, dy), lo, hi);
      if (texelFetch(uItems, ivec3(q, layer), 0).r == id) return true;
    }
  return false;
}

// `local` is the receiver relative to the region's eye in shooter coordinates (z along the normal, > 0).
bool visibleFromShooter(vec3 local, int id, int layer) {
  int n = uItemSize;
#ifdef HEMISPHERE
  vec2 xy = normalize(local).xy;
  ivec2 p = ivec2(floor((xy * 0.5 + 0.5) * float(n)));
  return findIn(p, ivec2(0), ivec2(n - 1), id, layer);
#else
  vec3 a = abs(local);
  if (local.z >= a.x && local.z >= a.y) {
    vec2 st = local.xy / local.z;
    ivec2 p = ivec2(floor((st * 0.5 + 0.5) * float(n)));
    return findIn(p, ivec2(0), ivec2(n - 1), id, layer);
  }
  // Side faces: right, up (= shooter normal), forward as in hemicubeFaces() of gpu_solver.cpp.
  int face;
  vec3 v;
  if (a.x >= a.y) {
    face = local.x > 0.0 ? 1 : 2;
    v = local.x > 0.0 ? vec3(local.y, local.z, local.x) : vec3(-local.y, local.z, -local.x);
  } else {
    face = local.y > 0.0 ? 3 : 4;
    v = local.y > 0.0 ? vec3(-local.x, local.z, local.y) : vec3(local.x, local.z, -local.y);
  }
  int half_ = n / 2;
  int y0 = n + (face - 1) * half_;
  int px = int(floor((v.x / v.z * 0.5 + 0.5) * float(n)));
  int py = y0 + int(floor(v.y / v.z * float(half_)));
  return findIn(ivec2(px, py), ivec2(0, y0), ivec2(n - 1, y0 + half_ - 1), id, layer);
#endif
}
