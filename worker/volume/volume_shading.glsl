// Gradient shading (common/shading.h) in the GL volume renderers' SHADING variant: shadeColour(),
// the float version of common/shading.h shadeSample(), the gradient read from the brick texture:
// one voxel is u_voxel_tex in texture coordinates, and the difference over two voxels times
// u_gradient_scale = 1 / (2 spacing) is the world gradient. Returns c when the weight is 0, and
// c + w (shaded - c) otherwise, as the reference does. worker/volume/volume_shading.h has why a
// brick's one ghost layer is enough, and sets the uniforms.
uniform vec3 u_phong;           // ka, kd, ks
uniform float u_shininess;      // p
uniform vec3 u_voxel_tex;       // one voxel along each axis, in texture coordinates
uniform vec3 u_gradient_scale;  // 1 / (2 spacing) per axis
uniform float u_flat_gradient;  // |gradient| (per world unit) at or below which a sample is unshaded
#ifdef FLOAT_TAPS
// A GPU's texture unit interpolates with fixed-point weights (8 fractional bits on NVIDIA's): two
// taps one voxel apart then differ by up to 1/256 of the local step between voxels, which the
// normalised gradient turns into shading noise where the field is nearly flat (measured on an
// H200: 21/255 on neghip, 57 dB against llvmpipe). On such GPUs the gradient's taps interpolate
// the 8 texels in float instead (scripts/gpu-check; volume_shading.h says when).
float gradientTap(sampler3D volume, vec3 tc) {
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
float gradientTap(sampler3D volume, vec3 tc) { return texture(volume, tc).r; }
#endif
vec3 shadeColour(vec3 c, sampler3D volume, vec3 tc, vec3 dir) {
  vec3 dx = vec3(u_voxel_tex.x, 0.0, 0.0), dy = vec3(0.0, u_voxel_tex.y, 0.0),
       dz = vec3(0.0, 0.0, u_voxel_tex.z);
  vec3 g = vec3(gradientTap(volume, tc + dx) - gradientTap(volume, tc - dx),
                gradientTap(volume, tc + dy) - gradientTap(volume, tc - dy),
                gradientTap(volume, tc + dz) - gradientTap(volume, tc - dz)) * u_gradient_scale;
  float len = length(g);
  float w = clamp(len / u_flat_gradient - 1.0, 0.0, 1.0);
  if (w == 0.0) return c;
  float cosine = min(abs(dot(g, dir)) / len, 1.0);
  vec3 shaded = clamp(c * (u_phong.x + u_phong.y * cosine) + u_phong.z * pow(cosine, u_shininess),
                      0.0, 1.0);
  return c + w * (shaded - c);
}
