// The ray caster's projections (render.blend: mip, minip, average, additive), compiled with
// PROJECTION defined as 1 mip, 2 minip, 3 average, 4 additive; placed before
// raycast_march.frag.glsl, whose block walk calls projectSamples() for the lattice samples each
// block owns (so every lattice sample is still taken by exactly one brick and block) and never
// stops a ray early. The pixel (compositing/projection_pixels.h):
//   mip / minip: (v, 0, 0, 1), v the largest / smallest sample; (0, 0, 0, 0) if no sample was
//     taken (NaN samples, a stencil touching a missing voxel, are not taken);
//   average: (sum of the samples, 0, 0, their count);
//   additive: the sum of (c a, a), a = 1 - exp(-tau delta): emission without absorption.
// The transfer function colours the final value once, after compositing (not here).
//
// MIP_EXACT (mip / minip with render.mip_exact): instead of the lattice samples, the exact
// extremum of the trilinear field along the ray's part inside this brick's own box (bricks tile
// the volume, so the max over bricks is the whole ray's). The ray walks the volume's cells (texel
// centres of the brick's texture, ghost layer included); in a cell the field along the ray is
// the trilinear interpolant of its 8 corners (texelFetch) at a point linear in t, a cubic
// k0 + k1 s + k2 s^2 + k3 s^3 in s in [0, 1] over the cell's segment; its extremum is at an end
// or at a root of the derivative k1 + 2 k2 s + 3 k3 s^2 inside (0, 1). A cell touching a NaN
// corner is skipped.
//
// Bounded by an opaque layer (particles or subdivision surfaces): the rays end at
// the brick's layer t as every variant's do (raycast_march.frag.glsl main), and the pixel carries
// the layer's colour for the compositor's over-like operator (compositing/projection_pixels.h's
// bounded formats): (v, r + 256 g + 65536 b of its 8-bit rgb, 0, flags), flags = 1 (a value) + 2
// (a layer). Without a layer the pixel is the unbounded one, (v, 0, 0, 1) or absent. Average and
// additive (u_bounded: the frame has a layer, so every brick's pixels take the bounded format,
// with or without a layer of its own): ValueSumBounded's (sum, rgb, count, flags) and
// AdditiveBounded's packed halves.
#ifndef PROJECTION
#error raycast_projection.frag.glsl needs PROJECTION
#endif
#define ERT_REACHED(a) false

uniform sampler2D u_surface_colour;  // the layer's colour (premultiplied RGBA32F, alpha 1 where hit)
uniform int u_bounded;  // 1: the frame has an opaque layer, the pixels are the bounded formats'
// The opaque layer's 8-bit rgb at px, or (-1) where this brick has none.
ivec3 layerAt(ivec2 px) {
  if (!surfaceAt(px) || !(texelFetch(u_surface, px, 0).x < 1e29)) return ivec3(-1);
  return ivec3(clamp(texelFetch(u_surface_colour, px, 0).rgb, 0.0, 1.0) * 255.0 + 0.5);
}
#if PROJECTION <= 2
// The partial pixel of ray result acc at px: with the opaque layer's colour where the brick has one.
vec4 projectionPixel(vec4 acc, ivec2 px) {
  ivec3 b = layerAt(px);
  if (b.r < 0) return acc;
  return vec4(acc.x, float(b.r + 256 * b.g + 65536 * b.b), 0.0, acc.w + 2.0);
}
#elif PROJECTION == 3
// average bounded: (sum, layer r + 256 g + 65536 b, count, flags) (ValueSumBounded).
vec4 projectionPixel(vec4 acc, ivec2 px) {
  if (u_bounded == 0) return acc;
  vec4 p = vec4(acc.x, 0.0, acc.w, acc.w > 0.0 ? 1.0 : 0.0);
  ivec3 b = layerAt(px);
  if (b.r >= 0) p.y = float(b.r + 256 * b.g + 65536 * b.b), p.w += 2.0;
  return p;
}
#else
// additive bounded (AdditiveBounded): each float the integer h + 65536 l, h a sum's half bits, l
// the layer's r, g, b, then the flags (1: a sum, 2: a layer). The same rounding as the wire's.
vec4 projectionPixel(vec4 acc, ivec2 px) {
  if (u_bounded == 0) return acc;
  ivec3 b = layerAt(px);
  bool value = any(greaterThan(acc, vec4(0.0)));
  uvec4 hi = uvec4(b.r >= 0 ? uvec3(b) : uvec3(0u), (value ? 1u : 0u) + (b.r >= 0 ? 2u : 0u));
  vec4 s = value ? min(acc, vec4(65504.0)) : vec4(0.0);
  uvec4 h = uvec4(packHalf2x16(vec2(s.x, 0.0)), packHalf2x16(vec2(s.y, 0.0)),
                  packHalf2x16(vec2(s.z, 0.0)), packHalf2x16(vec2(s.w, 0.0))) & 0xffffu;
  return vec4((h & 0xffffu) + 65536u * hi);
}
#endif

