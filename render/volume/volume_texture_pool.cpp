#include "render/volume/volume_texture_pool.h"

namespace sortlast {

unsigned newVolumeTexture(const GlApi& gl, const glm::ivec3& size) {
  unsigned texture = 0;
  gl.GenTextures(1, &texture);
  gl.BindTexture(GL_TEXTURE_3D, texture);
  gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, size.x, size.y, size.z, 0, GL_RED, GL_FLOAT, nullptr);
  return texture;
}

unsigned VolumeTexturePool::take(const glm::ivec3& size) {
  for (size_t i = 0; i < spare_.size(); ++i)
    if (spare_[i].first == size) {
      const unsigned texture = spare_[i].second;
      spare_.erase(spare_.begin() + long(i));
      gl_.BindTexture(GL_TEXTURE_3D, texture);
      return texture;
    }
  return newVolumeTexture(gl_, size);
}

void VolumeTexturePool::give(unsigned texture, const glm::ivec3& size) {
  if (texture) spare_.emplace_back(size, texture);
}

void VolumeTexturePool::dropSpares() {
  for (auto& [size, texture] : spare_) gl_.DeleteTextures(1, &texture);
  spare_.clear();
}

}  // namespace sortlast
