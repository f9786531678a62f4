// What every metaball program shares (the billboard passes, render/particles/metaball_renderer.cpp,
// and the one-pass grid and slices ray casters): the camera's rays, the brick's clip interval, the
// sample lattice, the refinement probes and the shading. The first chunk of each of their
// shaders but the pyramid's reduction.
//
// The billboard ray caster (Mishima et al., ../shared/PAPERS.md §2): every pass works on
// per-pixel ray state kept in float textures:
//   state  (rgba32f): x = where the next window may start (INF: the pixel is finished),
//                     y = I at the last sample, z = t of the last sample, w = samples taken
//   hit    (rgba32f): the bracket (t_neg, I_neg, t_pos, I_pos) once a sign change is found;
//                     z > 0 marks a hit
//   next   (r32f):    start of the current window (MIN-blended, eqs. 2-4), later the refined t
//   pot, pot2 (rgba32f): the field F = sum P at the window's samples, 4 per target (additive
//                     blending, §4.2; pot2 holds samples 4-7 of an 8-sample window)
//   pyramid (rg32f, mipmapped): per pixel [lo, hi] of the distances a pass needs, reduced 2x2 by
//                     min/max so one fetch bounds a whole tile (§4.3 culling)
// Distances t are along the unit ray from its origin (the eye; orthographic: the pixel's point on
// the eye plane, Camera::pixelRay); samples sit on the lattice t = k*w, shared by every brick, so
// bricks sample the same points a single brick would.
uniform vec3 u_eye;       // the eye (orthographic: the centre of the eye plane)
uniform vec3 u_fwd;
uniform vec3 u_right_s;   // camera right * tan(fov/2) * aspect (orthographic: parallel_scale * aspect)
uniform vec3 u_up_s;      // camera up * tan(fov/2) (orthographic: parallel_scale)
uniform int u_orthographic;  // 1: parallel rays along u_fwd, each from its pixel's eye-plane point
uniform vec2 u_size;      // image width, height
uniform float u_h;        // influence radius
uniform float u_T;        // threshold
uniform float u_w;        // sample step
uniform vec3 u_box_lo;    // clip box: the brick this image belongs to
uniform vec3 u_box_hi;
uniform float u_lookahead;  // how far past a pixel's next sample the advance pass looks
uniform int u_window;       // samples per window: 4 (one RGBA target, the paper) or 8 (two)
const float INF = 1e30;