// mip / minip: a block whose samples all lie at or below (above) what the ray already holds cannot
// change it, and is jumped: u_block_range holds each block's (min, max) over the samples of its
// cells (BrickBlocks::vmin / vmax), which bound the trilinear field inside it (a convex
// combination of them, up to one float rounding of the filter). Exact for the result, whatever
// the blocks' opacity; before any sample is taken nothing is jumped. Average and additive jump no
// such block (every sample adds to a sum).
#if PROJECTION <= 2
uniform sampler3D u_block_range;
bool blockCannotChange(ivec3 idx, vec4 acc) {
  if (!(acc.w > 0.0)) return false;
  vec2 r = texelFetch(u_block_range, idx, 0).rg;
#if PROJECTION == 1
  return r.y <= acc.x;
#else
  return r.x >= acc.x;
#endif
}
#define BLOCK_CANNOT_CHANGE(idx, acc) blockCannotChange(idx, acc)
#else
#define BLOCK_CANNOT_CHANGE(idx, acc) false
#endif

void projectValue(inout vec4 acc, float v) {
  if (isnan(v)) return;
#if PROJECTION == 1
  acc = vec4(acc.w > 0.0 ? max(acc.x, v) : v, 0.0, 0.0, 1.0);
#elif PROJECTION == 2
  acc = vec4(acc.w > 0.0 ? min(acc.x, v) : v, 0.0, 0.0, 1.0);
#else
  acc += vec4(v, 0.0, 0.0, 1.0);
#endif
}

// Lattice samples k0 .. k1 - 1 into acc.
void projectSamples(inout vec4 acc, int k0, int k1, vec3 dir) {
  for (int k = k0; k < k1; ++k) {
    float v = sampleVolume(u_eye + float(k) * u_delta * dir);
#if PROJECTION == 4
    vec4 e = classify(v);  // NaN: transparent
    float a = 1.0 - exp(-e.a * u_delta);
    acc += vec4(e.rgb * a, a);
#else
    projectValue(acc, v);
#endif
  }
}

