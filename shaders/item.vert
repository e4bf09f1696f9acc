// Item buffer: every scene triangle drawn with its patch ID, as seen from the shooter's centre.
// HEMISPHERE: the thesis's single-pass hemispherical projection (p = normalize(pos in shooter frame),
// xy = p.xy, depth = distance), whose straight rasterised edges are wrong for large triangles (fig. 6.2).
// Otherwise one face of a hemicube: a standard perspective projection, so straight edges stay straight.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in int aPatch;
layout(location = 2) in vec3 aNormal;  // the side its patch receives on
flat out int vPatch;
out vec3 vLocal;  // the point relative to the eye, for its distance (item.frag)

uniform vec3 uEye;
uniform mat3 uToShooter;  // rows: shooter tangent, bitangent, normal
uniform float uFar;
#ifndef HEMISPHERE
uniform mat3 uFace;       // rows: face right, up, forward in shooter coordinates
uniform float uNear;
uniform int uHalfFace;    // 1 for the side faces, which keep only the half above the shooter's plane
#endif

out float gl_ClipDistance[1];

void main() {
  vPatch = aPatch;
  vec3 local = uToShooter * (aPosition - uEye);
  bool fromBehind = dot(uToShooter * aNormal, local) > 0.0;
  vLocal = local;
#ifdef HEMISPHERE
  float d = length(local);
  vec3 p = local / max(d, 1e-12);
  gl_Position = vec4(p.xy, 2.0 * d / uFar - 1.0, 1.0);
  gl_ClipDistance[0] = local.z;  // the half-space behind the shooter is not part of the hemisphere
#else
  vec3 v = uFace * local;
  float zc = (v.z * (uFar + uNear) - 2.0 * uFar * uNear) / (uFar - uNear);
  float y = uHalfFace == 1 ? 2.0 * v.y - v.z : v.y;
  gl_Position = vec4(v.x, y, zc, v.z);
  gl_ClipDistance[0] = local.z;
#endif
  // A triangle seen from behind is drawn a few depth steps farther, so that where it coincides with a
  // front face (the two sides of a zero-thickness partition) the front face shows, not whichever depth
  // rounding favours: a shooter on one side saw the other side's patch over 40 % of the partition, light
  // that no receiver took (openings C, converged: 4 % dark). 1e-6 in NDC is ~16 float steps of the depth
  // buffer near 1, and moves a surface by less than 0.5 % of its distance at the far plane.
  if (fromBehind) gl_Position.z += 1e-6 * gl_Position.w;
}