// The ray of the pixel whose centre is fc (gl_FragCoord.xy), Camera::pixelRay's formula, so GL and
// the CPU reference trace the same rays: pixelRay() sets its origin g_eye (the eye, or the pixel's
// point on the eye plane when orthographic) and returns its unit direction. Every fragment pass
// calls it before anything else that follows a ray, and from here on u_eye means that origin (as
// in the volume ray caster, render/volume/raycast_sample.frag.glsl); the billboards' vertex shader
// (no pixel yet) reads the camera through cameraEye().
vec3 cameraEye() { return u_eye; }
vec3 g_eye;
#define u_eye g_eye
vec3 pixelRay(vec2 fc) {
  vec2 s = vec2(2.0 * fc.x / u_size.x - 1.0, 1.0 - 2.0 * fc.y / u_size.y);
  g_eye = cameraEye();
  if (u_orthographic != 0) {
    g_eye += s.x * u_right_s + s.y * u_up_s;
    return u_fwd;
  }
  return normalize(u_fwd + s.x * u_right_s + s.y * u_up_s);
}
// [t_in, t_out] of the ray inside the clip box; t_in >= t_out: no overlap. Two bricks sharing a
// face compute that face's t with the same expression, so their intervals meet exactly.
vec2 clipInterval(vec3 d) {
  vec3 inv = 1.0 / d;
  vec3 a = (u_box_lo - u_eye) * inv, b = (u_box_hi - u_eye) * inv;
  vec3 lo = min(a, b), hi = max(a, b);
  return vec2(max(max(lo.x, lo.y), max(lo.z, 0.0)), min(min(hi.x, hi.y), hi.z));
}
// Lattice points k*w: the first one after t, and the first one at or after t.
float latticeNext(float t) {
  float k = floor(t / u_w);
  float n = (k + 1.0) * u_w;
  return n > t ? n : (k + 2.0) * u_w;
}
float latticeCeil(float t) {
  float k = ceil(t / u_w);
  float c = k * u_w;
  return c >= t ? c : (k + 1.0) * u_w;
}
// The window of u_window samples starting at s0: lattice steps, clamped to the box exit (repeats
// of t_out are the same sample and are skipped by the reader). Entries past u_window are unused.
// The advance pass only draws particles that can start a window within [t_next, lookaheadEnd]:
// the particles far behind a pixel's front cost nothing until the front gets near them.
float lookaheadEnd(float t_next, float t_out) { return min(t_next + u_lookahead, t_out); }
void windowSamples(float s0, float t_out, out float s[8]) {
  s[0] = min(s0, t_out);
  for (int i = 1; i < 8; ++i) s[i] = i < u_window ? min(latticeNext(s[i - 1]), t_out) : s[i - 1];
}
// Refinement probes inside a bracket b = (t_neg, I_neg, t_pos, I_pos): the secant estimate of
// eq. 5, two points close around it and the midpoint, ascending. Where I is smooth the root lies
// within the close pair, so one pass shrinks the bracket about 25-fold; the midpoint guarantees
// at least a halving where it is not (grazing rays, where I is flat near the surface).
float secantEstimate(vec4 b) { return clamp((b.x * b.w - b.z * b.y) / (b.w - b.y), b.x, b.z); }
void refineProbes(vec4 b, out float q[4]) {
  float ts = secantEstimate(b), d = 0.02 * (b.z - b.x), mid = 0.5 * (b.x + b.z);
  float a0 = max(ts - d, b.x), a1 = ts, a2 = min(ts + d, b.z);
  // insert mid into the sorted triple
  if (mid <= a0) { q[0] = mid; q[1] = a0; q[2] = a1; q[3] = a2; }
  else if (mid <= a1) { q[0] = a0; q[1] = mid; q[2] = a1; q[3] = a2; }
  else if (mid <= a2) { q[0] = a0; q[1] = a1; q[2] = mid; q[3] = a2; }
  else { q[0] = a0; q[1] = a1; q[2] = a2; q[3] = mid; }
}
// Refinement, eq. 6: the new bracket is the first sign change along the ray among t_neg, the 4
// probes q (ascending, F there in f) and t_pos; b itself where no probe narrows it.
vec4 refineBracket(vec4 b, float q[4], vec4 f) {
  vec2 neg = b.xy;
  for (int k = 0; k < 4; ++k) {
    float value = sqrt(f[k]) - u_T;
    if (value >= 0.0) return q[k] > neg.x ? vec4(neg, q[k], value) : b;
    if (q[k] > neg.x) neg = vec2(q[k], value);
  }
  return b.z > neg.x ? vec4(neg, b.zw) : b;
}
// Shading, the formula of transfer/metaball_shading.h: headlight L = -D, N = -grad F / |grad F|,
// rgb = colour * (0.2 + 0.8 * max(N.L, 0)), alpha 1 (premultiplied).
vec4 shade(vec3 colour, vec3 grad, vec3 d, out vec3 n) {
  float len = length(grad);
  n = len > 0.0 ? -grad / len : -d;
  float diffuse = max(dot(n, -d), 0.0);
  return vec4(clamp(colour * (0.2 + 0.8 * diffuse), 0.0, 1.0), 1.0);
}
// The one-pass ray casters (grid, slices): a direction with no zero component (their slab tests
// divide by it), and the ray's stretch in the clip box, [t_in, t_out], with the part of it in the
// box of the brick's data (where the field can be non-zero), [g0, g1], for data interval g:
// false if either is empty, else iv = (t_in, t_out, g0, g1).
vec3 safeDir(vec3 d) { return mix(d, vec3(1e-30), equal(d, vec3(0.0))); }
bool rayStretch(vec3 d, vec2 g, out vec4 iv) {
  vec2 c = clipInterval(d);
  if (c.x >= c.y) return false;
  iv = vec4(c, max(g.x, c.x), min(g.y, c.y));
  if (iv.z >= iv.w) return false;
  return true;
}
