// The slices method's ray pass, after render/particles/metaball_common.glsl
// (metaball_slices_splat.comp.glsl describes both passes; SIDE as there).
layout(std430, binding = 1) readonly buffer SlotOf { int slot_of[]; };
layout(std430, binding = 4) readonly buffer Samples { float samples[]; };
uniform float u_spacing;
uniform ivec4 u_voxel_lo;  // global index of the brick's voxel (0, 0, 0), xyz
uniform ivec4 u_dims;      // voxels per axis, xyz
uniform float u_cap;       // samples allowed per pixel (those with field > 0 count)
uniform int u_refine;      // refinement passes
uniform vec3 u_colour;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_surface;
const int CELLS = SIDE - 1;

// The brick's voxel holding lattice cell c, and its slot (-1: no slot, or outside the brick).
ivec3 voxelOfCell(ivec3 c) { return ivec3(floor(vec3(c) / float(CELLS))); }
int slotOf(ivec3 v) {
  ivec3 l = v - u_voxel_lo.xyz;
  if (any(lessThan(l, ivec3(0))) || any(greaterThanEqual(l, u_dims.xyz))) return -1;
  return slot_of[(l.z * u_dims.y + l.y) * u_dims.x + l.x];
}
// The interpolated field at x and the slot it came from (-1: none, the field is 0).
float fieldAt(vec3 x, out int slot) {
  vec3 g = x / u_spacing;
  ivec3 c = ivec3(floor(g));
  vec3 f = g - vec3(c);
  ivec3 v = voxelOfCell(c);
  slot = slotOf(v);
  if (slot < 0) return 0.0;
  ivec3 l = c - v * CELLS;
  int base = slot * SIDE * SIDE * SIDE + (l.z * SIDE + l.y) * SIDE + l.x;
  const int DY = SIDE, DZ = SIDE * SIDE;
  float c00 = mix(samples[base], samples[base + 1], f.x);
  float c10 = mix(samples[base + DY], samples[base + DY + 1], f.x);
  float c01 = mix(samples[base + DZ], samples[base + DZ + 1], f.x);
  float c11 = mix(samples[base + DZ + DY], samples[base + DZ + DY + 1], f.x);
  return mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z);
}
float fieldAt(vec3 x) { int s; return fieldAt(x, s); }
// Where the ray leaves voxel v (slab exits).
float voxelExit(ivec3 v, vec3 d) {
  vec3 lo = vec3(v * CELLS) * u_spacing, hi = vec3((v + 1) * CELLS) * u_spacing;
  vec3 a = (lo - u_eye) / d, b = (hi - u_eye) / d;
  vec3 m = max(a, b);
  return min(min(m.x, m.y), m.z);
}
vec2 gridInterval(vec3 d) {
  vec3 lo = vec3(u_voxel_lo.xyz * CELLS) * u_spacing;
  vec3 hi = vec3((u_voxel_lo.xyz + u_dims.xyz) * CELLS) * u_spacing;
  vec3 a = (lo - u_eye) / d, b = (hi - u_eye) / d;
  vec3 mn = min(a, b), mx = max(a, b);
  return vec2(max(max(mn.x, mn.y), mn.z), min(min(mx.x, mx.y), mx.z));
}

void main() {
  o_colour = vec4(0.0);
  o_surface = vec4(INF, 0.0, 0.0, 0.0);
  vec3 d = safeDir(pixelRay(gl_FragCoord.xy));
  vec4 iv;
  if (!rayStretch(d, gridInterval(d), iv)) return;
  float t_in = iv.x, t_out = iv.y, g0 = iv.z, g1 = iv.w;

  // Samples: the lattice points k w in [t_in, t_out): each point belongs to exactly one brick
  // (the half-open rule of the volume bricks), and no brick adds samples at its faces, so every
  // decomposition takes the same samples. The bracket starts at the point before the first one
  // (in the brick in front, or before the data), evaluated here: the lattice reaches w + s
  // beyond the brick. If it is already inside, the brick in front found this surface. A sample
  // in a voxel without a slot has F = 0: the march jumps to where the ray leaves that voxel, and
  // the point before the next sample (in the jumped stretch) carries the bracket with I = -T, as
  // if every jumped sample had been taken.
  float s = latticeCeil(t_in);
  if (s >= t_out || s > g1) return;
  float t_last = (round(s / u_w) - 1.0) * u_w;
  float i_last = sqrt(fieldAt(u_eye + t_last * d)) - u_T, n = 0.0;
  if (i_last >= 0.0) return;
  bool hit = false;
  vec4 b = vec4(0.0);
  for (int iter = 0; iter < 1000000; ++iter) {
    if (s >= t_out || s > g1) break;
    int slot;
    float F = fieldAt(u_eye + s * d, slot);
    if (slot < 0) {
      float t_exit = voxelExit(voxelOfCell(ivec3(floor((u_eye + s * d) / u_spacing))), d);
      float c = latticeCeil(t_exit);
      if (c <= s) c = latticeNext(s);
      float prev = (round(c / u_w) - 1.0) * u_w;
      t_last = max(s, prev);
      i_last = -u_T;
      s = c;
      continue;
    }
    if (n >= u_cap) break;  // out of samples: a hole, as the other methods
    if (F > 0.0) n += 1.0;
    float value = sqrt(F) - u_T;
    if (value >= 0.0) {
      hit = true;
      b = vec4(t_last, i_last, s, value);
      break;
    }
    t_last = s;
    i_last = value;
    s = latticeNext(s);
  }
  if (!hit) return;

  // Refinement (eqs. 5-6) on the interpolated field.
  for (int i = 0; i < u_refine; ++i) {
    float q[4];
    refineProbes(b, q);
    vec4 f;
    for (int k = 0; k < 4; ++k) f[k] = fieldAt(u_eye + q[k] * d);
    b = refineBracket(b, q, f);
  }
  float t = secantEstimate(b);

  // Gradient of the interpolated field by central differences one spacing apart.
  vec3 x = u_eye + t * d;
  float e = u_spacing;
  vec3 grad = vec3(fieldAt(x + vec3(e, 0, 0)) - fieldAt(x - vec3(e, 0, 0)),
                   fieldAt(x + vec3(0, e, 0)) - fieldAt(x - vec3(0, e, 0)),
                   fieldAt(x + vec3(0, 0, e)) - fieldAt(x - vec3(0, 0, e)));
  vec3 nrm;
  o_colour = shade(u_colour, grad, d, nrm);
  o_surface = vec4(t, nrm);
}
