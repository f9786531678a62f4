#pragma once
// What render/brick_renderer.cpp needs of a volume renderer, whichever the scene chose
// (render.method): 3D-texture slicing (render/volume/slicing_renderer.h) or ray casting
// (render/volume/raycast_renderer.h). Both take the same bricks, transfer function and shading and
// return the same brick images (render/gl/brick_output.h).
#include <vector>

#include "common/brick.h"
#include "common/camera.h"
#include "common/clip.h"
#include "transfer/shading.h"
#include "transfer/transfer_function.h"
#include "render/gl/brick_output.h"
#include "render/volume/brick_samples.h"

namespace sortlast {

class RaycastRenderer;
class SlicingRenderer;

class VolumeRenderer {
 public:
  virtual ~VolumeRenderer() = default;

  // The transfer function for the next frames, as a table of `table_size` entries; with
  // `preintegrated`, pre-integrated segments.
  virtual void setTransferFunction(const TransferFunction& tf, int table_size,
                                   bool preintegrated = false) = 0;
  // A new image size for the next frames (the bricks' textures stay).
  virtual void resize(int width, int height) = 0;
  // Gradient shading (transfer/shading.h) for the next frames.
  virtual void setShading(const Shading& shading) = 0;
  // The clip region (common/clip.h) for the next frames: rays (slices) show only the volume inside
  // it, and bricks wholly outside it are not drawn.
  void setClip(const ClipRegion& clip) { clip_ = clip; }
  // Uploads a brick's stored samples (x fastest); returns a handle for render().
  virtual int addBrick(const Brick& brick, const GridGeometry& grid,
                       const std::vector<float>& samples) = 0;
  virtual int addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) = 0;
  // Renders one brick for `cam` with samples (slices) `spacing` world units apart;
  // [near_plane, far_plane] encloses the whole volume, the same for all bricks of a frame. The
  // volume ends at `surface`, whose colour goes behind it.
  virtual RenderedBrick render(int handle, const Camera& cam, double spacing, double near_plane,
                               double far_plane, const SurfaceLayer* surface = nullptr) = 0;

  // Deferred read-back (FloatTarget::setDeferred): render() leaves an RGBA8 brick image in its
  // target (RenderedBrick::unread) for the caller to read asynchronously.
  virtual void setDeferredReadback(bool on) = 0;

  // The ray caster behind this interface, or null (slicing). What only ray casting has (its
  // settings, the block ranges adaptive steps need, adaptive bricks, glow) is reached through it
  // rather than as virtuals with do-nothing defaults: slicing must not silently drop an adaptive
  // brick or a glow pass, and the brick renderer refuses those (std::logic_error) where it finds
  // no ray caster.
  virtual RaycastRenderer* raycaster() { return nullptr; }
  // The slicing renderer behind this interface, or null (ray casting): its own settings
  // (SlicingRenderer::setSettings) are reached through it.
  virtual SlicingRenderer* slicer() { return nullptr; }

 protected:
  ClipRegion clip_;
};

}  // namespace sortlast
