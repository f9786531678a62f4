#pragma once
// GLSL for the metaball ray caster (Mishima et al., ../shared/PAPERS.md §2). Every pass works on
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
// Distances t are along the unit ray from the eye; samples sit on the lattice t = k*w, shared by
// every brick, so bricks sample the same points a single brick would.
namespace sortlast::shaders {

inline constexpr const char* kMetaballCommon = R"(#version 450 core
uniform vec3 u_eye;
uniform vec3 u_fwd;
uniform vec3 u_right_s;   // camera right * tan(fov/2) * aspect
uniform vec3 u_up_s;      // camera up * tan(fov/2)
uniform vec2 u_size;      // image width, height
uniform float u_h;        // influence radius
uniform float u_T;        // threshold
uniform float u_w;        // sample step
uniform vec3 u_box_lo;    // clip box: the brick this image belongs to
uniform vec3 u_box_hi;
uniform float u_lookahead;  // how far past a pixel's next sample the advance pass looks
uniform int u_window;       // samples per window: 4 (one RGBA target, the paper) or 8 (two)
const float INF = 1e30;

// The ray of the pixel whose centre is fc (gl_FragCoord.xy); the same formula as
// Camera::rayDirection, so GL and the CPU reference trace the same rays.
vec3 rayDir(vec2 fc) {
  vec2 s = vec2(2.0 * fc.x / u_size.x - 1.0, 1.0 - 2.0 * fc.y / u_size.y);
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
// Shading, the formula of common/metaball_shading.h: headlight L = -D, N = -grad F / |grad F|,
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
)";

// Billboards: for each particle the square facing the eye in front of its sphere of influence
// (the front face of the paper's bounding cube), drawn as an instanced 4-vertex strip. With
// culling on, a particle whose distance range [d - h, d + h] cannot meet any pixel's [lo, hi]
// in the tile it covers is moved off screen before rasterisation (§4.3).
inline constexpr const char* kBillboardVertex = R"(
layout(location = 0) in vec3 a_centre;
uniform mat4 u_view_proj;
uniform sampler2D u_pyramid;
uniform int u_levels;        // 0: no culling
uniform float u_cull_pad;    // cull when d + pad < tile lo, or d - h > tile hi
uniform ivec4 u_rect;        // x, y, w, h of the brick's screen rectangle
flat out vec3 v_centre;
void main() {
  vec3 c = a_centre;
  vec3 n = c - u_eye;
  float dist = length(n);
  n /= dist;
  vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 u = normalize(cross(n, a)), v = cross(n, u);
  vec3 f = c - u_h * n;
  vec2 lo = vec2(INF), hi = vec2(-INF);
  bool behind = false;
  vec4 mine = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    vec2 k = vec2(float(i & 1), float(i >> 1)) * 2.0 - 1.0;
    vec4 q = u_view_proj * vec4(f + u_h * (k.x * u + k.y * v), 1.0);
    if (i == gl_VertexID) mine = q;
    if (q.w <= 0.0) behind = true;
    vec2 s = (q.xy / q.w * 0.5 + 0.5) * u_size;
    lo = min(lo, s);
    hi = max(hi, s);
  }
  gl_Position = mine;
  v_centre = c;
  if (u_levels > 0 && !behind) {
    vec2 rlo = vec2(u_rect.xy), rhi = vec2(u_rect.xy + u_rect.zw) - 1.0;
    bool culled = any(lessThan(hi, rlo)) || any(greaterThan(lo, rhi + 1.0));
    if (!culled) {
      ivec2 p0 = ivec2(clamp(lo, rlo, rhi)), p1 = ivec2(clamp(hi, rlo, rhi));
      int span = max(p1.x - p0.x, p1.y - p0.y);
      // Tiles a quarter of the billboard's size (up to 5 x 5 fetches): coarser tiles mix
      // distances from too far away to cull much (measured: 2.6x slower frames on the 4,096-
      // particle slab at 512^2 than this level; an eighth was no better).
      int level = max(0, (span <= 0 ? 0 : int(ceil(log2(float(span + 1))))) - 2);
      if (level < u_levels) {
        ivec2 q0 = p0 >> level, q1 = p1 >> level, last = textureSize(u_pyramid, level) - 1;
        vec2 m = vec2(INF, -INF);
        for (int y = q0.y; y <= q1.y; ++y)
          for (int x = q0.x; x <= q1.x; ++x) {
            vec2 t = texelFetch(u_pyramid, min(ivec2(x, y), last), level).rg;
            m = vec2(min(m.x, t.x), max(m.y, t.y));
          }
        culled = dist + u_cull_pad < m.x || dist - u_h > m.y;
      }
    }
    if (culled) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
  }
}
)";

