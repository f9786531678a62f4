#include "render/volume/isosurface_uniforms.h"

#include <stdexcept>
#include <string>

namespace sortlast {

void setIsosurfaceUniforms(const GlProgram& program, const std::vector<Isovalue>& isovalues,
                           const Shading& shading, const VolumeBrick& b, const Box3& volume) {
  if (isovalues.empty() || isovalues.size() > size_t(kMaxIsovalues))
    throw std::logic_error("ray caster: " + std::to_string(isovalues.size()) + " isovalues (1 to " +
                           std::to_string(kMaxIsovalues) + " are drawn)");
  program.set("u_iso_count", int(isovalues.size()));
  for (size_t i = 0; i < isovalues.size(); ++i) {
    const Isovalue& v = isovalues[i];
    const std::string n = "[" + std::to_string(i) + "]";
    program.set("u_iso_value" + n, float(v.value));
    program.set("u_iso_colour" + n, glm::vec4(glm::vec3(v.colour), float(v.opacity)));
  }
  program.set("u_iso_phong", glm::vec3(float(shading.ambient), float(shading.diffuse), float(shading.specular)));
  program.set("u_iso_shininess", float(shading.shininess));
  program.set("u_iso_inv_spacing", glm::vec3(1.0 / b.spacing));
}

bool isoVisible(const std::vector<Isovalue>& isovalues, float lo, float hi) {
  for (const Isovalue& v : isovalues)
    if (float(v.value) >= lo && float(v.value) <= hi) return true;
  return false;
}

}  // namespace sortlast
