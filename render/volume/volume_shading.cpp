#include "render/volume/volume_shading.h"

#include <cstdlib>
#include <string>

namespace sortlast {

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

bool floatFilter(const GlDeviceInfo& device) {
  if (const char* force = std::getenv("SORTLAST_FLOAT_FILTER")) return std::string(force) == "1";
  return device.device >= 0;
}

}  // namespace sortlast
