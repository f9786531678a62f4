// The ray caster's glow (its GLOW variant, docs/glow.md "In the volume"), the chunk before
// raycast_march.frag.glsl (which lists them all); glow_segment.glsl and glow_emitters.glsl come
// first with glowSegment(), the emitters' uniforms and glowSpan(); glowFlushDue sums glowSegment.
// Emission without opacity, added to acc.rgb and never to acc.a. The ray's glow is integrated over
// [g_t, g_end] seen through the transmittance the reference (reference/reference.cpp) uses:
// in front of the volume 1; over a sample's segment [(k - 1/2) delta, (k + 1/2) delta] (an
// anchor's: its steps; the span's first and last reach its ends, raycast_march.frag.glsl
// stepsLength) the transmittance at its middle, T_k = (1 - acc.a) exp(-tau len / 2) (its square:
// 1 - alpha); over jumped empty blocks the (constant) transmittance; behind the volume what is
// left. The volume's span is the clipped one (clip.planes, clip.box cut volumes only): in front of
// and behind a cut the glow is seen as through empty space, as the reference sees it. Only inside
// this brick's part of the glow box (u_glow_lo, u_glow_hi), so the bricks' pieces tile every ray,
// also in a brick the clip leaves no volume in (its rectangle is the glow box's); up to the
// surface's t. After early ray termination the rest is dropped (at most 1 - u_ert of it).
//
// Consecutive segments make one piece of length L, middle t_m. Per sample two FMAs gather
// S = sum T_k len_k and the first moment of T about the piece's start; at the piece's end the
// closed form gives its exact glow G and the field's slope g'(t_m) (glowFlushDue), and
// the piece adds
//   G Tbar + g'(t_m) int (t - t_m) T dt,  Tbar = S / L,
// the first-order (in g) value of int g T. Against the reference's sum of G_k T_k it is off by
// int h (T - Tbar) dt with h = g - gbar - g'(t_m)(t - t_m) (the gbar and linear parts are
// exact); a constant integrates to 0 against T - Tbar, so h may be taken as
// g - g(t_m) - g'(t_m)(t - t_m), at most K2 L^2 / 8 in size (Taylor about t_m; K2 >= |g''| over
// the piece), while int |T - Tbar| <= L dT / 2 (T falls along the ray: dT = T_first - T_last; a
// mean absolute deviation is at most half the range): off by at most K2 L^3 dT / 16. K2 per ray
// (glowRayLength): each emitter's term on one side of its plane is a / sqrt(x^2 + rho^2) (rho^2 =
// the line's squared distance to the centre plus eps^2, x along the ray) or b / sqrt(sin^2 x^2 +
// rho^2) (to the axis), whose second derivative is at most a / rho^3 (b / rho^3) in size; summed
// over the emitters, times the largest colour channel. Across an emitter's plane the field and
// its slope jump, so a piece whose T changes never spans a plane: it is split there (g_tx, the
// first plane beyond the piece's start; a piece of constant T is exact whatever g does, so the
// front, empty blocks and the back make one piece each when they can). A piece ends before a
// segment that would make its T change and its length exceed g_lmax = (16 E / (intensity K2))^(1/3),
// E = kGlowErr: its error is then at most E dT in the image's radiance (before tone mapping),
// and the sum of dT over a ray is at most 1, so the glow inside the volume is off by at most
// E = 1/1024 per pixel (a quarter of an 8-bit level; the exponential tone map's slope is at most
// glow.exposure). Far from every core pieces are long (K2 small); near a core or axis they shrink
// to single segments, where the rule is the reference's own.
// Every brick of a ray keeps to this with its own T, which the bricks in front dim further, so
// the bound holds for the whole ray.
// glowTo() only closes a piece (g_due); the sample loops only record a segment that would close
// one (glowSample, branch-free) and stop. The closed form has a single call site in main
// (glowCatchUp at the foot of the stage loop): llvmpipe runs every if's body, masked, whenever a
// group of pixels reaches it, so each site costs every pixel a closed form whether taken or not.
uniform vec3 u_glow_lo, u_glow_hi, u_glow_hi_open;
uniform float u_glow_intensity;
const float kGlowErr = 1.0 / 1024.0;
float g_t = 0.0, g_end = 0.0;  // closed up to g_t; the glow span ends at g_end
float g_pend = 0.0;            // pending piece [g_t, g_pend], first T g_tr0; S, first moment about g_t
float g_tr0 = -1.0, g_sum = 0.0, g_mom = 0.0;  // g_tr0 -1: no segment yet
float g_lmax = 3.0e38;         // longest piece whose T may change (above)
float g_tx = 3.0e38;           // the first emitter plane beyond g_t
float g_tlim = 3.0e38;         // min(g_t + g_lmax, g_tx): a segment ending beyond may close the piece
bool g_due = false;            // a closed piece [g_due_t0, g_due_t1] to integrate
float g_due_t0 = 0.0, g_due_t1 = 0.0, g_due_s = 0.0, g_due_m = 0.0;
bool g_hit = false;            // a sample's segment [g_pend, g_hit_te] at T g_hit_tr, not yet added
float g_hit_te = 0.0, g_hit_tr = 0.0;
vec3 g_dir;
#define GLOW_STOP g_hit  // the sample loops stop at a segment that ends beyond g_tlim

