// The hemisphere item buffer's tessellation: each edge cut into pieces that subtend a small angle from
// the eye (evenly in angle, item_hemisphere.tese), so that the projection's curves (a straight edge maps
// to an arc of the unit disk) are followed to about half a pixel. Drawn straight, a wall next to the eye
// lost a wedge of the view (thesis fig. 6.2): seed1's room B came out 1.48× the reference, openings' C
// 2.4×.
layout(vertices = 3) out;
in vec3 tcLocal[];
flat in int tcPatch[];
flat in int tcFromBehind[];
out vec3 teLocal[];
flat out int tePatch[];
flat out int teFromBehind[];

uniform int uItemSize;

float pieces(vec3 a, vec3 b) {
  // A piece of angle α drawn as a chord misses its arc by the sagitta, ≈ α²/8 of the disk's radius
  // (n/2 pixels): 0.56 px (7.6° at 512), within the 64 pieces an edge may have (2.8° each). What falls
  // between the chords and the rim is looked up a pixel inwards (visibility.glsl). Pieces of 5° cost
  // 1.7× the CPU for the same figures; of 10°, openings' room B came out 0.5 % darker.
  float pieceAngle = max(sqrt(9.0 / float(uItemSize)), 3.14159265 / 64.0);
  float la = length(a), lb = length(b);
  if (la <= 0.0 || lb <= 0.0) return 64.0;
  float angle = acos(clamp(dot(a, b) / (la * lb), -1.0, 1.0));
  return clamp(ceil(angle / pieceAngle), 1.0, 64.0);
}

void main() {
  teLocal[gl_InvocationID] = tcLocal[gl_InvocationID];
  tePatch[gl_InvocationID] = tcPatch[gl_InvocationID];
  teFromBehind[gl_InvocationID] = tcFromBehind[gl_InvocationID];
  if (gl_InvocationID == 0) {
    // Outer level i is the edge opposite vertex i.
    float e0 = pieces(tcLocal[1], tcLocal[2]), e1 = pieces(tcLocal[2], tcLocal[0]), e2 = pieces(tcLocal[0], tcLocal[1]);
    gl_TessLevelOuter[0] = e0;
    gl_TessLevelOuter[1] = e1;
    gl_TessLevelOuter[2] = e2;
    gl_TessLevelInner[0] = max(e0, max(e1, e2));
  }
}
