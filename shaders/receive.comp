// One shot (thesis ch. 6, step 3): every texel of a visible patch that sees the shooter's centre in the
// item buffer gathers ΔB_i = ρ_i Σ_k ΔB_k F(dA_i → A_k), with the disk approximation
// F ≈ A_k cosθ_i cosθ_k / (π r² + A_k) over the shooter's pieces: the whole patch when the receiver is
// far from it (r > farField × radius), else its texel blocks, and inside a near block its texels.
#include "common.glsl"
#include "visibility.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) readonly uniform image2D uPosArea;
layout(binding = 1, rgba32f) readonly uniform image2D uNormalPatch;
layout(binding = 2, rgba32f) readonly uniform image2D uAlbedo;
layout(binding = 3, rgba32f) uniform image2D uRadiosity;
layout(binding = 4, rgba32f) uniform image2D uResidual;
layout(binding = 5, rgba32f) uniform image2D uIncident;
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };
layout(std430, binding = 4) readonly buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 6) readonly buffer Blocks { Block blocks[]; };

uniform int uShooter;
uniform int uBlockCount;  // texel blocks after blocks[0]
uniform vec3 uEye;
uniform mat3 uToShooter;
uniform vec3 uShooterNormal;
uniform float uFarField;

// ΔB_k F(dA_x → disk k): the receiver at x with normal n, a disk of area A at c facing uShooterNormal.
vec3 disk(vec3 x, vec3 n, vec3 c, float area, vec3 radiosity) {
  vec3 v = c - x;
  float r2 = dot(v, v);
  float ci = dot(n, v), cs = -dot(uShooterNormal, v);
  if (ci <= 0.0 || cs <= 0.0 || r2 <= 0.0) return vec3(0.0);
  return radiosity * (area * ci * cs / (r2 * (PI * r2 + area)));
}

vec3 irradiance(vec3 x, vec3 n) {
  Block whole = blocks[0];
  float far2 = uFarField * whole.radiosityRadius.w;
  vec3 d = whole.centreArea.xyz - x;
  if (dot(d, d) > far2 * far2) return disk(x, n, whole.centreArea.xyz, whole.centreArea.w, whole.radiosityRadius.rgb);
  vec3 sum = vec3(0.0);
  for (int k = 1; k <= uBlockCount; ++k) {
    Block b = blocks[k];
    if (b.centreArea.w <= 0.0) continue;
    vec3 db = b.centreArea.xyz - x;
    float fb = uFarField * b.radiosityRadius.w;
    if (dot(db, db) > fb * fb) {
      sum += disk(x, n, b.centreArea.xyz, b.centreArea.w, b.radiosityRadius.rgb);
      continue;
    }
    for (int ty = b.rect.y; ty < b.rect.w; ++ty)
      for (int tx = b.rect.x; tx < b.rect.z; ++tx) {
        ivec2 t = ivec2(tx, ty);
        if (int(imageLoad(uNormalPatch, t).w) != uShooter) continue;
        vec4 pa = imageLoad(uPosArea, t);
        sum += disk(x, n, pa.xyz, pa.w, imageLoad(uResidual, t).rgb);
      }
  }
  return sum;
}

void main() {
  uint entry = gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x;
  if (entry >= tileCount) return;
  ivec4 tile = tiles[tileList[entry]];
  ivec2 t = tile.xy + ivec2(gl_LocalInvocationID.xy);
  vec4 np = imageLoad(uNormalPatch, t);
  int id = int(np.w);
  // Tiles are 8×8 from the chart corner and may overhang into a neighbour: keep only this tile's patch.
  if (id != tile.z || id == uShooter) return;
  vec3 x = imageLoad(uPosArea, t).xyz;
  vec3 local = uToShooter * (x - uEye);
  if (local.z <= 0.0 || dot(np.xyz, uEye - x) <= 0.0) return;
  if (!visibleFromShooter(local, id)) return;
  vec3 e = irradiance(x, np.xyz);
  if (e == vec3(0.0)) return;
  vec3 gained = imageLoad(uAlbedo, t).rgb * e;
  imageStore(uIncident, t, imageLoad(uIncident, t) + vec4(e, 0.0));
  imageStore(uRadiosity, t, imageLoad(uRadiosity, t) + vec4(gained, 0.0));
  imageStore(uResidual, t, imageLoad(uResidual, t) + vec4(gained, 0.0));
}
