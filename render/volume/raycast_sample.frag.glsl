// The ray caster's fragment shader, its first own chunk: the uniforms, where the particle surface
// is known (surfaceAt), a block's step multiple (blockStep), and how a sample is read
// (sampleVolume; both per variant), classified (classify) and evaluated (sampleAt).
// raycast_march.frag.glsl describes the whole and lists the chunks.
uniform sampler3D u_volume;
uniform sampler1D u_table;
uniform sampler2D u_planes;     // texel (i, axis): world coordinate of block plane i on that axis
uniform usampler3D u_skip;      // per block: r = reach (distance to another class), g = class
uniform vec3 u_tex_scale;
uniform vec3 u_tex_offset;
uniform vec3 u_eye;             // the eye (orthographic: the centre of the eye plane)
uniform vec3 u_forward;
uniform vec3 u_right;           // scaled by tan(fov / 2) * aspect (orthographic: parallel_scale * aspect)
uniform vec3 u_up;              // scaled by tan(fov / 2) (orthographic: parallel_scale)
uniform int u_orthographic;     // 1: parallel rays from the eye plane (Camera::pixelRay)
uniform vec2 u_pixel_scale;     // 2 / width, 2 / height
uniform float u_delta;          // lattice step along every ray (world units)
uniform float u_ert;            // stop at this opacity; > 1: never
uniform vec2 u_value_map;       // normalised value = scaledValue(v) * x + y
uniform vec2 u_table_map;       // table coordinate = normalised * x + y (texel centres at the ends)
uniform sampler2D u_surface;    // particle surface (t, normal) per pixel, t = 1e30 on a miss
uniform int u_has_surface;
uniform ivec4 u_surface_rect;   // x, y, w, h where u_surface is valid (stale elsewhere)
uniform vec3 u_vol_lo;          // the whole volume's world box (floats of the same doubles as
uniform vec3 u_vol_hi;          //   the brick planes at the volume's faces)
out vec4 frag;
// The ray's span through the whole volume cut to the clip region, and the first and last lattice
// samples in it (set by raycast_march.frag.glsl volumeSpan; read by the march and the isosurfaces).
float g_span_t0, g_span_t1;
int g_k_first, g_k_last;

vec3 g_inv;  // 1 / ray direction, per axis
ivec3 g_step;

// This pixel's ray, set by pixelRay() (raycast_march.frag.glsl): its origin g_eye (the eye, or the
// pixel's point on the eye plane when orthographic) and unit direction g_ray_dir. Every chunk from here
// on means the ray's origin by u_eye: samples lie at u_eye + t dir, t from the origin.
vec3 cameraEye() { return u_eye; }
vec3 g_eye;
vec3 g_ray_dir;
#define u_eye g_eye

// Whether u_surface holds the particle surface at pixel px.
bool surfaceAt(ivec2 px) {
  return u_has_surface != 0 && all(greaterThanEqual(px, u_surface_rect.xy)) &&
         all(lessThan(px, u_surface_rect.xy + u_surface_rect.zw));
}

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
// adaptive/adaptive_brick.h sampleCell(), the block-local lattice coordinate clamped to the block;
// the hardware's trilinear filter on the texel centres (offset + local + 0.5) / atlas dims, as
// the plain sampleVolume filters the brick's texture: the same filter precision (float weights
// on llvmpipe; 8 fractional bits on NVIDIA for both), and at lossless settings the two images
// agree within 1/255 (tests/mpi/adaptive.sh lossless).
float sampleVolume(vec3 p) {
  vec3 local = clamp((p * u_index_scale + u_index_offset - g_origin) * g_block.w, vec3(0.0),
                     u_block_cells * g_block.w);
  return texture(u_volume, (g_block.xyz + local + 0.5) * u_atlas_inv).r;
}
// The step multiple of non-empty block idx (class g): 2^level, its level's; the block's table
// texel becomes the current one.
int blockStep(ivec3 idx, uint g) {
  g_block = texelFetch(u_blocks, idx, 0);
  g_origin = vec3(idx) * u_block_cells;
  return u_own_steps != 0 ? int(1.0 / g_block.w + 0.5) : 1;  // 2^level
}
#else
// The volume's value at world point p. The one place that reads the volume: a multi-resolution
// lookup would replace this function alone.
float sampleVolume(vec3 p) { return volumeAt(u_volume, p * u_tex_scale + u_tex_offset); }
// The step multiple of non-empty block idx of class g (1 + log2 m; render/volume/step_rule.h).
int blockStep(ivec3 idx, uint g) { return 1 << int(g - 1u); }
#endif

// (r, g, b, tau) of a value, through the transfer-function table. NaN, a value whose trilinear
// stencil touches a missing sample (io/volume_source.h), is transparent.
vec4 classify(float v) {
  if (isnan(v)) return vec4(0.0);
  float x = clamp(scaledValue(v) * u_value_map.x + u_value_map.y, 0.0, 1.0);
  return texture(u_table, x * u_table_map.x + u_table_map.y);
}

// (r, g, b, tau) at world point p: the one place a sample is evaluated; its colour shaded with the
// field's gradient in the program's shaded variant (SHADING defined; shadeColour:
// render/volume/volume_shading.glsl; light at the eye, so the ray's direction). A sample of
// zero tau adds nothing whatever its colour: no gradient is read. Adaptive bricks are never shaded
// (the scene refuses the combination): their blocks hold only their own samples, not the field one
// voxel across a block face.
#if defined(SHADING) && defined(ADAPTIVE)
#error gradient shading of adaptive blocks
#endif
#ifndef FIELDS  // several fields: raycast_fields.frag.glsl's
vec4 sampleAt(vec3 p) {
  vec4 e = classify(sampleVolume(p));
#ifdef SHADING
  if (e.a > 0.0)
    e.rgb = shadeColour(e.rgb, u_volume, p * u_tex_scale + u_tex_offset, g_ray_dir);
#endif
  return e;
}
#endif
