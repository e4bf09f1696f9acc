// Writes the patch ID and the distance of what the pixel shows (visibility.glsl tests receivers against
// it), and flags the patch as seen. Early depth testing drops most hidden fragments, but
// a fragment drawn before a nearer one still flags its patch: the flags are a superset of the visible
// patches, which only costs the receiver pass some work; the exact test is per texel (visibility.glsl).
layout(early_fragment_tests) in;
flat in int vPatch;
in vec3 vLocal;
layout(location = 0) out int outPatch;
layout(location = 1) out float outDistance;
layout(std430, binding = 2) buffer Visible { uint visible[]; };
void main() {
  outPatch = vPatch;
  outDistance = length(vLocal);
  if (vPatch >= 0) visible[vPatch] = 1u;
}