// Where the ray u_eye + t g_dir crosses the plane of the emitter with texels e0, e1 (-1: parallel).
float glowPlaneT(vec4 e0, vec4 e1) {
  float ud = dot(g_dir, e1.xyz);
  return ud != 0.0 ? dot(e0.xyz - u_eye, e1.xyz) / ud : -1.0;
}
// The emitters' texels (render/glow/glow_gl.h's layout: (centre, a), (direction, b), (colour, 0)).
// g_lmax of the ray o + s u over its glow span [s0, s1] (above). Each term's |g''| is at most
// a / rho^3 (rho: the line's closest approach, with eps) and, pointwise, 2 a / R^3
// (|2 y^2 - rho^2| <= 2 R^2), so over the part of the span on the term's side of the plane it is
// at most min(a / rho^3, 2 a / Rmin^3), Rmin at the point of that part closest to the centre
// (sphere) or the axis (cylinder): a ray passing a core on the other side of its plane, or far
// from it, gets a small K2. Closest points are computed as vectors (no difference of squares).
float glowTermBound(vec3 w0, vec3 w1, float lo, float hi, float e2) {
  if (!(hi >= lo)) return 0.0;  // the span has no part on this side
  float q = dot(w1, w1);
  float tc = q > 1e-30 ? -dot(w0, w1) / q : lo;
  vec3 c = w0 + clamp(tc, lo, hi) * w1;        // the part's closest point
  vec3 c0 = q > 1e-30 ? w0 - dot(w0, w1) / q * w1 : w0;  // the whole line's
  float rm = inversesqrt(dot(c, c) + e2), r0 = inversesqrt(dot(c0, c0) + e2);
  return min(r0 * r0 * r0, 2.0 * rm * rm * rm);
}
// Also gives tx, the first emitter plane the ray crosses beyond s0 (3e38: none), in the same loop
// over the emitters (their texels fetched once per ray).
float glowRayLength(vec3 o, vec3 u, float s0, float s1, out float tx) {
  float k2 = 0.0, e2 = u_glow_eps * u_glow_eps;
  tx = 3.0e38;
  for (int i = 0; i < u_glow_count; ++i) {
    vec4 e0 = texelFetch(u_glow_emitters, ivec2(0, i), 0), e1 = texelFetch(u_glow_emitters, ivec2(1, i), 0);
    vec3 col = texelFetch(u_glow_emitters, ivec2(2, i), 0).rgb;
    vec3 p = o - e0.xyz;
    // The span's part on the cylinder's side (height >= 0) and on the sphere's.
    float h0 = dot(p, e1.xyz), ud = dot(u, e1.xyz);
    float tp = ud != 0.0 ? -h0 / ud : 0.0;
    float ulo = s0, uhi = s1, dlo = s0, dhi = s1;
    if (ud > 0.0) { ulo = max(s0, tp); dhi = min(s1, tp); }
    else if (ud < 0.0) { uhi = min(s1, tp); dlo = max(s0, tp); }
    else if (h0 >= 0.0) dhi = -1.0e38;
    else uhi = -1.0e38;
    float cyl = glowTermBound(p - h0 * e1.xyz, u - ud * e1.xyz, ulo, uhi, e2);
    float sph = glowTermBound(p, u, dlo, dhi, e2);
    k2 += max(max(col.r, col.g), col.b) * max(e1.w * cyl, e0.w * sph);
    float tc = glowPlaneT(e0, e1);
    if (tc > s0) tx = min(tx, tc);
  }
  float x = 16.0 * kGlowErr / max(u_glow_intensity * k2, 1e-30);
  return x > 1e30 ? 3.0e38 : pow(x, 1.0 / 3.0);
}
// The closed piece [g_due_t0, g_due_t1]: its exact glow G (glowSegment per emitter), the field's
// slope g'(t_m) at its middle (the side of each plane as glowSegment takes it) and the next plane
// crossing beyond g_t (as glowRayLength finds the first), in one loop over the emitters: each
// emitter's texels are fetched once per piece instead of three times (three loops), which cost 8
// emitters at 512^2 about a tenth of the frame's CPU (docs/glow.md).
void glowFlushDue(inout vec4 acc) {
  if (g_due) {
    float len = g_due_t1 - g_due_t0, tm = 0.5 * (g_due_t0 + g_due_t1);
    // int (t - t_m) T dt; zero for a piece of constant T.
    float m = g_due_m - 0.5 * len * g_due_s;
    float e2 = u_glow_eps * u_glow_eps, tx = 3.0e38;
    vec3 g = vec3(0.0), slope = vec3(0.0);
    for (int i = 0; i < u_glow_count; ++i) {
      vec4 e0 = texelFetch(u_glow_emitters, ivec2(0, i), 0), e1 = texelFetch(u_glow_emitters, ivec2(1, i), 0);
      vec3 col = texelFetch(u_glow_emitters, ivec2(2, i), 0).rgb;
      float along = glowSegment(e0.xyz, e1.xyz, e0.w, e1.w, u_glow_eps, u_eye, g_dir, g_due_t0, g_due_t1);
      g += col * along;
      vec3 p = u_eye - e0.xyz + tm * g_dir;
      bool up = dot(p, e1.xyz) >= 0.0;
      vec3 q = up ? p - dot(p, e1.xyz) * e1.xyz : p;
      vec3 v = up ? g_dir - dot(g_dir, e1.xyz) * e1.xyz : g_dir;
      float r = inversesqrt(dot(q, q) + e2);
      slope -= col * ((up ? e1.w : e0.w) * dot(q, v) * r * r * r);
      float tp = glowPlaneT(e0, e1);
      tx = tp > g_t ? min(tx, tp) : tx;
    }
    g *= g_due_s / len;
    if (m != 0.0) g += slope * m;
    acc.rgb += u_glow_intensity * g;
    g_tx = tx;
    g_tlim = min(g_t + g_lmax, g_tx);
  }
  g_due = false;
}
// Closes the pending piece (the caller has integrated any earlier closed one).
void glowClose() {
  if (g_pend > g_t) {
    g_due = true;
    g_due_t0 = g_t;
    g_due_t1 = g_pend;
    g_due_s = g_sum;
    g_due_m = g_mom;
  }
  g_t = g_pend;
  g_sum = 0.0;
  g_mom = 0.0;
  g_tr0 = -1.0;
}
void glowAdd(float te, float tr) {
  g_tr0 = max(g_tr0, tr);  // the first T (T falls along the ray)
  float len = te - g_pend;
  g_sum += tr * len;
  g_mom += tr * len * (0.5 * (te + g_pend) - g_t);
  g_pend = te;
}
// The segment from the pending piece's end to t_end, seen through transmittance tr.
void glowTo(float t_end, float tr) {
  float te = min(t_end, g_end);
  if (!(te > g_pend)) return;
  // The segment would make the piece's T change (tr < g_tr0: never for an empty piece) and end
  // beyond g_tlim: close the piece before it if the piece already spans a plane or would grow
  // too long, else split the segment at the plane it crosses.
  if (te > g_tlim && tr < g_tr0) {
    if (g_pend > g_tx || te - g_t > g_lmax) glowClose();
    else {
      glowAdd(g_tx, tr);
      glowClose();
    }
  }
  glowAdd(te, tr);
}
// A sample loop's segment, branch-free: llvmpipe runs 8-16 pixels in lock-step and executes an
// if's body, masked, whenever any lane takes it, so glowTo's closing code in the sample loop
// cost every sample the masked stores of a dozen globals. Here a segment ending beyond g_tlim
// and would change T is only recorded (g_hit) and the loop stops; glowCatchUp at the block
// loop's top runs glowTo's rule on it.
void glowSample(float t_end, float tr) {
  float te = min(t_end, g_end);
  g_hit = te > g_tlim && tr < g_tr0 && te > g_pend;  // glowTo's test (a clipped segment: none)
  g_hit_te = te;
  g_hit_tr = tr;
  float w = g_hit ? 0.0 : tr * max(te - g_pend, 0.0);
  g_sum += w;
  g_mom += w * (0.5 * (te + g_pend) - g_t);
  g_tr0 = max(g_tr0, tr);  // the first T (T falls along the ray; a hit's T is not above it)
  g_pend = g_hit ? g_pend : max(g_pend, te);
}
// The hit segment, if any, by the rule; then the closed piece, if any.
void glowCatchUp(inout vec4 acc) {
  if (g_hit) {
    g_hit = false;
    glowTo(g_hit_te, g_hit_tr);
  }
  glowFlushDue(acc);
}
// The glow of the ray u_eye + t dir through this brick, begun: its span (up to the particle surface
// at pixel px), the longest piece whose T may change and the first emitter plane, and the part in
// front of the brick's blocks, [g_t, t0] (nothing closes: no piece is pending yet). A ray that
// misses the blocks (t0 >= t1) goes through the march as every other (no early return: llvmpipe
// would run that return's closed form, masked, for every pixel), its span one piece at T = 1.
void glowBegin(vec3 dir, ivec2 px, float t0, float t1) {
  g_dir = dir;
  if (!glowSpan(u_eye, dir, u_glow_lo, u_glow_hi, u_glow_hi_open, g_t, g_end)) g_end = g_t;
  g_pend = g_t;
  if (surfaceAt(px)) g_end = min(g_end, texelFetch(u_surface, px, 0).x);
  g_lmax = glowRayLength(u_eye, dir, g_t, g_end, g_tx);
  g_tlim = min(g_t + g_lmax, g_tx);
  if (t0 < t1) glowTo(t0, 1.0);
}
