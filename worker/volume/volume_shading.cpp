#include "worker/volume/volume_shading.h"

#include <stdexcept>

namespace sortlast {

namespace {

// The float version of common/shading.h shadeSample(), the gradient read from the brick texture:
// one voxel is u_voxel_tex in texture coordinates, and the difference over two voxels times
// u_gradient_scale = 1 / (2 spacing) is the world gradient. Returns c when the weight is 0, and
// c + w (shaded - c) otherwise, as the reference does.
constexpr const char* kShadingGlsl = R"(#define SHADING 1
uniform vec3 u_phong;           // ka, kd, ks
uniform float u_shininess;      // p
uniform vec3 u_voxel_tex;       // one voxel along each axis, in texture coordinates
uniform vec3 u_gradient_scale;  // 1 / (2 spacing) per axis
uniform float u_flat_gradient;  // |gradient| (per world unit) at or below which a sample is unshaded
vec3 shadeColour(vec3 c, sampler3D volume, vec3 tc, vec3 dir) {
  vec3 dx = vec3(u_voxel_tex.x, 0.0, 0.0), dy = vec3(0.0, u_voxel_tex.y, 0.0),
       dz = vec3(0.0, 0.0, u_voxel_tex.z);
  vec3 g = vec3(texture(volume, tc + dx).r - texture(volume, tc - dx).r,
                texture(volume, tc + dy).r - texture(volume, tc - dy).r,
                texture(volume, tc + dz).r - texture(volume, tc - dz).r) * u_gradient_scale;
  float len = length(g);
  float w = clamp(len / u_flat_gradient - 1.0, 0.0, 1.0);
  if (w == 0.0) return c;
  float cosine = min(abs(dot(g, dir)) / len, 1.0);
  vec3 shaded = clamp(c * (u_phong.x + u_phong.y * cosine) + u_phong.z * pow(cosine, u_shininess),
                      0.0, 1.0);
  return c + w * (shaded - c);
}
)";

}  // namespace

std::string withShading(const char* fragment_src) {
  std::string src = fragment_src;
  const std::string version = "#version 450 core\n";
  if (src.rfind(version, 0) != 0) throw std::logic_error("volume shader: no #version line");
  src.insert(version.size(), kShadingGlsl);
  return src;
}

void setShadingUniforms(const GlApi& gl, unsigned program, const Shading& s, const VolumeBrick& b,
                        const TransferFunction& tf) {
  auto at = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  gl.Uniform3f(at("u_phong"), float(s.ambient), float(s.diffuse), float(s.specular));
  gl.Uniform1f(at("u_shininess"), float(s.shininess));
  const glm::dvec3 voxel = 1.0 / glm::dvec3(b.brick.stored.size());
  gl.Uniform3f(at("u_voxel_tex"), float(voxel.x), float(voxel.y), float(voxel.z));
  const glm::dvec3 scale = 0.5 / b.spacing;
  gl.Uniform3f(at("u_gradient_scale"), float(scale.x), float(scale.y), float(scale.z));
  gl.Uniform1f(at("u_flat_gradient"), float(flatGradient(tf.rangeLo(), tf.rangeHi(), b.spacing)));
}

}  // namespace sortlast
