#pragma once
// GLSL for ray casting one brick. A fullscreen triangle, scissored to the brick's rectangle, runs
// one ray per pixel, from the eye through the pixel centre (the reference's rays:
// Camera::rayDirection), clipped to the brick's own box.
//
// Samples lie on one lattice for every brick: distance t_k = k * delta from the eye. Sample k
// belongs to the brick, and to the block inside it, whose interval [enter, exit) along the ray
// holds float(k) * delta. Every interval end is (plane - eye) * inv_dir of a block plane, and a
// plane shared by two blocks or bricks is the same float in both, so each sample is taken by
// exactly one brick and one block: no seam, no double sample, whatever the decomposition.
//
// The loop (main): the ray walks the brick's block grid (a DDA over the block planes,
// worker/volume/ray_blocks.h: blocks of render.ray_block_cells cells aligned to the volume, cut by the
// brick's faces). Per block, one texel of u_skip holds its class g (0: empty under the transfer
// function; else 1 + log2 of its step multiple m) and its reach r >= 1, the chessboard distance to
// the nearest block of another class: every block within r - 1 of it has its class, so the ray
// crosses that whole cube of blocks in one step, to where it leaves it (then finds the block it is
// in on each axis: past every slab it has left by then). One lookup jumps many empty blocks, and
// samples run across many non-empty ones without stopping at each block plane.
//   - Empty: the ray jumps to the first lattice sample beyond the cube (the samples it passes
//     would add exactly nothing).
//   - Non-empty: m = 1 unless render.adaptive_step (worker/volume/step_rule.h; always 1 in the ADAPTIVE
//     variant's texel, whose blocks carry their own m and are taken one at a time). The block
//     evaluates only the lattice samples at multiples of m, the "anchors", of the samples k0 ..
//     k1 - 1 it owns (decided as above). Anchor a stands for the m lattice steps around it,
//     a - m/2 <= k < a + m/2 (integer m/2: 0 for m = 1), as far as the cube owns them: n such
//     steps give alpha = 1 - exp(-tau(v(a)) * n * delta). So every lattice step of the ray is
//     counted exactly once, where it is owned, whatever the neighbours' m (the rule the ADAPTIVE
//     variant found; below). The anchor may lie up to m/2 steps outside the block or brick: m is
//     capped so that m/2 steps stay within the one-sample ghost layer (worker/volume/step_rule.h), so
//     every brick owning part of an anchor's steps reads the same value there, and m is chosen
//     from the whole block's range, the same in every brick: brick faces stay seam-free. With
//     m = 1 the loop is the plain one, each sample standing for delta:
//     alpha = 1 - exp(-tau * delta), the same samples in the same order as block by block.
// Each sample is evaluated by sampleAt() alone (value, then classification; shaded with
// render.shading: shadeColour, worker/volume/volume_shading.h, in a variant of the program), composited
// front to back. The ray stops once alpha >= u_ert (early ray termination), at the brick's exit, or at the
// particle surface's t.
//
// Pre-integration (the program compiled with PREINTEGRATED defined; transfer.preintegrated):
// lattice sample k stands for the segment [t_k - delta/2, t_k + delta/2] of the ray, as it does in
// the midpoint rule above, and is owned by the same brick and block (the one holding t_k, so the
// rule above decides, and segments tile the ray as the midpoint samples do; centred on the samples
// rather than running between two of them, a segment reaches only delta/2 beyond its owner, so
// the one-voxel ghost layer serves steps up to 2 voxels instead of 1). The segment's colour
// and opacity come from the 2D table (common/preintegration.h) between the values at its two ends,
// v((k - 1/2) delta) and v((k + 1/2) delta), and at its middle, v(t_k) (segment() has why and how
// the three make one linear segment), read from this brick's texture: an end lies at most
// delta/2 outside the block, and so within the brick's ghost layer (one voxel) while delta <= 2
// voxels, which the scene enforces (beyond, an end near a brick face would read the texture's
// clamped edge: seams of 55-74/255 at 3-4 voxels on neghip). The back value of sample k is the front value of sample k + 1 (the same
// float position, (float(k) + 0.5) * delta), so consecutive samples read the volume twice each.
// Skipping stays exact: a block is jumped only if the range of the whole block's samples grown by
// one sample (BrickBlocks::grown_min/max, which hold both ends of every segment it owns) maps to zero opacity, and
// a segment between two values of that range then integrates to exactly zero; after a jump the
// next segment reads its front value afresh. Early termination and the particle surface end the
// ray as in the midpoint rule: a sample k with t_k < t1 contributes its whole segment (no partial
// last segment, so the segment ends are the midpoint samples' and the two rules converge alike).
// Not with ADAPTIVE (refused when the scene is read). With SHADING too, a segment's colour is
// shaded with the gradient at its middle sample. With adaptive steps, an anchor's segment runs
// over the steps it stands for, from (k - 1/2) delta to (next - 1/2) delta, its middle value read
// at the anchor; its ends lie at most m/2 steps, under one voxel, outside the block.
//
// Adaptive sampling (the program compiled with ADAPTIVE defined; worker/volume/adaptive_gpu_brick.h):
// the blocks of the DDA are the adaptive blocks cut by the brick's faces, sampleVolume() reads the
// current block's samples from the atlas, and a block at level L, whose samples are r = 2^L cells
// apart, is rendered at its own resolution: it takes m = r (the loop above). Of that rule:
//   - every lattice step of the ray is still counted exactly once, in the block that owns it: no
//     gap and no overlap where the level changes (a rule that starts each block at its first
//     anchor and gives every anchor r steps leaves both, and cost 8-16 dB in tests/mpi/adaptive.sh
//     field, and a seam of 30/255 in its bricks test);
//   - each anchor sits in the middle of its steps, as each fine sample does (anchoring at the
//     first step instead shifts coarse blocks by (r - 1) delta / 2 along the ray: 1.9 dB worse
//     on Marschner-Lobb at 20 %, neghip within 0.2 dB either way);
//   - a block's first (or last) anchor may lie up to r/2 steps outside it, in the previous block
//     or brick: it is read from this block's own samples, the block-local coordinate clamped to
//     the block (its value at the nearest point of the block; the field is continuous across
//     block faces, so that is close to the true one);
//   - a block cut by a brick face gives both bricks the same anchors and values (each holds the
//     whole block), an anchor's steps are split between them, and A over B of one colour and tau
//     is exact: 1 - exp(-tau n1 delta) exp(-tau n2 delta) = 1 - exp(-tau (n1 + n2) delta). Brick
//     faces stay seam-free up to float rounding and the RGBA8 brick images;
//   - at level 0 every anchor is its own sample and n = 1: the arithmetic of the non-adaptive
//     loop. With u_own_steps = 0 (adaptive.steps: fine) every block takes r = 1: the adaptive
//     field at the full sampling cost.
namespace sortlast::shaders {

// A triangle covering the viewport; the scissor cuts it to the brick's rectangle.
inline constexpr const char* kRaycastVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

inline constexpr const char* kRaycastFragment = R"(#version 450 core
uniform sampler3D u_volume;
uniform sampler1D u_table;
uniform sampler2D u_planes;     // texel (i, axis): world coordinate of block plane i on that axis
uniform usampler3D u_skip;      // per block: r = reach (distance to another class), g = class
uniform vec3 u_tex_scale;
uniform vec3 u_tex_offset;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform vec3 u_right;           // scaled by tan(fov / 2) * aspect
uniform vec3 u_up;              // scaled by tan(fov / 2)
uniform vec2 u_pixel_scale;     // 2 / width, 2 / height
uniform float u_delta;          // lattice step along every ray (world units)
uniform float u_ert;            // stop at this opacity; > 1: never
uniform vec2 u_value_map;       // normalised value = v * x + y
uniform vec2 u_table_map;       // table coordinate = normalised * x + y (texel centres at the ends)
uniform sampler2D u_surface;    // particle surface (t, normal) per pixel, t = 1e30 on a miss
uniform int u_has_surface;
uniform ivec4 u_surface_rect;   // x, y, w, h where u_surface is valid (stale elsewhere)
out vec4 frag;

vec3 g_inv;  // 1 / ray direction, per axis
ivec3 g_step;

#ifdef ADAPTIVE
uniform sampler3D u_blocks;     // per block (cell of this brick): atlas offset xyz, 2^-level
uniform vec3 u_index_scale;     // sample index relative to cell (0,0,0)'s block origin
uniform vec3 u_index_offset;    //   = world * scale + offset
uniform vec3 u_block_cells;     // s: cells per block per axis
uniform vec3 u_atlas_inv;       // 1 / atlas dims
uniform int u_own_steps;        // 1: a block takes every 2^level-th lattice sample; 0: every one
vec4 g_block;                   // the current block's table texel
vec3 g_origin;                  // its first sample, relative to cell (0,0,0)'s block origin

// The adaptive field at world point p, read from the current block (u_volume is the atlas):
// common/adaptive_brick.h sampleCell(), the block-local lattice coordinate clamped to the block;
// the hardware's trilinear filter on the texel centres (offset + local + 0.5) / atlas dims, as
// the plain sampleVolume filters the brick's texture: the same filter precision (float weights
// on llvmpipe; 8 fractional bits on NVIDIA for both), and at lossless settings the two images
// agree within 1/255 (tests/mpi/adaptive.sh lossless).
float sampleVolume(vec3 p) {
  vec3 local = clamp((p * u_index_scale + u_index_offset - g_origin) * g_block.w, vec3(0.0),
                     u_block_cells * g_block.w);
  return texture(u_volume, (g_block.xyz + local + 0.5) * u_atlas_inv).r;
}
#else
// The volume's value at world point p. The one place that reads the volume: a multi-resolution
// lookup would replace this function alone.
float sampleVolume(vec3 p) { return texture(u_volume, p * u_tex_scale + u_tex_offset).r; }
#endif

// (r, g, b, tau) of a value, through the transfer-function table.
vec4 classify(float v) {
  float x = clamp(v * u_value_map.x + u_value_map.y, 0.0, 1.0);
  return texture(u_table, x * u_table_map.x + u_table_map.y);
}

// (pre-integration: worker/volume/preintegration_glsl.h inserts segment() here)

// (r, g, b, tau) at world point p: the one place a sample is evaluated; its colour shaded with the
// field's gradient in the program's shaded variant (SHADING defined; shadeColour:
// worker/volume/volume_shading.h; light at the eye, so the direction from it to p). A sample of zero tau
// adds nothing whatever its colour: no gradient is read. Adaptive bricks are never shaded (the
// scene refuses the combination): their blocks hold only their own samples, not the field one
// voxel across a block face.
#if defined(SHADING) && defined(ADAPTIVE)
#error gradient shading of adaptive blocks
#endif
vec4 sampleAt(vec3 p) {
  vec4 e = classify(sampleVolume(p));
#ifdef SHADING
  if (e.a > 0.0)
    e.rgb = shadeColour(e.rgb, u_volume, p * u_tex_scale + u_tex_offset, normalize(p - u_eye));
#endif
  return e;
}

#ifdef GLOW
// Glow emitters (the GLOW variant, docs/glow.md "In the volume"; withGlow() puts glowSegment(),
// the emitters' uniforms and glowSpan() before this text; glowFlushDue sums glowSegment): emission
// without opacity, added to acc.rgb and never to acc.a. The ray's glow is integrated over
// [g_t, g_end] seen through the transmittance the reference (master/reference/reference.cpp) uses: in front
// of the volume 1; over a sample's segment [(k - 1/2) delta, (k + 1/2) delta] (an anchor's: its
// steps) the transmittance at its middle, T_k = (1 - acc.a) exp(-tau len / 2) (its square:
// 1 - alpha); over jumped empty blocks the (constant) transmittance; behind the volume what is
// left. Only inside this brick's part of the glow box (u_glow_lo, u_glow_hi), so the bricks'
// pieces tile every ray; up to the surface's t.
// After early ray termination the rest is dropped (at most 1 - u_ert of it).
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
// The emitters' texels (worker/glow/glow_gl.h's layout: (centre, a), (direction, b), (colour, 0)).
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
#endif

#ifndef GLOW
#define GLOW_STOP false
#endif

// A sample standing for `len` of the ray, front to back (opacity corrected for len); its segment
// ends at t_end (the glow variant's piece).
void composite(inout vec4 acc, vec4 e, float len, float t_end) {
#ifdef GLOW
  // The half segment's transmittance exp(-tau len / 2) is the glow's weight; its square gives
  // alpha (one exp per sample, no sqrt).
  float half_tr = exp(-0.5 * e.a * len);
  float alpha = 1.0 - half_tr * half_tr;
  glowSample(t_end, (1.0 - acc.a) * half_tr);
#else
  float alpha = 1.0 - exp(-e.a * len);
#endif
  acc += (1.0 - acc.a) * vec4(e.rgb * alpha, alpha);
}

#ifdef PREINTEGRATED
// The pre-integrated segment `len` long with front value vf and back value vb whose middle value
// is read at lattice sample `mid`, front to back; with SHADING its colour is shaded with the
// gradient there (premultiplied: shaded as the colour rgb / alpha, then weighted again).
void compositeSegment(inout vec4 acc, float vf, float vb, int mid, float len, vec3 dir, float t_end) {
  vec3 p = u_eye + float(mid) * u_delta * dir;
  vec4 e = segment(vf, sampleVolume(p), vb, len);
#ifdef SHADING
  if (e.a > 0.0) e.rgb = e.a * shadeColour(e.rgb / e.a, u_volume, p * u_tex_scale + u_tex_offset, dir);
#endif
#ifdef GLOW
  glowSample(t_end, (1.0 - acc.a) * sqrt(max(1.0 - e.a, 0.0)));
#endif
  acc += (1.0 - acc.a) * e;
}
#endif

// Ray distance to block plane i of an axis: the one formula every brick uses for a plane.
float planeT(int axis, int i) {
  return (texelFetch(u_planes, ivec2(i, axis), 0).r - u_eye[axis]) * g_inv[axis];
}
// Where the ray leaves slab `i` of an axis.
float exitT(int axis, int i) { return planeT(axis, g_step[axis] > 0 ? i + 1 : i); }

// The first lattice sample at or beyond t: the smallest k with float(k) * delta >= t, decided by
// the same product the sample loop compares, so bricks and blocks agree on every sample.
int firstSample(float t) {
  int k = int(ceil(t / u_delta));
  if (float(k) * u_delta < t) ++k;
  else if (float(k - 1) * u_delta >= t) --k;
  return k;
}

void main() {
  vec2 s = vec2(gl_FragCoord.x * u_pixel_scale.x - 1.0, 1.0 - gl_FragCoord.y * u_pixel_scale.y);
  vec3 dir = normalize(u_forward + s.x * u_right + s.y * u_up);
  ivec3 nb = textureSize(u_skip, 0);
  float t0 = 0.0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    // A zero component gets a tiny one: its slabs then span (almost) the whole line, as they should.
    g_inv[a] = 1.0 / (abs(dir[a]) < 1e-20 ? 1e-20 : dir[a]);
    g_step[a] = g_inv[a] > 0.0 ? 1 : -1;
    float ta = planeT(a, 0), tb = planeT(a, nb[a]);
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  // An opaque particle surface in this brick ends the ray; its colour is already in the target.
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (u_has_surface != 0 && all(greaterThanEqual(px, u_surface_rect.xy)) &&
      all(lessThan(px, u_surface_rect.xy + u_surface_rect.zw)))
    t1 = min(t1, texelFetch(u_surface, px, 0).x);
  vec4 acc = vec4(0.0);
#ifdef GLOW
  g_dir = dir;
  if (!glowSpan(u_eye, dir, u_glow_lo, u_glow_hi, u_glow_hi_open, g_t, g_end)) g_end = g_t;
  g_pend = g_t;
  if (u_has_surface != 0 && all(greaterThanEqual(px, u_surface_rect.xy)) &&
      all(lessThan(px, u_surface_rect.xy + u_surface_rect.zw)))
    g_end = min(g_end, texelFetch(u_surface, px, 0).x);
  g_lmax = glowRayLength(u_eye, dir, g_t, g_end, g_tx);
  g_tlim = min(g_t + g_lmax, g_tx);
  // In front of the volume (nothing closes: no piece is pending yet). A ray that misses the
  // volume takes the same path below, its span one piece at T = 1 (no early return: llvmpipe
  // would run that return's closed form, masked, for every pixel).
  if (t0 < t1) glowTo(t0, 1.0);
#else
  if (!(t0 < t1)) discard;
#endif

  // The block holding t0 on each axis: the first slab, in ray order, that the ray leaves after t0.
  ivec3 idx;
  for (int a = 0; a < 3; ++a) {
    int i = g_step[a] > 0 ? 0 : nb[a] - 1;
    while (i + g_step[a] >= 0 && i + g_step[a] < nb[a] && exitT(a, i) <= t0) i += g_step[a];
    idx[a] = i;
  }
  int k = firstSample(t0);
#ifdef PREINTEGRATED
  int k_back = k - 1;  // v_back holds the value at (float(k_back) - 0.5) * delta; none yet
  float v_back = 0.0;
#endif
  float t = t0;
#ifdef GLOW
  // llvmpipe runs 8-16 pixels in lock-step and every if's body, masked, whenever the group
  // reaches it, so the closed form runs as often as the group passes one of its call sites,
  // taken or not. It has one site (glowCatchUp at this loop's foot), passed once per round;
  // a round ends when a piece closes (the sample and block loops stop), so a group runs it
  // 1 + (most closures of its rays) times. Stages: 0 the march, 1 behind the volume, 2 the
  // last piece, 3 done.
  int stage = t0 < t1 ? 0 : 1;
  do {
  if (stage == 0) {
  bool more = false;  // stopped to integrate a closed piece; the march resumes at sample k
#endif
  while (t < t1 && acc.a < u_ert) {
    uvec2 info = texelFetch(u_skip, idx, 0).rg;
    // Every block within d - 1 of this one has its class: the ray crosses that cube at once (d = 1:
    // this block alone), jumping it if empty, else sampling it with one m.
    ivec3 last = clamp(idx + g_step * (int(info.r) - 1), ivec3(0), nb - 1);
    vec3 te = vec3(exitT(0, last.x), exitT(1, last.y), exitT(2, last.z));
    float tb = min(min(te.x, te.y), min(te.z, t1));
    int k_end = firstSample(tb);  // the first lattice sample this block (or cube) does not own
    if (info.g != 0u) {
#ifdef ADAPTIVE
      g_block = texelFetch(u_blocks, idx, 0);
      g_origin = vec3(idx) * u_block_cells;
      int m = u_own_steps != 0 ? int(1.0 / g_block.w + 0.5) : 1;  // 2^level
#else
      int m = 1 << int(info.g - 1u);
#endif
#ifdef PREINTEGRATED
      if (m == 1) {
        // The front value of sample k: the back value of sample k - 1 if that was just taken.
        float vf = k == k_back ? v_back : sampleVolume(u_eye + (float(k) - 0.5) * u_delta * dir);
        for (; k < k_end; ++k) {
          float vb = sampleVolume(u_eye + (float(k) + 0.5) * u_delta * dir);
          compositeSegment(acc, vf, vb, k, u_delta, dir, (float(k) + 0.5) * u_delta);
          vf = vb;
          if (acc.a >= u_ert || GLOW_STOP) { ++k; break; }
        }
        k_back = k;
        v_back = vf;
      } else {
        // An anchor's segment: its steps k .. next - 1, from (k - 1/2) delta to (next - 1/2) delta.
        float vf = k == k_back ? v_back : sampleVolume(u_eye + (float(k) - 0.5) * u_delta * dir);
        while (k < k_end) {
          int anchor = (k + m / 2) / m * m;
          int next = min(anchor - m / 2 + m, k_end);
          float vb = sampleVolume(u_eye + (float(next) - 0.5) * u_delta * dir);
          compositeSegment(acc, vf, vb, anchor, float(next - k) * u_delta, dir, (float(next) - 0.5) * u_delta);
          vf = vb;
          k = next;
          if (acc.a >= u_ert || GLOW_STOP) break;
        }
        k_back = k;
        v_back = vf;
      }
#else
      if (m == 1) {  // every sample (the same arithmetic as below with m = 1, without its cost)
        for (; k < k_end; ++k) {
          composite(acc, sampleAt(u_eye + float(k) * u_delta * dir), u_delta, (float(k) + 0.5) * u_delta);
          if (acc.a >= u_ert) break;
          if (GLOW_STOP) { ++k; break; }
        }
      } else {
        while (k < k_end) {
          int anchor = (k + m / 2) / m * m;
          int next = min(anchor - m / 2 + m, k_end);
          composite(acc, sampleAt(u_eye + float(anchor) * u_delta * dir), float(next - k) * u_delta,
                    (float(next) - 0.5) * u_delta);
          k = next;
          if (acc.a >= u_ert || GLOW_STOP) break;
        }
      }
#endif
    }
#ifdef GLOW
    else if (acc.a < u_ert) glowTo((float(k_end) - 0.5) * u_delta, 1.0 - acc.a);  // jumped: T constant
    // A piece closed inside the block: integrate it, then go on from sample k.
    if (g_hit && k < k_end && acc.a < u_ert) { more = true; break; }
#endif
    k = k_end;
    // Into the block holding tb: on each axis, past every slab the ray has left by then.
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      while (idx[a] >= 0 && idx[a] < nb[a] && exitT(a, idx[a]) <= tb) idx[a] += g_step[a];
      inside = inside && idx[a] >= 0 && idx[a] < nb[a];
    }
    if (!inside) break;
    t = tb;
#ifdef GLOW
    if (g_hit || g_due) { more = true; break; }
#endif
  }
#ifdef GLOW
  if (!more) stage = 1;
  }
  if (stage == 1 && !g_hit && !g_due) {
    if (acc.a < u_ert) glowTo(g_end, 1.0 - acc.a);  // the rest of the brick, behind the volume
    stage = 2;
  }
  if (stage == 2 && !g_hit && !g_due) {
    glowClose();  // the last piece
    stage = 3;
  }
  glowCatchUp(acc);  // the one place the closed form runs
  } while (stage < 3);
#endif
  frag = acc;
}
)";

}  // namespace sortlast::shaders
