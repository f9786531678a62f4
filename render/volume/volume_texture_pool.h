#pragma once
// Brick textures kept from one time step to the next. Every step of a series (in situ each
// execute(), a session's or the service's time steps) drops its bricks and uploads new ones of
// the same sizes; allocating each 3D texture anew costs its pages afresh (llvmpipe zeroes it: on
// the Gray-Scott example at 256^3 that was as much as uploading the samples). A renderer gives
// its bricks' textures back here when it is dropped, and the next one takes a spare of the same
// size and overwrites it whole. Spares that the next step did not take are deleted then
// (dropSpares), so a layout change never holds two sets beyond its upload.
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "render/gl/gl_api.h"

namespace sortlast {

// A new GL_R32F 3D texture of `size`, bound to GL_TEXTURE_3D on the active unit, contents undefined.
unsigned newVolumeTexture(const GlApi& gl, const glm::ivec3& size);

class VolumeTexturePool {
 public:
  explicit VolumeTexturePool(const GlApi& gl) : gl_(gl) {}
  ~VolumeTexturePool() { dropSpares(); }
  VolumeTexturePool(const VolumeTexturePool&) = delete;
  VolumeTexturePool& operator=(const VolumeTexturePool&) = delete;

  // A GL_R32F 3D texture of `size` bound to GL_TEXTURE_3D on the active unit, its contents
  // undefined (the caller writes every texel): a spare of that size, else a new one.
  unsigned take(const glm::ivec3& size);
  // Keeps `texture` (of `size`) for a later take().
  void give(unsigned texture, const glm::ivec3& size);
  // Deletes every spare.
  void dropSpares();

 private:
  const GlApi& gl_;
  std::vector<std::pair<glm::ivec3, unsigned>> spare_;
};

}  // namespace sortlast
