#pragma once
// How a metaball surface point is shaded: the one definition the CPU reference uses and the GLSL
// copy (render/particles/metaball_common.glsl, shade()) cites. Changing it means changing both.
//
//   L       = -D                        headlight: the light comes from the eye along the ray
//   diffuse = max(dot(N, L), 0)         N the outward unit normal, -grad F / |grad F|
//   rgb     = clamp(colour * (0.2 + 0.8 * diffuse), 0, 1)
//   alpha   = 1                         opaque (premultiplied, so rgb is already the colour)
//
// A miss is (0, 0, 0, 0).
#include <glm/glm.hpp>

namespace sortlast {

inline constexpr double kMetaballAmbient = 0.2;
inline constexpr double kMetaballDiffuse = 0.8;

// `normal` outward and unit, `dir` the unit ray direction (eye to surface). Templated on the
// scalar so float and double callers use the same expression.
template <typename T>
glm::vec<4, T> shadeMetaball(const glm::vec<3, T>& normal, const glm::vec<3, T>& dir,
                             const glm::vec<3, T>& colour) {
  T diffuse = glm::max(glm::dot(normal, -dir), T(0));
  glm::vec<3, T> rgb = colour * (T(kMetaballAmbient) + T(kMetaballDiffuse) * diffuse);
  return glm::vec<4, T>(glm::clamp(rgb, T(0), T(1)), T(1));
}

}  // namespace sortlast
