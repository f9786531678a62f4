// 3D-texture slicing's fragment shader, last chunk (render/volume/slicing_renderer.cpp composes
// [volume_shading] slicing_inputs [preintegrated_segment] slicing, the bracketed ones by variant).
// It classifies the interpolated sample through the transfer-function table (r, g, b, tau) and
// corrects opacity for the actual distance between slices along this pixel's ray,
// ds = spacing / cos(angle to the view axis), so that slicing and the reference integrator are the
// same emission-absorption model. With render.shading a variant
// of the program shades the colour first (shadedSample; with pre-integration, the segment's colour
// with the gradient at its middle).
//
// Pre-integration (PREINTEGRATED defined; transfer.preintegrated): the fragment stands for the
// segment of its pixel's ray from ds/2 before the slice to ds/2 beyond it, the stretch its
// midpoint sample stands for, and takes that segment's colour and opacity from the 2D table
// (transfer/preintegration.h, built for L0 = spacing) between the values at its ends (with the
// midpoint's value: see segment() in render/volume/preintegrated_segment.glsl), with the
// table's length correction for L = ds (exact for the opacity). Both ends are read from this
// brick's texture: they lie ds/2 from the fragment, within the ghost layer while the perpendicular
// reach, (spacing / 2) |dir . n| / (dir . forward), stays under one voxel: spacing <= 2 voxels
// (the scene enforces it) and up to 15 % beyond at a 60-degree field of view's corners, where the
// texture's clamped edge is read (measured seams at 2 voxels: 2/255 at most). Segments cross brick
// faces as the ray caster's do (render/volume/raycast_march.frag.glsl).
//
// Projections (PROJECTION defined: 1 mip, 2 minip, 3 average, 4 additive; render.blend): each
// fragment is one sample of its pixel's ray, where the ray crosses a slice plane, written in
// the ray caster's partial-image format (compositing/projection_pixels.h) and combined by the
// blend equation slicing_renderer.cpp sets, so no order is needed:
//   mip: (v, 0, 0, 1) under GL_MAX; minip: (-v, 0, 0, 1) under GL_MAX (the renderer negates the
//     value back); the largest / smallest trilinear value among the ray's slice-plane samples;
//   average: (v, 0, 0, 1) under GL_FUNC_ADD: the sum of those samples and their count;
//   additive: (c a, a), a = 1 - exp(-tau ds), under GL_FUNC_ADD, ds the ray's length between
//     two slices (as emission-absorption's opacity correction): emission without absorption.
// A ray's slice-plane samples are evenly spaced along it, ds apart, as the ray caster's lattice
// samples are delta apart (ds = delta on the view axis, longer off it), so both converge to the
// reference's mean, extremum and sum as the step shrinks. NaN samples (a stencil touching a
// missing voxel) are not taken (discarded), as the ray caster does not take them.

// (r, g, b, tau) of the sample at world point p, its colour shaded with the field's gradient in the
// program's shaded variant (SHADING defined; shadeColour: render/volume/volume_shading.glsl, put in
// front; light at the eye).
// A sample of zero tau adds nothing whatever its colour: no gradient is read.
// The ray from its origin to p: from the eye, or (orthographic) along the view axis from the
// pixel's point on the eye plane, so its length is p's t either way.
vec3 rayTo(vec3 p) { return u_orthographic != 0 ? u_forward * dot(p - u_eye, u_forward) : p - u_eye; }

// (r, g, b, tau) of value v through the transfer-function table.
vec4 classified(float v) {
  if (isnan(v)) return vec4(0.0);  // its trilinear stencil touches a missing sample
  float x = clamp(scaledValue(v) * u_value_map.x + u_value_map.y, 0.0, 1.0);
  return texture(u_table, x * u_table_map.x + u_table_map.y);
}

vec4 shadedSample(vec3 p) {
  vec3 tc = p * u_tex_scale + u_tex_offset;
  vec4 e = classified(volumeAt(u_volume, tc));
#ifdef SHADING
  if (e.a > 0.0) e.rgb = shadeColour(e.rgb, u_volume, tc, normalize(rayTo(p)));
#endif
  return e;
}

void main() {
  // An opaque particle surface in this brick ends the ray: nothing behind it is drawn.
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (!clipKeeps(v_world)) discard;  // clip.planes, clip.box: the sample lies outside
  if (u_has_surface != 0 && all(greaterThanEqual(px, u_surface_rect.xy)) &&
      all(lessThan(px, u_surface_rect.xy + u_surface_rect.zw)) &&
      length(rayTo(v_world)) >= texelFetch(u_surface, px, 0).x)
    discard;
#if defined(PROJECTION)
  float v = volumeAt(u_volume, v_world * u_tex_scale + u_tex_offset);
  if (isnan(v)) discard;
#if PROJECTION == 4
  vec4 e = classified(v);
  vec3 d = rayTo(v_world);
  float a = 1.0 - exp(-e.a * (u_spacing * length(d) / dot(d, u_forward)));
  frag = vec4(e.rgb * a, a);
#elif PROJECTION == 2
  frag = vec4(-v, 0.0, 0.0, 1.0);
#else
  frag = vec4(v, 0.0, 0.0, 1.0);
#endif
#elif defined(PREINTEGRATED)
  vec3 d = rayTo(v_world);
  float ds = u_spacing * length(d) / dot(d, u_forward);
  vec3 half_step = (0.5 * ds / length(d)) * d;
  float vf = volumeAt(u_volume, (v_world - half_step) * u_tex_scale + u_tex_offset);
  float vm = volumeAt(u_volume, v_world * u_tex_scale + u_tex_offset);
  float vb = volumeAt(u_volume, (v_world + half_step) * u_tex_scale + u_tex_offset);
  vec4 e = segment(vf, vm, vb, ds);
#ifdef SHADING
  if (e.a > 0.0)
    e.rgb = e.a * shadeColour(e.rgb / e.a, u_volume, v_world * u_tex_scale + u_tex_offset, normalize(d));
#endif
  frag = e;
#else
  vec4 e = shadedSample(v_world);
  vec3 d = rayTo(v_world);
  float ds = u_spacing * length(d) / dot(d, u_forward);
  float a = 1.0 - exp(-e.a * ds);
  frag = vec4(e.rgb * a, a);
#endif
}
