// Item-buffer lookup of a receiver point, with the same projection the item buffer was drawn with.
//
// A receiver is visible when its own pixel shows its patch, or when what its pixel shows lies behind the
// receiver's own plane (its own patch missed by rasterisation), or in that plane on a face that covers
// the receiver (the coincident back face of a zero-thickness partition; SEEN_PATCH_COVERS, in the receive
// pass): none of these can shadow it. A face merely in the same plane can be the far side of a wall. Anything in front of
// the plane hides it, however close: a tolerance of one pixel's footprint let light through a lamp 1 cm
// under a ceiling (measured: rel. RMSE 2.6 % → 9 % on seed1). This is a point test at the receiver's own
// direction, so along a door frame's silhouette it is right on average; the thesis's 3×3 test
// (uNeighbourhood = 1, kept to measure against) counts every texel within a pixel of the silhouette as
// fully lit: +9 % in seed1's room B at the default stop, growing as the item buffer shrinks (issue 11).
uniform int uItemSize;       // hemisphere: edge of the square buffer; hemicube: edge of a face
uniform int uNeighbourhood;  // r > 0: also accept the patch anywhere in the (2r+1)² pixels around
uniform float uPlaneSlack;  // metres, for float rounding

layout(binding = 0) uniform isampler2DArray uItems;     // one layer per shooter region
layout(binding = 1) uniform sampler2DArray uDistances;  // distance from the eye of what each pixel shows

bool findIn(ivec2 p, ivec2 lo, ivec2 hi, int id, int layer) {
  for (int dy = -uNeighbourhood; dy <= uNeighbourhood; ++dy)
    for (int dx = -uNeighbourhood; dx <= uNeighbourhood; ++dx) {
      if (dx == 0 && dy == 0) continue;  // tried first
      ivec2 q = clamp(p + ivec2(dx, dy), lo, hi);
      if (texelFetch(uItems, ivec3(q, layer), 0).r == id) return true;
    }
  return false;
}

#ifdef SEEN_PATCH_COVERS
// Defined by the including shader: whether the receiver lies on patch `seen`'s chart, i.e. the pixel shows
// a face coincident with the receiver (a zero-thickness partition's back face), not merely one in its
// plane. A floor seen in front of a partition's foot is in the plane of the floor behind it: accepted, it
// leaked light under the wall into the next room wherever a pixel's footprint reached past the wall
// (openings: C +5 % at 20 texels/m, +1.5 % with a buffer twice as fine; issue 11).
bool seenPatchCovers(int seen);
// Defined by the including shader: whether patch `seen` lies across the segment from the eye to the receiver.
bool seenPatchBlocks(int seen, vec3 local);
#endif

// `local`: the receiver relative to the eye; `normal`: its normal; `dir`: pixel p's centre direction (any
// length), all in shooter coordinates.
// When the lookup says hidden: how far what hides the receiver is from it (m), in gOccluderGap; whether
// the pixel shows the receiver's own patch, in gSeenOwn.
float gOccluderGap = 0.0;
bool gSeenOwn = false;

bool visibleAt(ivec2 p, ivec2 lo, ivec2 hi, vec3 dir, vec3 local, vec3 normal, int id, int layer) {
  int seenId = texelFetch(uItems, ivec3(p, layer), 0).r;
  gSeenOwn = seenId == id;
  if (seenId == id) return true;
  float d = texelFetch(uDistances, ivec3(p, layer), 0).r;
  vec3 seen = normalize(dir) * d;
  gOccluderGap = distance(seen, local);
  float off = dot(normal, seen - local);
#ifdef SEEN_PATCH_COVERS
  // Behind the plane: the ray crossed it unhindered next to the receiver, unless what the pixel shows lies
  // across the segment from the eye to the receiver: the ray then crossed the receiver's plane beyond a wall
  // the receiver's surface ends against (a side wall's T-junction with a partition). In the plane: only a
  // face covering the receiver itself, and not lying across that segment (a partition seen a hair under
  // the ceiling the room behind it shares).
  if (off < -uPlaneSlack && (seenId < 0 || !seenPatchBlocks(seenId, local))) return true;
  if (off >= -uPlaneSlack && off <= uPlaneSlack &&
      (seenId < 0 || (seenPatchCovers(seenId) && !seenPatchBlocks(seenId, local))))
    return true;
#else
  if (off <= uPlaneSlack) return true;
#endif
  return uNeighbourhood > 0 && findIn(p, lo, hi, id, layer);
}

