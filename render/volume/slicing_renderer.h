#pragma once
// 3D-texture slicing of bricks (the paper's renderer), in OpenGL 4.5 core. Each brick is a 3D
// texture of its stored samples (ghosts included); it is drawn as view-aligned slice polygons
// blended back to front with premultiplied alpha into a float framebuffer, and read back as RGBA8
// over the screen rectangle its projection covers.
//
// Empty-space skipping: each brick is cut into blocks of up to `block_cells` cells per axis; a
// block whose samples all map to zero opacity is not drawn, and the brick's rectangle covers only
// the blocks that are. Visible blocks are drawn in back-to-front block order, each with its part
// of the shared slice planes; "over" is associative, so this equals slicing the whole brick (up to
// float rounding) while rasterising no fragment in empty blocks.
//
// Projections (SlicingSettings::blend: mip, minip, average, additive; docs/volumes.md): the
// same slices, blended by an order-free equation instead of "over" (GL_MAX for mip and minip,
// GL_FUNC_ADD for average and additive), into the ray caster's partial-image format
// (compositing/projection_pixels.h), read back in float (RenderedBrick::pixels_f). The result is
// over the slice planes' samples of each ray, not the ray caster's lattice of distances: both
// converge to the reference's as the step shrinks (render/volume/slicing.frag.glsl says how).
#include <vector>

#include "common/brick.h"
#include "common/camera.h"
#include "io/image.h"
#include "scene/sections.h"
#include "transfer/shading.h"
#include "transfer/transfer_function.h"
#include "render/gl/brick_output.h"
#include "render/gl/float_target.h"
#include "render/gl/program_cache.h"
#include "render/gl/gl_context.h"
#include "render/volume/transfer_table.h"
#include "render/volume/volume_brick.h"
#include "render/volume/volume_renderer.h"

namespace sortlast {

struct SlicingSettings {
  // render.blend: a projection (mip, minip, average, additive) or emission-absorption
  // (composite); isosurfaces are the ray caster's only (std::logic_error here).
  VolumeBlend blend = VolumeBlend::kComposite;
  // A projection in a frame with an opaque layer (particles or subdivision surfaces): the pixels
  // take the bounded formats (render/volume/bounded_pixels.h), in every brick, layer or not.
  bool bounded = false;
};

class SlicingRenderer : public VolumeRenderer {
 public:
  SlicingRenderer(const GlContext& ctx, int width, int height, int block_cells = 64,
                  const SlicingSettings& settings = {});
  ~SlicingRenderer() override;
  SlicingRenderer(const SlicingRenderer&) = delete;
  SlicingRenderer& operator=(const SlicingRenderer&) = delete;

  // With `preintegrated`, fragments draw pre-integrated segments (render/volume/slicing.frag.glsl).
  void setTransferFunction(const TransferFunction& tf, int table_size, bool preintegrated = false) override;
  // A new image size for the next frames (the bricks' textures stay).
  void resize(int width, int height) override { target_.resize(width, height); }
  void setDeferredReadback(bool on) override { target_.setDeferred(on); }
  // Gradient shading (transfer/shading.h) for the next frames.
  void setShading(const Shading& shading) override { shading_ = shading; }
  // The blend mode for the next frames.
  void setSettings(const SlicingSettings& settings) { settings_ = settings; }
  const SlicingSettings& settings() const { return settings_; }
  SlicingRenderer* slicer() override { return this; }
  // Uploads a brick's stored samples (x fastest); returns a handle for render(). The samples'
  // min and max are kept so invisible bricks can be skipped.
  int addBrick(const Brick& brick, const GridGeometry& grid, const std::vector<float>& samples) override;
  int addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) override;

  // Renders one brick for `cam`; `spacing` is the world distance between slice planes and
  // [near_plane, far_plane] must enclose the whole volume (the same for all bricks of a frame).
  // Slice fragments at or behind `surface` are not drawn. A projection's image comes back in
  // float (`pixels_f`), not with a surface (the scene refuses it) or shading.
  RenderedBrick render(int handle, const Camera& cam, double spacing, double near_plane,
                       double far_plane, const SurfaceLayer* surface = nullptr) override;

 private:
  const GlApi& gl_;
  bool float_filter_;  // volume_shading.h: floatFilter
  int block_cells_;
  FloatTarget target_;
  TransferTable table_;
  Shading shading_;
  SlicingSettings settings_;
  // The program's variants (slicing_renderer.cpp's recipe: kPreintegrated, kShading,
  // kFloatFilter, the projection's bits): the plain
  // one linked with the renderer, the others when first drawn.
  ProgramCache programs_;
  unsigned vao_ = 0, vbo_ = 0;
  std::vector<VolumeBrick> bricks_;
};

}  // namespace sortlast