// Where may this pixel's next window start (eqs. 2-4)? MIN-blended over all particles into
// `next`. The paper bounds each particle by a cube; the exact sphere entry is used here instead,
// which skips strictly more empty space and samples the same lattice points.
inline constexpr const char* kAdvanceFragment = R"(
flat in vec3 v_centre;
uniform sampler2D u_state;
out float o_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float t_next = texelFetch(u_state, p, 0).x;
  if (t_next >= 0.5 * INF) discard;
  vec3 d = rayDir(gl_FragCoord.xy);
  vec3 oc = v_centre - u_eye;
  float tb = dot(d, oc);
  if (tb < t_next) discard;  // eq. 3: its candidate region ends before the next sample
  vec3 perp = oc - tb * d;
  float perp2 = dot(perp, perp);
  if (perp2 >= u_h * u_h) discard;  // the ray misses its sphere of influence
  float tf = tb - sqrt(u_h * u_h - perp2);
  o_next = tf <= t_next ? t_next : latticeCeil(tf);  // eq. 4
}
)";

// Field contributions (eq. 7) added up by blending. Mode 0: the window's samples (§4.2);
// mode 1: the 4 refinement probes of the pixel's bracket; mode 2: gradient and field at `next`.
inline constexpr const char* kPotentialFragment = R"(
flat in vec3 v_centre;
uniform sampler2D u_state;
uniform sampler2D u_hit;
uniform sampler2D u_next;
uniform int u_mode;
out vec4 o_sum;
layout(location = 1) out vec4 o_sum2;  // samples 4-7 of an 8-sample window
float field(float s, float tb, float perp2) {
  float ds = s - tb;
  float q = max(1.0 - sqrt(perp2 + ds * ds) / u_h, 0.0);
  return q * q;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (u_mode == 0) {
    float t_next = texelFetch(u_state, p, 0).x;
    if (t_next >= 0.5 * INF || t_next < 0.0) discard;
  } else if (texelFetch(u_hit, p, 0).z <= 0.0) {
    discard;
  }
  vec3 d = rayDir(gl_FragCoord.xy);
  vec3 oc = v_centre - u_eye;
  float tb = dot(d, oc);
  vec3 perp = oc - tb * d;
  float perp2 = dot(perp, perp);
  if (perp2 >= u_h * u_h) discard;
  float s0 = texelFetch(u_next, p, 0).x;
  if (u_mode == 0) {
    float s[8];
    windowSamples(s0, clipInterval(d).y, s);
    o_sum = vec4(field(s[0], tb, perp2), field(s[1], tb, perp2), field(s[2], tb, perp2),
                 field(s[3], tb, perp2));
    o_sum2 = u_window > 4 ? vec4(field(s[4], tb, perp2), field(s[5], tb, perp2),
                                 field(s[6], tb, perp2), field(s[7], tb, perp2))
                          : vec4(0.0);
  } else if (u_mode == 1) {
    float q[4];
    refineProbes(texelFetch(u_hit, p, 0), q);
    o_sum = vec4(field(q[0], tb, perp2), field(q[1], tb, perp2), field(q[2], tb, perp2),
                 field(q[3], tb, perp2));
    o_sum2 = vec4(0.0);
  } else {
    // r = x - c = (s - tb) d - perp; dP/dx = -2 (1 - |r|/h) / h * r / |r| (0 at the centre).
    vec3 r = (s0 - tb) * d - perp;
    float len = length(r);
    float q = max(1.0 - len / u_h, 0.0);
    vec3 g = len > 0.0 ? (-2.0 * q / (u_h * len)) * r : vec3(0.0);
    o_sum = vec4(g, q * q);
    o_sum2 = vec4(0.0);
  }
}
)";

