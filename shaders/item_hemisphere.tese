// The thesis's single-pass hemispherical projection of a tessellated triangle: p = normalize(the point
// in shooter coordinates), xy = p.xy (Nusselt's analogue: area in the disk is the form factor), depth =
// distance. The point is interpolated in the shooter frame, where the triangle is flat.
layout(triangles, equal_spacing, ccw) in;
in vec3 teLocal[];
flat in int tePatch[];
flat in int teFromBehind[];
flat out int vPatch;
out vec3 vLocal;  // the point relative to the eye, for its distance (item.frag)
uniform float uFar;
out float gl_ClipDistance[1];

void main() {
  vec3 local = gl_TessCoord.x * teLocal[0] + gl_TessCoord.y * teLocal[1] + gl_TessCoord.z * teLocal[2];
  vPatch = tePatch[0];
  vLocal = local;
  float d = length(local);
  // A point behind the shooter's plane goes to the disk's rim, where the hemisphere ends: clipped at
  // local.z = 0 instead, a piece crossing the plane was cut along the straight line between its projected
  // corners, well inside the rim, and left the ring around it empty (5 % of seed1's views).
  vec2 xy = local.z >= 0.0 ? local.xy / max(d, 1e-12) : local.xy / max(length(local.xy), 1e-12);
  gl_Position = vec4(xy, 2.0 * d / uFar - 1.0, 1.0);
  // Seen from behind: a few depth steps farther, as in item.vert (the hemisphere's depth is linear).
  if (teFromBehind[0] == 1) gl_Position.z += 1e-6;
  // Only a triangle wholly behind the plane (the shooter's own, anything behind it) is dropped; its
  // points would all go to the rim, and pieces inscribed in it would cover the disk.
  bool behind = teLocal[0].z <= 0.0 && teLocal[1].z <= 0.0 && teLocal[2].z <= 0.0;
  gl_ClipDistance[0] = behind ? -1.0 : 1.0;
}