// `local` is the receiver relative to the region's eye in shooter coordinates (z along the normal, > 0),
// `normal` the receiver's normal in the same frame.
bool visibleFromShooter(vec3 local, vec3 normal, int id, int layer) {
  int n = uItemSize;
#ifdef HEMISPHERE
  vec2 xy = normalize(local).xy;
  ivec2 p = clamp(ivec2(floor((xy * 0.5 + 0.5) * float(n))), ivec2(0), ivec2(n - 1));
  vec2 c = (vec2(p) + 0.5) / float(n) * 2.0 - 1.0;
  // A pixel straddling the rim with its centre outside the disk shows nothing (no direction there), and
  // one just inside may fall between the rim and the chords that approximate it (item_hemisphere.tesc):
  // nothing could hide the receiver there, so its neighbour inwards does the test. Grazing receivers
  // behind a door frame got light this way (openings, room C: 5.0 % too bright → 3.0 % for the pixels
  // outside the disk; 3.9 % → 2.4 % for the two-pixel band).
  float rimBand = 1.0 - 4.0 / float(n);  // two pixels
  if (dot(c, c) >= 1.0 || (dot(c, c) > rimBand * rimBand && texelFetch(uItems, ivec3(p, layer), 0).r == -1)) {
    if (abs(c.x) >= abs(c.y)) p.x -= int(sign(c.x)); else p.y -= int(sign(c.y));
    c = (vec2(p) + 0.5) / float(n) * 2.0 - 1.0;
  }
  vec3 dir = vec3(c, sqrt(max(1.0 - dot(c, c), 0.0)));
  return visibleAt(p, ivec2(0), ivec2(n - 1), dir, local, normal, id, layer);
#else
  vec3 a = abs(local);
  if (local.z >= a.x && local.z >= a.y) {
    vec2 st = local.xy / local.z;
    ivec2 p = clamp(ivec2(floor((st * 0.5 + 0.5) * float(n))), ivec2(0), ivec2(n - 1));
    vec2 c = (vec2(p) + 0.5) / float(n) * 2.0 - 1.0;
    return visibleAt(p, ivec2(0), ivec2(n - 1), vec3(c, 1.0), local, normal, id, layer);
  }
  // Side faces: right, up (= shooter normal), forward as in kFaces of gl_item_buffers.cpp.
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
  ivec2 lo = ivec2(0, y0), hi = ivec2(n - 1, y0 + half_ - 1);
  ivec2 p = clamp(ivec2(int(floor((v.x / v.z * 0.5 + 0.5) * float(n))), y0 + int(floor(v.y / v.z * float(half_)))),
                  lo, hi);
  // The pixel centre's direction in face coordinates, then back to shooter coordinates (the inverse of
  // the swizzles above).
  vec3 f = vec3((float(p.x) + 0.5) / float(n) * 2.0 - 1.0, (float(p.y - y0) + 0.5) / float(half_), 1.0);
  vec3 dir = face == 1 ? vec3(f.z, f.x, f.y)
           : face == 2 ? vec3(-f.z, -f.x, f.y)
           : face == 3 ? vec3(-f.x, f.z, f.y)
                       : vec3(f.x, -f.z, f.y);
  return visibleAt(p, lo, hi, dir, local, normal, id, layer);
#endif
}
