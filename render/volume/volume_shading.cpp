#include "render/volume/volume_shading.h"

#include <cstdlib>
#include <string>

namespace sortlast {

void setShadingUniforms(const GlProgram& program, const Shading& s, const VolumeBrick& b,
                        const TransferFunction& tf) {
  program.set("u_phong", glm::vec3(float(s.ambient), float(s.diffuse), float(s.specular)));
  program.set("u_shininess", float(s.shininess));
  const glm::dvec3 voxel = 1.0 / glm::dvec3(b.brick.stored.size());
  program.set("u_voxel_tex", glm::vec3(voxel));
  const glm::dvec3 scale = 0.5 / b.spacing;
  program.set("u_gradient_scale", glm::vec3(scale));
  program.set("u_flat_gradient", float(flatGradient(tf.rangeLo(), tf.rangeHi(), b.spacing)));
}

bool floatFilter(const GlDeviceInfo& device) {
  if (const char* force = std::getenv("SORTLAST_FLOAT_FILTER")) return std::string(force) == "1";
  return device.device >= 0;
}

}  // namespace sortlast
