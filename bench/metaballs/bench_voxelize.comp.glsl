// bench/metaballs/metaball_slices.cpp's GL bit voxelization: the same test as
// render/particles/metaball_slices.cpp (sphere of radius h padded 1% against each voxel's closed
// box), one invocation per particle, one bit per voxel (atomicOr), x fastest. Not used by the
// renderer: measured against the CPU pass it would replace.
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Centres { vec4 centres[]; };
layout(std430, binding = 2) buffer Bits { uint bits[]; };
uniform uint u_count;
uniform float u_r;
uniform float u_edge;
uniform ivec4 u_lo;    // xyz
uniform ivec4 u_dims;  // xyz
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  vec3 p = centres[i].xyz;
  ivec3 a = max(ivec3(floor((p - u_r) / u_edge)) - u_lo.xyz, ivec3(0));
  ivec3 b = min(ivec3(floor((p + u_r) / u_edge)) - u_lo.xyz, u_dims.xyz - 1);
  for (int z = a.z; z <= b.z; ++z)
    for (int y = a.y; y <= b.y; ++y)
      for (int x = a.x; x <= b.x; ++x) {
        vec3 lo = vec3(u_lo.xyz + ivec3(x, y, z)) * u_edge, hi = lo + u_edge;
        vec3 g = max(max(lo - p, p - hi), vec3(0.0));
        if (dot(g, g) > u_r * u_r) continue;
        uint v = uint((z * u_dims.y + y) * u_dims.x + x);
        atomicOr(bits[v >> 5], 1u << (v & 31u));
      }
}
