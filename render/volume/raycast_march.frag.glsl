// The ray caster's march: ray casting one brick. A fullscreen triangle
// (render/gl/fullscreen.vert.glsl), scissored to the brick's rectangle, runs one ray per pixel,
// from the eye through the pixel centre (the reference's rays: Camera::rayDirection), clipped to
// the brick's own box.
//
// The fragment shader is this file's last chunk. render/volume/raycast_renderer.cpp composes it,
// by variant (defines ADAPTIVE, PREINTEGRATED, SHADING, GLOW; the bracketed chunks only with the
// last two named):
//   [render/glow/glow_segment.glsl, render/glow/glow_emitters.glsl: GLOW]
//   [render/volume/volume_shading.glsl: SHADING]  shadeColour()
//   raycast_sample.frag.glsl                      uniforms, sampleVolume(), classify(), sampleAt()
//   volume_clip.glsl                              clipRay(): clip.planes and clip.box
//   [preintegrated_segment.glsl: PREINTEGRATED]   segment()
//   [raycast_glow.frag.glsl: GLOW]                the glow pieces along the ray
//   [raycast_projection.frag.glsl: PROJECTION]    the projections' samples (and MIP_EXACT)
//   [raycast_isosurface.frag.glsl: ISOSURFACE]    isovalue crossings (render.blend: isosurface)
//   raycast_march.frag.glsl                       compositing, the block walk and main()
//
// Samples lie on one lattice for every brick: distance t_k = k * delta from the ray's origin (the
// eye; orthographic: the pixel's point on the eye plane, raycast_sample.frag.glsl). Sample k
// belongs to the brick, and to the block inside it, whose interval [enter, exit) along the ray
// holds float(k) * delta. Every interval end is (plane - eye) * inv_dir of a block plane, and a
// plane shared by two blocks or bricks is the same float in both, so each sample is taken by
// exactly one brick and one block: no seam, no double sample, whatever the decomposition.
//
// The loop (main): the ray walks the brick's block grid (a DDA over the block planes,
// render/volume/ray_blocks.h: blocks of render.ray_block_cells cells aligned to the volume, cut by the
// brick's faces). Per block, one texel of u_skip holds its class g (0: empty under the transfer
// function; else 1 + log2 of its step multiple m) and its reach r >= 1, the chessboard distance to
// the nearest block of another class: every block within r - 1 of it has its class, so the ray
// crosses that whole cube of blocks in one step, to where it leaves it (then finds the block it is
// in on each axis: past every slab it has left by then). One lookup jumps many empty blocks, and
// samples run across many non-empty ones without stopping at each block plane.
//   - Empty: the ray jumps to the first lattice sample beyond the cube (the samples it passes
//     would add exactly nothing).
//   - Non-empty: m = 1 unless render.adaptive_step (render/volume/step_rule.h; always 1 in the ADAPTIVE
//     variant's texel, whose blocks carry their own m and are taken one at a time). The block
//     evaluates only the lattice samples at multiples of m, the "anchors", of the samples k0 ..
//     k1 - 1 it owns (decided as above). Anchor a stands for the m lattice steps around it,
//     a - m/2 <= k < a + m/2 (integer m/2: 0 for m = 1), as far as the cube owns them: n such
//     steps give alpha = 1 - exp(-tau(v(a)) * n * delta). So every lattice step of the ray is
//     counted exactly once, where it is owned, whatever the neighbours' m (the rule the ADAPTIVE
//     variant found; below). The anchor may lie up to m/2 steps outside the block or brick: m is
//     capped so that m/2 steps stay within the one-sample ghost layer (render/volume/step_rule.h), so
//     every brick owning part of an anchor's steps reads the same value there, and m is chosen
//     from the whole block's range, the same in every brick: brick faces stay seam-free. With
//     m = 1 the loop is the plain one, each sample standing for delta:
//     alpha = 1 - exp(-tau * delta), the same samples in the same order as block by block.
// Each sample is evaluated by sampleAt() alone (value, then classification; shaded with
// render.shading: shadeColour, render/volume/volume_shading.glsl, in a variant of the program),
// composited front to back. The ray stops once alpha >= u_ert (early ray termination), at the
// brick's exit, or at the particle surface's t.
//
// Pre-integration (the program compiled with PREINTEGRATED defined; transfer.preintegrated):
// lattice sample k stands for the segment [t_k - delta/2, t_k + delta/2] of the ray, as it does in
// the midpoint rule above, and is owned by the same brick and block (the one holding t_k, so the
// rule above decides, and segments tile the ray as the midpoint samples do; centred on the samples
// rather than running between two of them, a segment reaches only delta/2 beyond its owner, so
// the one-voxel ghost layer serves steps up to 2 voxels instead of 1). The segment's colour
// and opacity come from the 2D table (transfer/preintegration.h) between the values at its two ends,
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
// Adaptive sampling (the program compiled with ADAPTIVE defined; render/volume/adaptive_gpu_brick.h):
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
#ifndef GLOW
#define GLOW_STOP false
#endif
#ifndef PROJECTION  // (raycast_projection.frag.glsl: projections never stop early)
#define ERT_REACHED(a) ((a) >= u_ert)
#define BLOCK_CANNOT_CHANGE(idx, acc) false
#endif

