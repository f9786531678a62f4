// volumeAt(volume, tc): the brick texture's trilinear value at texture coordinate tc, the one
// filter both volume renderers read the volume with (values and gradient taps).
//
// A GPU's texture unit interpolates with fixed-point weights (8 fractional bits on NVIDIA's): a
// value then errs by up to 1/256 of the step between neighbouring voxels, which a sharp transfer
// function or a normalised gradient magnifies (measured on an H200 against llvmpipe, neghip with
// the sharp preset, shaded: 21/255, 57 dB). FLOAT_FILTER (hardware devices:
// render/volume/volume_shading.h floatFilter) interpolates the 8 texels in float instead, as
// llvmpipe's texture unit and the CPU reference do; clamped at the edges as CLAMP_TO_EDGE is.
#ifdef FLOAT_FILTER
float volumeAt(sampler3D volume, vec3 tc) {
  ivec3 size = textureSize(volume, 0);
  vec3 p = tc * vec3(size) - 0.5;
  vec3 base = floor(p), f = p - base;
  ivec3 lo = clamp(ivec3(base), ivec3(0), size - 1), hi = clamp(ivec3(base) + 1, ivec3(0), size - 1);
  float c000 = texelFetch(volume, ivec3(lo.x, lo.y, lo.z), 0).r, c100 = texelFetch(volume, ivec3(hi.x, lo.y, lo.z), 0).r;
  float c010 = texelFetch(volume, ivec3(lo.x, hi.y, lo.z), 0).r, c110 = texelFetch(volume, ivec3(hi.x, hi.y, lo.z), 0).r;
  float c001 = texelFetch(volume, ivec3(lo.x, lo.y, hi.z), 0).r, c101 = texelFetch(volume, ivec3(hi.x, lo.y, hi.z), 0).r;
  float c011 = texelFetch(volume, ivec3(lo.x, hi.y, hi.z), 0).r, c111 = texelFetch(volume, ivec3(hi.x, hi.y, hi.z), 0).r;
  return mix(mix(mix(c000, c100, f.x), mix(c010, c110, f.x), f.y),
             mix(mix(c001, c101, f.x), mix(c011, c111, f.x), f.y), f.z);
}
#else
float volumeAt(sampler3D volume, vec3 tc) { return texture(volume, tc).r; }
#endif
