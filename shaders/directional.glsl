// Directional emission (SolverParams::directionalEmission; radiosity/gpu/emission_lobes.h has the maths and
// the CPU twins of these functions). Included by receive.comp and shooter_pyramid.comp only when the
// program is built with DIRECTIONAL, so the default solve is unchanged. Three pieces, each self-contained:
//  - the lobe of a shooter texel (per-texel buffer) and of a pyramid node (nodeLobe, beside nodes[]);
//  - lobeFactor: f(ω) that multiplies a Lambertian form factor, ∫ f cos θ dω = π;
//  - noteArrival: the direction moments a receiver texel accumulates, read back for the next sync.
layout(std430, binding = 17) readonly buffer EmissionLobes { vec4 emissionLobe[]; };  // 0 = Lambertian
layout(std430, binding = 18) buffer Arrivals { vec4 arrivals[]; };  // Σ w (u + |u|² n_far), Σ w
layout(std430, binding = 19) buffer NodeLobes { vec4 nodeLobe[]; };  // per pyramid node, indexed like nodes[]
// Binned emission (radiosity/solve/emission_bins.h): a texel whose lobe is (0, 0, 0, −(k + 1)) emits with
// f per bin and channel from emissionLobe[k …], a bin a vec4 (red, green, blue, unused) after the texels'
// lobes (llvmpipe allows a compute shader 16 storage blocks, all taken), each channel normalised on the
// CPU so that the bilinear reading below integrates to the exitance; the square's radius is θ / (π/2).
#define BIN_GRID 18

#ifdef BINNED
#define BIN_SLOT_VEC4 (BIN_GRID * BIN_GRID)  // an emitter's bins
// A pyramid node holding binned texels has the lobe (n, −(node + 1)) and the power-weighted mean of its
// texels' bins, each channel by its own power (a Lambertian's all ones), at
// nodeLobe[uNodeBins + node · BIN_SLOT_VEC4 …]. It stands for them whole only beyond BIN_FAR of its radii,
// where it looks smaller than about half the narrowest bins (10° across): without node bins every
// receiver took a binned portal texel by texel, and openings' cells bake took 1.5× the time.
uniform int uNodeBins;
uniform vec3 uBinT1, uBinT2;  // the shooter's binFrame (receive.comp only), set from the CPU's
#define BIN_FAR 10.0

// Where unit ω leaving the shooter (ω · n > 0) lies in the concentric map's square, in cells, as
// binSquarePoint of its binFrame.
vec2 binSquarePoint(vec3 omega) {
  float a = dot(omega, uBinT1), b = dot(omega, uBinT2);
  float r = asin(min(sqrt(a * a + b * b), 1.0)) * (2.0 / PI), phi = atan(b, a);  // rings of equal θ
  if (phi < -0.25 * PI) phi += 2.0 * PI;
  vec2 xy;
  if (phi < 0.25 * PI) xy = vec2(r, r * phi * (4.0 / PI));
  else if (phi < 0.75 * PI) xy = vec2(-r * (phi - 0.5 * PI) * (4.0 / PI), r);
  else if (phi < 1.25 * PI) xy = vec2(-r, -r * (phi - PI) * (4.0 / PI));
  else xy = vec2(r * (phi - 1.5 * PI) * (4.0 / PI), -r);
  return clamp((xy + 1.0) * (0.5 * float(BIN_GRID)), vec2(0.0), vec2(float(BIN_GRID)));
}
// f per channel of bin b of the slot whose first vec4 is at `at` in emissionLobe (node: in nodeLobe).
vec3 binValue(bool node, int at, int b) { return node ? nodeLobe[at + b].rgb : emissionLobe[at + b].rgb; }

// f(ω) per channel of a binned texel's lobe (0, 0, 0, −(first + 1)) or a binned node's (n, −(node + 1)),
// n the shooter's normal: bilinear between the bins' centres, as binTaps.
vec3 binnedFactor(vec4 lobe, vec3 n, vec3 omega) {
  int k = int(-lobe.w) - 1;
  bool node = dot(lobe.xyz, n) > 0.5;
  int at = node ? uNodeBins + k * BIN_SLOT_VEC4 : k;
  vec2 s = binSquarePoint(omega) - 0.5, lo = floor(s), t = s - lo;
  ivec2 i0 = clamp(ivec2(lo), ivec2(0), ivec2(BIN_GRID - 1)), i1 = clamp(ivec2(lo) + 1, ivec2(0), ivec2(BIN_GRID - 1));
  return (1.0 - t.x) * (1.0 - t.y) * binValue(node, at, i0.y * BIN_GRID + i0.x) +
         t.x * (1.0 - t.y) * binValue(node, at, i0.y * BIN_GRID + i1.x) +
         (1.0 - t.x) * t.y * binValue(node, at, i1.y * BIN_GRID + i0.x) +
         t.x * t.y * binValue(node, at, i1.y * BIN_GRID + i1.x);
}
#endif