// A triangle covering the viewport; the scissor box limits it to the brick's rectangle.
inline constexpr const char* kFullscreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// Start of a brick: the clip interval, and "next window starts at the box entry".
inline constexpr const char* kInitFragment = R"(
layout(rgba32f, binding = 0) uniform writeonly image2D i_state;
layout(rgba32f, binding = 1) uniform writeonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 iv = clipInterval(rayDir(gl_FragCoord.xy));
  bool inside = iv.x < iv.y;
  // Before the first sample the field is taken as 0 (I = -T): if the box entry lies inside a
  // sphere of influence, the first window starts exactly there and measures it.
  imageStore(i_state, p, inside ? vec4(iv.x, -u_T, iv.x, 0.0) : vec4(INF, -u_T, 0.0, 0.0));
  imageStore(i_hit, p, vec4(0.0));
  imageStore(i_base, p, inside ? vec4(iv.x, lookaheadEnd(iv.x, iv.y), 0.0, 0.0) : vec4(INF, -INF, 0.0, 0.0));
}
)";

// After the advance pass: the window this pixel samples next, as [lo, hi] for culling.
inline constexpr const char* kWindowFragment = R"(
layout(rgba32f, binding = 0) uniform image2D i_state;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
uniform sampler2D u_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 st = imageLoad(i_state, p);
  vec2 base = vec2(INF, -INF);
  if (st.x < 0.5 * INF) {
    float t_out = clipInterval(rayDir(gl_FragCoord.xy)).y;
    float s0 = texelFetch(u_next, p, 0).x;
    float ahead = lookaheadEnd(st.x, t_out);
    if (s0 > ahead && ahead >= t_out) {
      // No candidate region before the box exit: nothing more to find in this brick.
      imageStore(i_state, p, vec4(INF, st.yzw));
    } else if (s0 > ahead) {
      // No candidate within the lookahead (the particles beyond it were not drawn): skip to its
      // end without sampling. A negative t marks the skip for the potential and step passes.
      imageStore(i_state, p, vec4(-latticeCeil(ahead), st.yzw));
    } else {
      float s[8];
      windowSamples(s0, t_out, s);
      base = vec2(s[0], s[u_window - 1]);
    }
  }
  imageStore(i_base, p, vec4(base, 0.0, 0.0));
}
)";

// After the potential pass: walk the window's samples in order, looking for the first I >= 0.
// Pixels still searching pass the fragment test, so an occlusion query tells the host whether
// another window is needed.
inline constexpr const char* kStepFragment = R"(
layout(rgba32f, binding = 0) uniform image2D i_state;
layout(rgba32f, binding = 1) uniform writeonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
uniform sampler2D u_next;
uniform sampler2D u_pot;
uniform sampler2D u_pot2;
uniform float u_cap;  // samples allowed per pixel
out vec4 o_unused;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 st = imageLoad(i_state, p);
  if (st.x >= 0.5 * INF) discard;
  vec2 iv = clipInterval(rayDir(gl_FragCoord.xy));
  if (st.x < 0.0) {
    // Skipped ahead this round (see the window pass): still searching, nothing sampled.
    float t_next = -st.x;
    if (t_next >= iv.y) {
      imageStore(i_state, p, vec4(INF, st.yzw));
      imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
      discard;
    }
    imageStore(i_state, p, vec4(t_next, st.yzw));
    imageStore(i_base, p, vec4(t_next, lookaheadEnd(t_next, iv.y), 0.0, 0.0));
    o_unused = vec4(1.0);
    return;
  }
  vec4 f = texelFetch(u_pot, p, 0), f2 = texelFetch(u_pot2, p, 0);
  float s[8];
  windowSamples(texelFetch(u_next, p, 0).x, iv.y, s);
  float t_last = st.z, i_last = st.y, n = st.w;
  bool done = false;
  for (int k = 0; k < u_window; ++k) {
    if (k > 0 && s[k] == s[k - 1]) break;
    if (n >= u_cap) { done = true; break; }  // out of samples: a hole, the paper's Fig. 12
    float field = k < 4 ? f[k] : f2[k - 4];
    float value = sqrt(field) - u_T;
    // Only samples inside some particle's reach count against the cap: a window of 8 runs on
    // through gaps a window of 4 would jump, and those samples must not use up the budget.
    if (field > 0.0) n += 1.0;
    if (value >= 0.0) {
      // A sample exactly at the box entry that is already inside: the surface lies in front of
      // this brick (its owner draws it), so this brick shows nothing here.
      if (s[k] > iv.x) imageStore(i_hit, p, vec4(t_last, i_last, s[k], value));
      done = true;
      break;
    }
    t_last = s[k];
    i_last = value;
    if (s[k] >= iv.y) { done = true; break; }
  }
  if (done) {
    imageStore(i_state, p, vec4(INF, i_last, t_last, n));
    imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
    discard;
  }
  // The next lattice point, or the box exit if that comes first: the exit is always sampled, so
  // a surface between the last lattice point and the face is found in this brick.
  float t_next = min(latticeNext(s[u_window - 1]), iv.y);
  imageStore(i_state, p, vec4(t_next, i_last, t_last, n));
  imageStore(i_base, p, vec4(t_next, lookaheadEnd(t_next, iv.y), 0.0, 0.0));
  o_unused = vec4(1.0);
}
)";