// The ray's span through the whole volume, clipped (clip.planes, clip.box): g_span_t0 .. g_span_t1,
// computed from the same floats in every brick (the volume's faces are brick planes), and the
// first and last lattice samples inside it, g_k_first and g_k_last.
int firstSample(float t);

void volumeSpan(vec3 dir) {
  vec3 ta = (u_vol_lo - u_eye) * g_inv, tb = (u_vol_hi - u_eye) * g_inv;
  vec3 lo = min(ta, tb), hi = max(ta, tb);
  vec2 s = clipRay(u_eye, dir, vec2(max(max(0.0, lo.x), max(lo.y, lo.z)), min(hi.x, min(hi.y, hi.z))));
  g_span_t0 = s.x;
  g_span_t1 = s.y;
  g_k_first = firstSample(s.x);
  g_k_last = firstSample(s.y) - 1;
}

// The length of ray that lattice steps k_from .. k_to - 1 stand for: (k_to - k_from) delta, from
// (k_from - 1/2) delta to (k_to - 1/2) delta, except at the ends of the volume's span, where the
// first sample's segment reaches back to where the ray enters the volume (or the clip region)
// and the last one's forward to where it leaves: the segments tile the span exactly. With every
// segment delta long, the span's two ends were off by up to delta / 2 each (a first-order error
// where the ray enters or leaves dense data: the head CT's cut face showed wood-grain rings of
// up to 33/255 at 0.5 voxel, halving with the step; issue 43). Inside the span the length is the
// product it always was, so frames away from those ends keep every bit. The GLOW variant too: its
// pieces end where the segments do (backT), so the glow of the span's end segments is seen through
// their own transmittance; on a clip plane cutting dense data next to an emitter's core whole
// steps there were 8 levels off the reference, the span's ends 3 (tests/mpi/glow.sh).
float stepsLength(int k_from, int k_to) {
  float len = float(k_to - k_from) * u_delta;
  if (k_from == g_k_first) len += (float(k_from) - 0.5) * u_delta - g_span_t0;
  if (k_to - 1 == g_k_last) len += g_span_t1 - (float(k_to) - 0.5) * u_delta;
  return len;
}
// Where segment k's front and back values are read (pre-integration): its ends, the span's ends
// for the span's first and last samples.
float frontT(int k) {
  if (k == g_k_first) return g_span_t0;
  return (float(k) - 0.5) * u_delta;
}
float backT(int k) {
  if (k == g_k_last) return g_span_t1;
  return (float(k) + 0.5) * u_delta;
}