// f(ω) for unit ω leaving a surface of normal n: (1 − a) + a exp(−|s − s0|² / 2σ²) / (2σ² cos⁴θ),
// s = ω_t / cos θ; lobe = (s0 + a n, σ²). `blur2` widens σ² (still normalised): the receiver's footprint.
float lobeFactor(vec4 lobe, vec3 n, vec3 omega, float blur2) {
  float c = dot(omega, n);
  if (c <= 0.0) return 0.0;
  float a = dot(lobe.xyz, n);
  if (!(a > 0.0) || !(lobe.w > 0.0)) return 1.0;
  vec3 d = omega / c - n - (lobe.xyz - a * n);
  float c2 = c * c, sigma2 = lobe.w + blur2;
  return (1.0 - a) + a * exp(-dot(d, d) / (2.0 * sigma2)) / (2.0 * sigma2 * c2 * c2);
}

// The lobe seen by a receiver texel of area `area` (m²) at v from the shooter point (receiver normal n,
// shooter normal ns) is averaged over the texel, not sampled at its centre: a beam narrower than the texel
// would otherwise light it fully or not at all (hot and black texels near a portal). The texel's angular
// variance per axis, A cos θr / 12 r², in gnomonic units (stretched by about 1 / cos³θs), at most 0.1: a
// per-receiver width keeps each receiver's share right only while the lobe stays well inside the
// hemisphere, where the 1 / cos⁴θ of the gnomonic map is small.
float receiverBlur(vec3 v, vec3 n, vec3 ns, float area) {
  float r2 = dot(v, v);
  float cr = abs(dot(n, v)) * inversesqrt(r2), cs = max(abs(dot(ns, v)) * inversesqrt(r2), 0.1);
  return min(area * cr / (12.0 * r2 * cs * cs * cs), 0.1);
}

// Can a piece of this radius (m) at squared distance r2 stand for its texels as one disk or a few points?
// Only if its lobe is wider than the piece seen from there: a narrow lobe (a beam through a door) would
// otherwise be emitted from the piece's centre instead of from where each texel sends it. A node holding
// binned texels only from far off (BIN_FAR), a binned texel always (its bins are wider than it).
bool lobeResolvesPiece(vec4 lobe, vec3 n, float r2, float radius) {
#ifdef BINNED
  if (lobe.w < 0.0) return !(dot(lobe.xyz, n) > 0.5) || r2 >= BIN_FAR * BIN_FAR * radius * radius;
#endif
  return !(dot(lobe.xyz, n) > 0.0) || lobe.w * r2 >= radius * radius;
}

// A power-weighted mixture of lobes of one planar shooter (normal n), replaced by the lobe with the same
// weight, mean and variance: still normalised. `sum` = (Σ P a s0, Σ P a), `second` = (Σ P a σ², Σ P a |s0|²,
// Σ P, 1 if any is binned). Mixing the mixed lobes of groups (pyramid children) gives the same lobe as mixing all texels.
struct LobeMix {
  vec4 sum;
  vec4 second;
};
LobeMix addLobe(LobeMix mix, vec4 lobe, vec3 n, float power) {
  if (lobe.w < 0.0) {  // binned (a texel's slot, or a node already holding some): no moments to mix
    mix.second.w = 1.0;
    return mix;
  }
  float a = dot(lobe.xyz, n);
  vec3 s0 = lobe.xyz - a * n;
  float pa = power * max(a, 0.0);
  mix.sum += vec4(pa * s0, pa);
  mix.second += vec4(pa * lobe.w, pa * dot(s0, s0), power, 0.0);
  return mix;
}
vec4 mixedLobe(LobeMix mix, vec3 n) {
  if (mix.second.w > 0.0) return vec4(n, -1.0);
  if (!(mix.sum.w > 0.0) || !(mix.second.z > 0.0)) return vec4(0.0);
  vec3 s0 = mix.sum.xyz / mix.sum.w;
  float sigma2 = mix.second.x / mix.sum.w + 0.5 * max(mix.second.y / mix.sum.w - dot(s0, s0), 0.0);
  return vec4(s0 + (mix.sum.w / mix.second.z) * n, sigma2);
}

// Contribution `e` reaching a receiver of normal n from a shooter point at receiver + v: accumulates
// arrivalMoment(ω = −v̂, n_far = −n, w = e.r + e.g + e.b) into `acc`.
void noteArrival(inout vec4 acc, vec3 v, vec3 n, vec3 e) {
  float w = e.r + e.g + e.b;
  if (!(w > 0.0)) return;
  vec3 omega = -normalize(v), nFar = -n;
  vec3 u = omega - dot(omega, nFar) * nFar;
  acc += vec4(w * (u + dot(u, u) * nFar), w);
}