#ifdef MIP_EXACT
// The cubic's extremum over s in [0, 1] of the trilinear field of corners c (c[i], i = x + 2y + 4z)
// at local point l0 + dl s.
float cellExtremum(float c[8], vec3 l0, vec3 dl) {
  // f = a + bx x + by y + bz z + bxy xy + bxz xz + byz yz + bxyz xyz
  float a = c[0], bx = c[1] - c[0], by = c[2] - c[0], bz = c[4] - c[0];
  float bxy = c[3] - c[1] - c[2] + c[0], bxz = c[5] - c[1] - c[4] + c[0], byz = c[6] - c[2] - c[4] + c[0];
  float bxyz = c[7] - c[3] - c[5] - c[6] + c[1] + c[2] + c[4] - c[0];
  float x0 = l0.x, y0 = l0.y, z0 = l0.z, dx = dl.x, dy = dl.y, dz = dl.z;
  float k0 = a + bx * x0 + by * y0 + bz * z0 + bxy * x0 * y0 + bxz * x0 * z0 + byz * y0 * z0 + bxyz * x0 * y0 * z0;
  float k1 = bx * dx + by * dy + bz * dz + bxy * (x0 * dy + dx * y0) + bxz * (x0 * dz + dx * z0) +
             byz * (y0 * dz + dy * z0) + bxyz * (dx * y0 * z0 + x0 * dy * z0 + x0 * y0 * dz);
  float k2 = bxy * dx * dy + bxz * dx * dz + byz * dy * dz + bxyz * (dx * dy * z0 + dx * y0 * dz + x0 * dy * dz);
  float k3 = bxyz * dx * dy * dz;
  float f1 = k0 + k1 + k2 + k3;
#if PROJECTION == 1
  float best = max(k0, f1);
#else
  float best = min(k0, f1);
#endif
  // Roots of 3 k3 s^2 + 2 k2 s + k1 (a linear one when k3 is negligible).
  float qa = 3.0 * k3, qb = 2.0 * k2, qc = k1;
  float r[2] = float[2](-1.0, -1.0);
  if (abs(qa) <= 1e-12 * (abs(qb) + abs(qc))) {
    if (qb != 0.0) r[0] = -qc / qb;
  } else {
    float disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      // The numerically stable pair: q = -(b + sign(b) sqrt(disc)) / 2.
      float q = -0.5 * (qb + (qb >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
      r[0] = q / qa;
      if (q != 0.0) r[1] = qc / q;
    }
  }
  for (int i = 0; i < 2; ++i)
    if (r[i] > 0.0 && r[i] < 1.0) {
      float s = r[i];
      float f = k0 + s * (k1 + s * (k2 + s * k3));
#if PROJECTION == 1
      best = max(best, f);
#else
      best = min(best, f);
#endif
    }
  return best;
}

// The exact extremum of the field along the pixel's ray inside this brick's own box (clipped, up
// to the opaque layer) into acc. The ray, its span and its texel coordinates are taken in double
// (Camera::pixelRay's and the reference's arithmetic): in float, the eye and the direction are
// off by ~1e-7 rad (~1e-5 voxel at 100 voxels from the eye), and the span's ends t0, t1 (brickSpan,
// clipRay: float products of t ~ 100) by up to an ulp of t, 7.6e-6-1.5e-5 world units at
// t in [64, 256]. Where the ray's extremum lies at an end (a line of the lattice in
// tests/mpi/projection.sh reaching the volume's face, the field falling by its value per voxel
// away from it), an end off by that much moved the value by 1.6e-5 of the range (measured on
// that lattice, the float ends with the double ray).
uniform dvec3 u_eye_d;
uniform dvec3 u_forward_d;
uniform dvec3 u_right_d;
uniform dvec3 u_up_d;
uniform dvec2 u_pixel_scale_d;
uniform dvec3 u_box_lo_d, u_box_hi_d;             // the brick's own box (world)
uniform dvec3 u_index_scale_d, u_index_offset_d;  // texel index = world * scale + offset

// The span of o + t d (t >= 0) in the brick's own box, cut by the clip region (volume_clip.glsl's
// clipRay in double, its planes as float uniforms) and the opaque layer at pixel px. A ray lying
// in a face plane shared by two bricks is walked by both: the max (min) of the two is the same.
dvec2 exactSpan(dvec3 o, dvec3 d, ivec2 px) {
  double t0 = 0.0LF, t1 = 1.0e300LF;
  for (int a = 0; a < 3; ++a) {
    if (d[a] != 0.0LF) {
      double ta = (u_box_lo_d[a] - o[a]) / d[a], tb = (u_box_hi_d[a] - o[a]) / d[a];
      t0 = max(t0, min(ta, tb));
      t1 = min(t1, max(ta, tb));
    } else if (o[a] < u_box_lo_d[a] || o[a] > u_box_hi_d[a]) {
      t1 = t0;
    }
  }
  for (int i = 0; i < u_clip_count; ++i) {
    dvec3 n = dvec3(u_clip[i].xyz);
    double nd = dot(n, d), gap = double(u_clip[i].w) - dot(n, o);
    if (nd > 0.0LF) t1 = min(t1, gap / nd);
    else if (nd < 0.0LF) t0 = max(t0, gap / nd);
    else if (gap < 0.0LF) t1 = min(t1, t0);
  }
  if (surfaceAt(px)) t1 = min(t1, double(texelFetch(u_surface, px, 0).x));
  return dvec2(t0, t1);
}

void projectExact(inout vec4 acc, ivec2 px) {
  ivec3 size = textureSize(u_volume, 0);
  dvec2 sd = dvec2(double(gl_FragCoord.x) * u_pixel_scale_d.x - 1.0LF,
                   1.0LF - double(gl_FragCoord.y) * u_pixel_scale_d.y);
  dvec3 od = u_eye_d, dd;
  if (u_orthographic != 0) {
    od += sd.x * u_right_d + sd.y * u_up_d;
    dd = u_forward_d;
  } else {
    dd = normalize(u_forward_d + sd.x * u_right_d + sd.y * u_up_d);
  }
  dvec2 span = exactSpan(od, dd, px);
  if (!(span.x < span.y)) return;
  // Texel index coordinates (texel centres at integers) of the ray from its entry into the brick:
  // u(s) = u_o + s u_d, s = t - t0. Relative to the entry, s and u stay small (a brick's extent
  // in voxels), so their float rounding does not grow with the eye's distance (from the eye,
  // t u_d ~ 100 voxels rounds to 8e-6 voxel a step: measured 2.5e-5 of the range on a lattice of
  // lines, against 1e-5 from the entry). What the float walk and the float cubic leave: 1.4e-6 of
  // the range on that lattice (the walk in double: 3.6e-7, the cubic's rounding; not taken, since
  // a GPU's doubles are 1/2-1/64 of its float rate and the walk divides three times a cell).
  vec3 u_o = vec3((od + span.x * dd) * u_index_scale_d + u_index_offset_d);
  vec3 u_d = vec3(dd * u_index_scale_d);
  float s = 0.0, s1 = float(span.y - span.x);
  int guard = 3 * (size.x + size.y + size.z) + 8;
  while (s < s1 && guard-- > 0) {
    vec3 ua = u_o + s * u_d;
    ivec3 cell = clamp(ivec3(floor(ua + sign(u_d) * 1e-4)), ivec3(0), size - 2);
    // Where the ray leaves the cell on each axis.
    float sb = s1;
    for (int ax = 0; ax < 3; ++ax) {
      if (abs(u_d[ax]) < 1e-20) continue;
      float plane = float(cell[ax] + (u_d[ax] > 0.0 ? 1 : 0));
      float se = (plane - u_o[ax]) / u_d[ax];
      if (se > s) sb = min(sb, se);
    }
    if (!(sb > s)) sb = min(s1, s + 1e-4 / max(length(u_d), 1e-20));  // no progress: nudge
    float c[8];
    bool missing = false;
    for (int i = 0; i < 8; ++i) {
      c[i] = texelFetch(u_volume, cell + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1), 0).r;
      missing = missing || isnan(c[i]);
    }
    if (!missing) {
      vec3 l0 = clamp(ua - vec3(cell), 0.0, 1.0), l1 = clamp(u_o + sb * u_d - vec3(cell), 0.0, 1.0);
      projectValue(acc, cellExtremum(c, l0, l1 - l0));
    }
    s = sb;
  }
}
#endif
