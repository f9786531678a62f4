#pragma once
// What the three metaball renderers share (billboards, render/particles/metaball_renderer.h; grid,
// render/particles/metaball_grid_renderer.h; slices, render/particles/metaball_slices_renderer.h):
// the GL API, the settings, the surface target all three draw into and read back from, an empty
// vertex array for full-screen passes, the storage-buffer limit and the upload of a storage
// buffer, the uniforms every method's rays take, and the one-pass draw of grid and slices.
#include <functional>
#include <string>
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/particles/particle_renderer.h"
#include "render/particles/surface_target.h"

namespace sortlast {

// The uniforms every method's programs share (render/particles/metaball_common.glsl and the
// passes'): the rays of `cam` over a width x height image, h, T, the step w, the sample cap, the
// refinement passes, the colour and the brick's clip box. A program that lacks one ignores it
// (location -1).
void setRayUniforms(const GlApi& gl, const GlProgram& program, const Camera& cam, int width,
                    int height, const MetaballSettings& s, const Box3& clip);

class MetaballBase : public ParticleRenderer {
 public:
  ~MetaballBase() override;
  MetaballBase(const MetaballBase&) = delete;
  MetaballBase& operator=(const MetaballBase&) = delete;

  // A new image size for the next frames: the surface target's textures are reallocated, the
  // bricks' buffers stay.
  void resize(int width, int height) override;
  // After render(): a texture of (t, nx, ny, nz) per pixel over the last brick's rectangle
  // (t = 1e30 where it missed), for a volume renderer to end its rays at the surface.
  unsigned surfaceTexture() const override { return target_.surface(); }
  // After render(): the shaded colour (RGBA32F, premultiplied, alpha 1 on the surface).
  unsigned colourTexture() const override { return target_.colour(); }

 protected:
  // What every method keeps of a brick, whatever else it holds: the clip box its rays are cut
  // to, and the box inside it that can show (its screen rectangle is the brick image's).
  struct BrickBox {
    Box3 clip;
    Box3 bound;
  };

  // `name` ("metaball", "metaball grid", ...) names the renderer in the errors GL checks throw.
  MetaballBase(const GlContext& ctx, int width, int height, const MetaballSettings& settings,
               std::string name);

  // A shader storage buffer holding `bytes` of `data` (null: uninitialised), owned by the caller.
  // An empty list still needs a buffer to bind: 4 bytes.
  unsigned uploadStorage(const void* data, size_t bytes) const;
  // The same, owned by this renderer: deleted with it.
  unsigned keepStorage(const void* data, size_t bytes);

  // One fragment pass over the screen rectangle of `box.bound` (grid and slices): `program` in
  // use with the ray uniforms for `box.clip`, `bind` setting the method's own uniforms and
  // buffers, then one full-screen triangle into the surface target and its read-back. rounds = 1.
  SurfaceBrick drawOnePass(const GlProgram& program, const BrickBox& box, const Camera& cam,
                           bool want_surface, const std::function<void()>& bind);

  const GlApi& gl_;
  MetaballSettings s_;
  const std::string name_;
  long long max_block_bytes_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  SurfaceTarget target_;           // the shaded colour and the surface (t, normal)
  unsigned empty_vao_ = 0;         // full-screen passes draw without attributes

 private:
  std::vector<unsigned> kept_;  // keepStorage's buffers
};

}  // namespace sortlast
