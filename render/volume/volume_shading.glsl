// Gradient shading (transfer/shading.h) in the GL volume renderers' SHADING variant: shadeColour(),
// the float version of transfer/shading.h shadeSample(), the gradient read from the brick texture
// (volumeAt: render/volume/volume_filter.glsl, put in front):
// one voxel is u_voxel_tex in texture coordinates, and the difference over two voxels times
// u_gradient_scale = 1 / (2 spacing) is the world gradient. Returns c when the weight is 0, and
// c + w (shaded - c) otherwise, as the reference does. render/volume/volume_shading.h has why a
// brick's one ghost layer is enough, and sets the uniforms.
uniform vec3 u_phong;           // ka, kd, ks
uniform float u_shininess;      // p
uniform vec3 u_voxel_tex;       // one voxel along each axis, in texture coordinates
uniform vec3 u_gradient_scale;  // 1 / (2 spacing) per axis
uniform float u_flat_gradient;  // |gradient| (per world unit) at or below which a sample is unshaded
vec3 shadeColour(vec3 c, sampler3D volume, vec3 tc, vec3 dir) {
  vec3 dx = vec3(u_voxel_tex.x, 0.0, 0.0), dy = vec3(0.0, u_voxel_tex.y, 0.0),
       dz = vec3(0.0, 0.0, u_voxel_tex.z);
  vec3 g = vec3(volumeAt(volume, tc + dx) - volumeAt(volume, tc - dx),
                volumeAt(volume, tc + dy) - volumeAt(volume, tc - dy),
                volumeAt(volume, tc + dz) - volumeAt(volume, tc - dz)) * u_gradient_scale;
  float len = length(g);
  if (isnan(len)) return c;  // a tap touches a missing sample: unshaded, as the reference
  float w = clamp(len / u_flat_gradient - 1.0, 0.0, 1.0);
  if (w == 0.0) return c;
  float cosine = min(abs(dot(g, dir)) / len, 1.0);
  vec3 shaded = clamp(c * (u_phong.x + u_phong.y * cosine) + u_phong.z * pow(cosine, u_shininess),
                      0.0, 1.0);
  return c + w * (shaded - c);
}
