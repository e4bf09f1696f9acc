// The thesis's single-pass hemispherical projection of a tessellated triangle: xy = the direction of the
// point from the eye, in shooter coordinates (Nusselt's analogue: area in the disk is the form factor),
// depth = distance.
//
// The tessellator spaces points evenly in the triangle's parameters, and a straight edge passing close to
// the eye sweeps most of its angle in a few of those pieces: drawn as chords, they left wedges of the
// disk empty (a wall shooter 5 cm above the floor saw 8 % of its hemisphere as nothing, and 1–3 % of
// every shot in a closed box escaped). So the points are spaced evenly in angle instead: slerp along an
// edge, then from there to the third corner (exact on all three edges, so neighbours sharing an edge
// agree), and the point is where that direction meets the triangle's plane. The three ways of doing so
// are averaged, so that a triangle's points do not depend on the order of its corners: the two faces of
// a zero-thickness partition (one wound the other way) must be drawn at the same depths, for the small
// bias that lets the front face win (item.vert); one order alone striped 8 % of a view with the back.
layout(triangles, equal_spacing, ccw) in;
in vec3 teLocal[];
flat in int tePatch[];
flat in int teFromBehind[];
flat out int vPatch;
out vec3 vLocal;  // the point relative to the eye, for its distance (item.frag)
flat out vec4 vPlane;
flat out int vFromBehind;
uniform float uFar;
out float gl_ClipDistance[1];

vec3 unitOr(vec3 v, vec3 fallback) {
  float l = length(v);
  return l > 1e-20 ? v / l : fallback;
}

// The direction a fraction s of the way along the great circle from unit p to unit q.
vec3 slerpDirection(vec3 p, vec3 q, float s) {
  float angle = acos(clamp(dot(p, q), -1.0, 1.0));
  float sine = sin(angle);
  // Nearly equal directions: the chord is the arc. Nearly opposite: the edge passes through the eye and
  // the triangle is seen edge-on, with no area to draw.
  if (sine < 1e-4) return unitOr(mix(p, q, s), p);
  return unitOr(sin((1.0 - s) * angle) * p + sin(s * angle) * q, p);
}

// Along the edge p→q, then from there towards r: exact on all three edges.
vec3 twoStep(vec3 p, vec3 q, vec3 r, float wp, float wq, float wr) {
  vec3 onPQ = wp + wq > 0.0 ? slerpDirection(p, q, wq / (wp + wq)) : p;
  return slerpDirection(onPQ, r, wr);
}

void main() {
  vec3 A = teLocal[0], B = teLocal[1], C = teLocal[2];
  float u = gl_TessCoord.x, v = gl_TessCoord.y, w = gl_TessCoord.z;
  vec3 a = unitOr(A, vec3(0.0, 0.0, 1.0)), b = unitOr(B, a), c = unitOr(C, a);
  vec3 dir = unitOr(twoStep(a, b, c, u, v, w) + twoStep(b, c, a, v, w, u) + twoStep(c, a, b, w, u, v), a);

  // Where that direction meets the triangle's plane; edge-on (the eye in the plane), the plain blend.
  vec3 local = u * A + v * B + w * C;
  vec3 n = cross(B - A, C - A);
  float facing = dot(n, dir), toPlane = dot(n, A);
  if (abs(facing) > 1e-4 * length(n)) {
    float t = toPlane / facing;
    if (t > 0.0) local = dir * t;
  }
  vPatch = tePatch[0];
  vLocal = local;
  float area2 = length(n);
  vPlane = area2 > 0.0 ? vec4(n / area2, toPlane / area2) : vec4(0.0);
  vFromBehind = teFromBehind[0];
  // A direction behind the shooter's plane goes to the disk's rim, where the hemisphere ends: clipped at
  // z = 0 instead, a piece crossing the plane was cut along the straight line between its projected
  // corners, well inside the rim, and left the ring around it empty (5 % of seed1's views).
  vec2 xy = dir.z >= 0.0 ? dir.xy : unitOr(vec3(dir.xy, 0.0), vec3(1.0, 0.0, 0.0)).xy;
  // The depth written is the exact one per pixel (item.frag); this one only places the vertex.
  gl_Position = vec4(xy, 2.0 * length(local) / uFar - 1.0, 1.0);
  // Only a triangle wholly behind the plane (the shooter's own, anything behind it) is dropped; its
  // points would all go to the rim, and pieces inscribed in it would cover the disk.
  bool behind = A.z <= 0.0 && B.z <= 0.0 && C.z <= 0.0;
  gl_ClipDistance[0] = behind ? -1.0 : 1.0;
}