// Where lattice sample k's value is read (the midpoint rule; pre-integration: its middle value): at t_k,
// the middle of its segment, except for the span's first and last samples, whose segments reach
// the span's ends (stepsLength) and so are up to 3 delta / 2 long with t_k anywhere in them: they
// are read at their segments' middles instead (at most delta / 4 from t_k, within the bricks'
// ghost layer). Read at t_k, the value where the ray enters dense data (the head CT's cut face)
// was up to a step inside it: a first-order error of up to 51/255 at 1 voxel on the head CT's
// rim, 14/255 at 0.5 (issue 43, results/accuracy/causes.md).
float sampleT(int k) {
  if (k == g_k_first || k == g_k_last)
    return 0.5 * ((k == g_k_first ? g_span_t0 : (float(k) - 0.5) * u_delta) +
                  (k == g_k_last ? g_span_t1 : (float(k) + 0.5) * u_delta));
  return float(k) * u_delta;
}

// A sample standing for `len` of the ray, front to back (opacity corrected for len); its segment
// ends at t_end (backT: the glow variant's piece).
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
// is read at ray distance t_mid (sampleT: the span's end segments' own middles), front to back;
// with SHADING its colour is shaded with the gradient there (premultiplied: shaded as the colour
// rgb / alpha, then weighted again).
void compositeSegment(inout vec4 acc, float vf, float vb, float t_mid, float len, vec3 dir, float t_end) {
  vec3 p = u_eye + t_mid * dir;
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

// The ray through this pixel's centre (Camera::pixelRay): sets its origin g_eye and returns its
// unit direction (also g_ray_dir).
vec3 pixelRay() {
  vec2 s = vec2(gl_FragCoord.x * u_pixel_scale.x - 1.0, 1.0 - gl_FragCoord.y * u_pixel_scale.y);
  g_eye = cameraEye();
  if (u_orthographic != 0) {
    g_eye += s.x * u_right + s.y * u_up;
    g_ray_dir = u_forward;
  } else {
    g_ray_dir = normalize(u_forward + s.x * u_right + s.y * u_up);
  }
  return g_ray_dir;
}

// Where the ray enters and leaves the brick's block grid (nb blocks per axis), from t >= 0:
// (t0, t1), empty if t0 >= t1. Sets g_inv and g_step for the ray.
vec2 brickSpan(vec3 dir, ivec3 nb) {
  float t0 = 0.0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    // A zero component gets a tiny one: its slabs then span (almost) the whole line, as they should.
    g_inv[a] = 1.0 / (abs(dir[a]) < 1e-20 ? 1e-20 : dir[a]);
    g_step[a] = g_inv[a] > 0.0 ? 1 : -1;
    float ta = planeT(a, 0), tb = planeT(a, nb[a]);
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return vec2(t0, t1);
}

// The block holding t0 on each axis: the first slab, in ray order, that the ray leaves after t0.
ivec3 firstBlock(float t0, ivec3 nb) {
  ivec3 idx;
  for (int a = 0; a < 3; ++a) {
    int i = g_step[a] > 0 ? 0 : nb[a] - 1;
    while (i + g_step[a] >= 0 && i + g_step[a] < nb[a] && exitT(a, i) <= t0) i += g_step[a];
    idx[a] = i;
  }
  return idx;
}

// Where a ray's walk through the brick is: block idx, lattice sample k, distance t; and (the
// pre-integrated variant) the value v_back at (float(k_back) - 0.5) * delta, the front value of
// sample k_back.
struct Walk {
  ivec3 idx;
  int k;
  int k_back;
  float v_back;
  float t;
};

// The lattice samples w.k .. k_end - 1 that a non-empty block (or cube of blocks) owns, taken with
// step multiple m (every sample for m = 1, else the anchors), front to back into acc. w.k ends at
// k_end, or past the sample after which the ray stopped: its opacity reached u_ert, or (GLOW_STOP)
// a glow piece is to be closed first.
void sampleBlock(inout vec4 acc, inout Walk w, int k_end, int m, vec3 dir) {
#if defined(PROJECTION)
  projectSamples(acc, w.k, k_end, dir);  // every sample (m = 1), never stopping early
  w.k = k_end;
#elif defined(ISOSURFACE)
  isoSamples(acc, w.k, w.k_back, w.v_back, k_end, dir);  // raycast_isosurface.frag.glsl
#elif defined(PREINTEGRATED)
  if (m == 1) {
    // The front value of sample w.k: the back value of sample w.k - 1 if that was just taken.
    float vf = w.k == w.k_back ? w.v_back : sampleVolume(u_eye + frontT(w.k) * dir);
    for (; w.k < k_end; ++w.k) {
      float vb = sampleVolume(u_eye + backT(w.k) * dir);
      compositeSegment(acc, vf, vb, sampleT(w.k), stepsLength(w.k, w.k + 1), dir, backT(w.k));
      vf = vb;
      if (acc.a >= u_ert || GLOW_STOP) { ++w.k; break; }
    }
    w.k_back = w.k;
    w.v_back = vf;
  } else {
    // An anchor's segment: its steps w.k .. next - 1, from (w.k - 1/2) delta to (next - 1/2) delta.
    float vf = w.k == w.k_back ? w.v_back : sampleVolume(u_eye + frontT(w.k) * dir);
    while (w.k < k_end) {
      int anchor = (w.k + m / 2) / m * m;
      int next = min(anchor - m / 2 + m, k_end);
      float vb = sampleVolume(u_eye + backT(next - 1) * dir);
      compositeSegment(acc, vf, vb, float(anchor) * u_delta, stepsLength(w.k, next), dir, backT(next - 1));
      vf = vb;
      w.k = next;
      if (acc.a >= u_ert || GLOW_STOP) break;
    }
    w.k_back = w.k;
    w.v_back = vf;
  }
#else
  if (m == 1) {  // every sample (the same arithmetic as below with m = 1, without its cost)
    for (; w.k < k_end; ++w.k) {
      composite(acc, sampleAt(u_eye + sampleT(w.k) * dir), stepsLength(w.k, w.k + 1), backT(w.k));
      if (acc.a >= u_ert) break;
      if (GLOW_STOP) { ++w.k; break; }
    }
  } else {
    while (w.k < k_end) {
      int anchor = (w.k + m / 2) / m * m;
      int next = min(anchor - m / 2 + m, k_end);
      composite(acc, sampleAt(u_eye + float(anchor) * u_delta * dir), stepsLength(w.k, next),
                backT(next - 1));
      w.k = next;
      if (acc.a >= u_ert || GLOW_STOP) break;
    }
  }
#endif
}

// The walk over the brick's blocks (nb per axis) from w up to t1, front to back into acc (the loop
// described at the top). Returns true if it stopped for a closed glow piece to be integrated (the
// GLOW variant), to go on from w.
bool march(inout vec4 acc, inout Walk w, float t1, ivec3 nb, vec3 dir) {
  bool more = false;
  while (w.t < t1 && !ERT_REACHED(acc.a)) {
    uvec2 info = texelFetch(u_skip, w.idx, 0).rg;
    // Every block within d - 1 of this one has its class: the ray crosses that cube at once (d = 1:
    // this block alone), jumping it if empty, else sampling it with one m.
    ivec3 last = clamp(w.idx + g_step * (int(info.r) - 1), ivec3(0), nb - 1);
    vec3 te = vec3(exitT(0, last.x), exitT(1, last.y), exitT(2, last.z));
    float tb = min(min(te.x, te.y), min(te.z, t1));
    int k_end = firstSample(tb);  // the first lattice sample this block (or cube) does not own
    if (info.g != 0u && !BLOCK_CANNOT_CHANGE(w.idx, acc)) sampleBlock(acc, w, k_end, blockStep(w.idx, info.g), dir);
#ifdef GLOW
    else if (acc.a < u_ert) glowTo((float(k_end) - 0.5) * u_delta, 1.0 - acc.a);  // jumped: T constant
    // A piece closed inside the block: integrate it, then go on from sample w.k.
    if (g_hit && w.k < k_end && acc.a < u_ert) { more = true; break; }
#endif
    w.k = k_end;
    // Into the block holding tb: on each axis, past every slab the ray has left by then.
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      while (w.idx[a] >= 0 && w.idx[a] < nb[a] && exitT(a, w.idx[a]) <= tb) w.idx[a] += g_step[a];
      inside = inside && w.idx[a] >= 0 && w.idx[a] < nb[a];
    }
    if (!inside) break;
    w.t = tb;
#ifdef GLOW
    if (g_hit || g_due) { more = true; break; }
#endif
  }
  return more;
}

