#include "render/volume/volume_clip.h"

#include <stdexcept>
#include <string>

namespace sortlast {

void setClipUniforms(const GlProgram& program, const ClipRegion& clip) {
  const std::vector<ClipPlane> hs = clip.halfSpaces();
  if (int(hs.size()) > kMaxClipHalfSpaces)
    throw std::logic_error("volume clip: " + std::to_string(hs.size()) + " half-spaces, at most " +
                           std::to_string(kMaxClipHalfSpaces));
  for (size_t i = 0; i < hs.size(); ++i)
    program.set("u_clip[" + std::to_string(i) + "]",
                glm::vec4(glm::vec3(hs[i].normal), float(hs[i].offset)));
  program.set("u_clip_count", int(hs.size()));
}

Rect clippedRectOf(const Camera& cam, const Box3& bound, const ClipRegion& clip) {
  if (clip.culls(bound)) return {};
  return screenRectOf(cam, clip.bound(bound));
}

}  // namespace sortlast
