// Writes the patch ID and the distance of what the pixel shows (visibility.glsl tests receivers against
// it), and flags the patch as seen. The flags are a superset of the visible patches (a fragment drawn
// before a nearer one still flags its patch), which only costs the receiver pass some work; the exact test
// is per texel (visibility.glsl).
flat in int vPatch;
in vec3 vLocal;
layout(location = 0) out int outPatch;
layout(location = 1) out float outDistance;
layout(std430, binding = 2) buffer Visible { uint visible[]; };

#ifdef HEMISPHERE
// The hemisphere's depth is the distance along the pixel's own direction to the triangle's plane, not
// the distance interpolated between tessellated points: those follow a curve in chords, and the two faces
// of a zero-thickness partition, tessellated differently, fought over 1–8 % of a view where only the
// front face's small bias (below) should decide. Writing the depth turns off early depth tests.
flat in vec4 vPlane;  // the triangle's unit normal and its plane's offset from the eye, n·x = w
flat in int vFromBehind;
uniform int uItemSize;
uniform float uFar;

void main() {
  vec2 c = gl_FragCoord.xy / float(uItemSize) * 2.0 - 1.0;
  vec3 dir = vec3(c, sqrt(max(1.0 - dot(c, c), 0.0)));
  float facing = dot(vPlane.xyz, dir);
  float distance = length(vLocal);
  // Grazing, or a rim pixel of a triangle that crosses the shooter's plane: the interpolated distance.
  if (abs(facing) > 1e-4) {
    float t = vPlane.w / facing;
    if (t > 0.0) distance = t;
  }
  // Seen from behind: a few depth steps farther, as in item.vert.
  gl_FragDepth = clamp(distance / uFar + (vFromBehind == 1 ? 5e-7 : 0.0), 0.0, 1.0);
  outPatch = vPatch;
  outDistance = distance;
  if (vPatch >= 0) visible[vPatch] = 1u;
}
#else
layout(early_fragment_tests) in;
void main() {
  outPatch = vPatch;
  outDistance = length(vLocal);
  if (vPatch >= 0) visible[vPatch] = 1u;
}
#endif
