// The slices method's splat (render/particles/metaball_slices_renderer.h), and how its ray pass
// (metaball_slices_ray.frag.glsl) reads what it writes. SIDE (a slot's lattice points per axis)
// is defined by the renderer (kSliceSlotSide).
//
// kSliceSplatCompute: one work group per occupied coarse voxel (slot), one invocation per lattice
// point of the slot. Each point sums the kernel of every particle on its slot's list, in list
// order (global particle order): a gather form of the paper's splatting. Additive blending or
// float atomics would add in whatever order the rasteriser or the threads run; summing in a fixed
// order gives a point the same value in every slot, brick and rank that holds it. The kernel is
// one function of (particle number, point): another kernel (an anisotropic one, with a frame per
// particle in a buffer indexed by the number in items[j].w) replaces kernelAt alone.
//
// The ray pass (metaball_slices_ray.frag.glsl, after render/particles/metaball_common.glsl for the
// ray, the clip interval, the sample lattice along rays and the refinement probes): each pixel's
// ray samples the trilinear interpolation of the lattice at the points t = k w its brick owns,
// jumps the coarse voxels with no slot (the field is 0 there), refines the first sign change of
// sqrt(F) - T, and shades with the gradient of the interpolated field (central differences one
// lattice spacing apart, so it is continuous across cell faces).
layout(local_size_x = SIDE, local_size_y = SIDE, local_size_z = 1) in;
layout(std430, binding = 1) readonly buffer Offsets { uint offsets[]; };
// The lists as the particles' centres (xyz) and numbers (w, as uint bits): one load per entry.
layout(std430, binding = 2) readonly buffer Items { vec4 items[]; };
layout(std430, binding = 3) readonly buffer SlotVoxel { ivec4 slot_voxel[]; };
layout(std430, binding = 4) writeonly buffer Samples { float samples[]; };
uniform float u_h;
uniform float u_spacing;
uniform uint u_slots;
uniform uint u_first;   // slot of work group (0, 0, 0): dispatches are split at 65,535 groups

#ifdef ANISOTROPIC
// Smoothed anisotropic metaballs (io/anisotropic_kernels.h), as the grid method evaluates them:
// C (1 - |A r| / h)^2 inside the ellipsoid |A r| < h. Per particle 3 vec4: (A row 0, C),
// (A row 1, reach), (A row 2, unused); the item's w holds the particle's number.
layout(std430, binding = 5) readonly buffer Kernels { vec4 kernels[]; };
float kernelAt(vec4 item, vec3 x) {
  vec3 r = x - item.xyz;
  uint i = 3u * floatBitsToUint(item.w);
  vec4 k0 = kernels[i], k1 = kernels[i + 1u], k2 = kernels[i + 2u];
  if (dot(r, r) >= k1.w * k1.w) return 0.0;
  float q = max(1.0 - length(vec3(dot(k0.xyz, r), dot(k1.xyz, r), dot(k2.xyz, r))) / u_h, 0.0);
  return k0.w * q * q;
}
#else
// The paper-2 kernel P(r) = (1 - r/h)^2 for r < h.
float kernelAt(vec4 item, vec3 x) {
  vec3 r = x - item.xyz;
  float d2 = dot(r, r);
  if (d2 >= u_h * u_h) return 0.0;
  float q = 1.0 - sqrt(d2) / u_h;
  return q * q;
}
#endif

// Each invocation sums one column of SIDE points along z: one load of a list entry serves them all
// (measured 3.5x faster than one point per invocation: 0.5 against 1.75 s for the 65,536-particle
// splash in one brick, build/bench/bench_metaball_slices). Every point still adds its list in order.
void main() {
  uint slot = u_first + gl_WorkGroupID.x;
  if (slot >= u_slots) return;
  ivec2 local = ivec2(gl_LocalInvocationID.xy);
  ivec3 k0 = slot_voxel[slot].xyz * (SIDE - 1) + ivec3(local, 0);
  vec3 x[SIDE];
  float f[SIDE];
  for (int z = 0; z < SIDE; ++z) {
    x[z] = vec3(k0 + ivec3(0, 0, z)) * u_spacing;
    f[z] = 0.0;
  }
  for (uint j = offsets[slot]; j < offsets[slot + 1]; ++j) {
    vec4 item = items[j];
    for (int z = 0; z < SIDE; ++z) f[z] += kernelAt(item, x[z]);
  }
  uint base = slot * uint(SIDE * SIDE * SIDE) + uint(local.y * SIDE + local.x);
  for (int z = 0; z < SIDE; ++z) samples[base + uint(z * SIDE * SIDE)] = f[z];
}
