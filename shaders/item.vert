// Item buffer: every scene triangle drawn with its patch ID, as seen from the shooter's centre.
// Hemicube: one face, a standard perspective projection, so straight edges stay straight.
// HEMISPHERE: the thesis's single-pass hemispherical projection (item_hemisphere.tese), where a straight
// edge becomes a curve; here each triangle only passes through to the tessellator (item_hemisphere.tesc).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in int aPatch;
layout(location = 2) in vec3 aNormal;  // the side its patch receives on

uniform vec3 uEye;
uniform mat3 uToShooter;  // rows: shooter tangent, bitangent, normal
uniform float uFar;

#ifdef HEMISPHERE
out vec3 tcLocal;
flat out int tcPatch;
flat out int tcFromBehind;
void main() {
  tcLocal = uToShooter * (aPosition - uEye);
  tcPatch = aPatch;
  tcFromBehind = dot(uToShooter * aNormal, tcLocal) > 0.0 ? 1 : 0;
}
#else
flat out int vPatch;
out vec3 vLocal;  // the point relative to the eye, for its distance (item.frag)
uniform mat3 uFace;     // rows: face right, up, forward in shooter coordinates
uniform float uNear;
uniform int uHalfFace;  // 1 for the side faces, which keep only the half above the shooter's plane

out float gl_ClipDistance[1];

void main() {
  vPatch = aPatch;
  vec3 local = uToShooter * (aPosition - uEye);
  vLocal = local;
  vec3 v = uFace * local;
  float zc = (v.z * (uFar + uNear) - 2.0 * uFar * uNear) / (uFar - uNear);
  float y = uHalfFace == 1 ? 2.0 * v.y - v.z : v.y;
  gl_Position = vec4(v.x, y, zc, v.z);
  gl_ClipDistance[0] = local.z;
  // A triangle seen from behind is drawn a few depth steps farther, so that where it coincides with a
  // front face (the two sides of a zero-thickness partition) the front face shows, not whichever depth
  // rounding favours: a shooter on one side saw the other side's patch over 40 % of the partition, light
  // that no receiver took (openings C, converged: 4 % dark). 1e-6 in NDC is ~16 float steps of the depth
  // buffer near 1, and moves a surface by less than 0.5 % of its distance at the far plane.
  if (dot(uToShooter * aNormal, local) > 0.0) gl_Position.z += 1e-6 * gl_Position.w;
}
#endif