#ifdef GLOW
// The march with the glow: llvmpipe runs 8-16 pixels in lock-step and every if's body, masked,
// whenever the group reaches it, so the closed form runs as often as the group passes one of its
// call sites, taken or not. It has one site (glowCatchUp at this loop's foot), passed once per
// round; a round ends when a piece closes (the sample and block loops stop), so a group runs it
// 1 + (most closures of its rays) times. Stages: 0 the march, 1 behind the volume, 2 the last
// piece, 3 done.
void marchWithGlow(inout vec4 acc, inout Walk w, float t0, float t1, ivec3 nb, vec3 dir) {
  int stage = t0 < t1 ? 0 : 1;
  do {
    if (stage == 0) {
      if (!march(acc, w, t1, nb, dir)) stage = 1;
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
}
#endif

void main() {
  vec3 dir = pixelRay();
  ivec3 nb = textureSize(u_skip, 0);
  vec2 span = clipRay(u_eye, dir, brickSpan(dir, nb));  // clip.planes, clip.box: volume_clip.glsl
  volumeSpan(dir);  // (after brickSpan, which sets g_inv)
  float t0 = span.x, t1 = span.y;
  // An opaque particle surface in this brick ends the ray; its colour is already in the target.
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (surfaceAt(px)) t1 = min(t1, texelFetch(u_surface, px, 0).x);
#ifdef ISOSURFACE
  // At the surface, or leaving the volume or the clip region (span.y and g_span_t1 are both the
  // min over the same clip candidates, of this brick's exit and of the volume's).
  bool ends_here = t1 < span.y || span.y >= g_span_t1;
#endif
  vec4 acc = vec4(0.0);
#ifdef MIP_EXACT  // the exact extremum over the brick's own part of the ray (its span in double)
  projectExact(acc, px);
  frag = projectionPixel(acc, px);
  return;
#endif
#ifdef PROJECTION  // no volume here: the opaque layer's colour alone (raycast_projection.frag.glsl)
  if (!(t0 < t1)) {
    frag = projectionPixel(acc, px);
    return;
  }
#endif
#ifdef GLOW
  glowBegin(dir, px, t0, t1);
#else
  if (!(t0 < t1)) discard;
#endif
#if !defined(PROJECTION) && !defined(ISOSURFACE) && !defined(GLOW)
  // A span that holds no lattice sample (a chord shorter than a step, at the silhouette's edges
  // and corners; 60 pixels of up to 19/255 on a uniform cube at 1 voxel) gets one sample at its
  // middle, standing for the whole chord, taken by the brick whose part of the ray holds it, read
  // through the block holding it (the adaptive variant reads that block's own samples; an empty
  // block adds nothing).
  if (g_k_first > g_k_last && g_span_t0 < g_span_t1) {
    float tm = 0.5 * (g_span_t0 + g_span_t1);
    if (!(tm >= t0 && tm < t1)) discard;
    ivec3 bi = firstBlock(tm, nb);
    uint g = texelFetch(u_skip, bi, 0).g;
    if (g != 0u) {
      blockStep(bi, g);
      composite(acc, sampleAt(u_eye + tm * dir), g_span_t1 - g_span_t0, g_span_t1);
    }
    frag = acc;
    return;
  }
#endif
  ivec3 idx = firstBlock(t0, nb);
  int k = firstSample(t0);
  Walk w = Walk(idx, k, k - 1, 0.0, t0);  // no back value yet
#ifdef GLOW
  marchWithGlow(acc, w, t0, t1, nb, dir);
#else
  march(acc, w, t1, nb, dir);
#endif
#ifdef ISOSURFACE
  if (ends_here) isoTail(acc, firstSample(t1) - 1, t1, dir);
#ifdef ISO_DEBUG
  acc = g_iso_first;
#endif
#ifdef ISO_DEPTH
  acc = g_iso_opaque;
#endif
#endif
#ifdef PROJECTION
  acc = projectionPixel(acc, px);
#endif
  frag = acc;
}