// Before a refinement pass: each hit pixel's bracket as [lo, hi] for culling.
inline constexpr const char* kBracketBaseFragment = R"(
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  imageStore(i_base, p, b.z > 0.0 ? vec4(b.x, b.z, 0.0, 0.0) : vec4(INF, -INF, 0.0, 0.0));
}
)";

// Refinement, eq. 6 over the probes (refineBracket).
inline constexpr const char* kBracketFragment = R"(
layout(rgba32f, binding = 1) uniform image2D i_hit;
uniform sampler2D u_pot;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  if (b.z <= 0.0) return;
  float q[4];
  refineProbes(b, q);
  imageStore(i_hit, p, refineBracket(b, q, texelFetch(u_pot, p, 0)));
}
)";

// After refinement: the surface is the secant estimate in the final bracket (eq. 5).
inline constexpr const char* kSecantFragment = R"(
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
layout(r32f, binding = 3) uniform writeonly image2D i_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  if (b.z <= 0.0) {
    imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
    return;
  }
  float t = secantEstimate(b);
  imageStore(i_next, p, vec4(t));
  imageStore(i_base, p, vec4(t, t, 0.0, 0.0));
}
)";

// Shading (shade(), common/metaball_shading.h). Also stores (t, N) for depth tests and the
// surface output; misses get t = INF.
inline constexpr const char* kShadeFragment = R"(
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rgba32f, binding = 4) uniform writeonly image2D i_surface;
uniform sampler2D u_next;
uniform sampler2D u_pot;
uniform vec3 u_colour;
out vec4 o_colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (imageLoad(i_hit, p).z <= 0.0) {
    imageStore(i_surface, p, vec4(INF, 0.0, 0.0, 0.0));
    o_colour = vec4(0.0);
    return;
  }
  vec3 d = rayDir(gl_FragCoord.xy);
  vec3 n;
  o_colour = shade(u_colour, texelFetch(u_pot, p, 0).xyz, d, n);
  imageStore(i_surface, p, vec4(texelFetch(u_next, p, 0).x, n));
}
)";

// One level of the min/max pyramid from the level below; children wholly outside the brick's
// rectangle hold stale values from earlier bricks and are ignored.
inline constexpr const char* kReduceFragment = R"(#version 450 core
layout(rg32f, binding = 5) uniform readonly image2D i_below;
layout(rg32f, binding = 6) uniform writeonly image2D i_level;
uniform int u_level;
uniform ivec4 u_rect;
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy);
  int cs = 1 << (u_level - 1);
  ivec2 size = imageSize(i_below);
  vec2 m = vec2(1e30, -1e30);
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 c = 2 * q + ivec2(dx, dy);
      ivec2 lo = c * cs, hi = lo + cs - 1;
      if (any(greaterThanEqual(c, size)) || hi.x < u_rect.x || hi.y < u_rect.y ||
          lo.x >= u_rect.x + u_rect.z || lo.y >= u_rect.y + u_rect.w)
        continue;
      vec2 t = imageLoad(i_below, c).rg;
      m = vec2(min(m.x, t.x), max(m.y, t.y));
    }
  imageStore(i_level, q, vec4(m, 0.0, 0.0));
}
)";

}  // namespace sortlast::shaders
