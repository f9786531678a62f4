#pragma once
// One rank's renderers, behind one call per brick: the volume part (3D-texture slicing or ray
// casting, as the scene chooses) and the particle part (metaball ray caster, either method) of a brick become one premultiplied brick image. In a brick
// holding both, the particle surface is drawn first and ends the volume's rays, so the image is
// correctly ordered inside the brick; between bricks the compositor's visibility order does it.
// Subdivision surfaces (render/surfaces/subdiv_renderer.h) are a third part: each brick draws the
// fragments whose exact limit points it holds, merged by depth with the particle surface into one
// opaque layer (mergeSurfaceLayers) that ends the volume's rays.
#include <memory>
#include <optional>
#include <vector>

#include "adaptive/adaptive_brick.h"
#include "common/brick.h"
#include "io/particles.h"
#include "scene/surface_scene.h"
#include "transfer/transfer_function.h"
#include "render/gl/gl_context.h"
#include "render/gl/gpu_timer.h"
#include "render/gl/pixel_readback.h"
#include "render/glow/glow_renderer.h"
#include "render/particles/metaball_grid_renderer.h"
#include "render/particles/metaball_renderer.h"
#include "render/particles/metaball_slices_renderer.h"
#include "render/particles/particle_renderer.h"
#include "render/volume/raycast_renderer.h"
#include "render/volume/slicing_renderer.h"
#include "render/volume/volume_renderer.h"
#include "render/surfaces/subdiv_renderer.h"

namespace sortlast {

struct Scene;

// The volume renderer a scene asks for (render.method), with its settings.
struct VolumeMethod {
  bool raycast = false;  // false: 3D-texture slicing
  RaycastSettings raycast_settings;
  SlicingSettings slicing_settings;
  Shading shading;       // either renderer
  int ray_block_cells = 8;  // the ray caster's blocks (the slicing renderer takes block_cells)
};
VolumeMethod volumeMethod(const Scene& scene);

struct BrickFrame {
  Rect rect;
  ImageRGBA8 pixels;
  // With glow (enableGlow): the brick image unrounded instead, light without opacity included
  // (rect.w x rect.h premultiplied RGBA floats); `pixels` is then empty.
  std::vector<float> pixels_f;
  std::vector<float> surface;  // (t, nx, ny, nz) per pixel of rect, when asked for and there are particles or surfaces
  int particle_rounds = 0;
  // A volume brick's image still in its target after render() (`pixels` empty): readBack() reads
  // it. Then, overlapped (setOverlappedReadback), its RGBA8 pixels are on their way (`pending`;
  // the caller maps them, pending.ring->map, and releases them); serial, they are in `pixels`.
  FloatTarget* unread = nullptr;
  PendingPixels pending;
};

class BrickRenderer {
 public:
  BrickRenderer(const std::string& backend, int width, int height, const DeviceRequest& device = {});
  std::string description() const { return ctx_->description(); }
  const GlDeviceInfo& deviceInfo() const { return ctx_->info(); }

  void enableVolume(const TransferFunction& tf, int table_size, int block_cells,
                    const VolumeMethod& method = {}, bool preintegrated = false);
  void enableParticles(const MetaballSettings& settings);
  // The scene's subdivision surfaces, drawn in every brick added after this call (each brick
  // clips them to its box). Kept by reset(): a session's surfaces do not change (`surfaces` is
  // not a frame key), so a second call with the same list does nothing.
  void enableSurfaces(const std::vector<SurfaceSpec>& surfaces);
  // Glow emitters (docs/glow.md): every brick's image comes back in float (BrickFrame::pixels_f),
  // and bricks given a glow box (setBrickGlow) integrate the emitters inside it, up to their
  // particle surface; in volume bricks the ray caster integrates it per step.
  void enableGlow();
  void setGlowEmitters(const std::vector<GlowEmitter>& emitters, double eps, double intensity);
  void setBrickGlow(int handle, const Box3& box, const Box3& whole);  // its part of the glow box

  // A brick: its volume samples (stored box; null: no volume) and its particles with ghosts
  // (null: no particles), clipped to `particle_clip`. With `adaptive` (ray casting only) the
  // volume is drawn from the brick's adaptive blocks instead, and `samples` is not read (may be
  // null). Returns a handle for render().
  int addBrick(const Brick* volume_brick, const GridGeometry* grid, const std::vector<float>* samples,
               const Box3& particle_clip, const std::vector<glm::vec3>* particles,
               const AdaptiveBrickBlocks* adaptive = nullptr);

  // Several fields (render/volume/field_bricks.h; the ray caster, after enableVolume): their
  // transfer functions for the next frames, and a brick of the layout's grid with their parts.
  void setFieldTransfers(const std::vector<TransferFunction>& tfs, const std::vector<int>& table_sizes);
  int addFieldsBrick(const Brick& brick, const GridGeometry& grid, const std::vector<FieldBrickPart>& parts,
                     const Box3& clip);

  // What a resident session changes between frames without re-uploading any brick.
  void setImageSize(int width, int height);
  void setTransferFunction(const TransferFunction& tf, int table_size, bool preintegrated = false);
  void setVolumeMethodSettings(const VolumeMethod& method);
  // The clip region for the next frames (common/clip.h): volumes only.
  void setClip(const ClipRegion& clip) {
    if (volume_) volume_->setClip(clip);
  }  // same renderer kind; its settings, shading
  void setMetaballSettings(const MetaballSettings& settings);  // same h
  // Ray casting, once every rank's bricks are added: the block value ranges adaptive steps need,
  // this rank's part of them (blockRangesPart: per block of the grid, min and max over this
  // rank's bricks), which the session reduces over ranks (min of mins, max of maxes) and hands
  // back (setBlockRanges). Slicing needs none: nullopt.
  using BlockRanges = std::pair<std::vector<float>, std::vector<float>>;
  std::optional<BlockRanges> blockRangesPart(const GridGeometry& grid) const;
  void setBlockRanges(BlockRanges ranges);
  // Drops the renderers and every brick (their GL objects), keeping the GL context: the session
  // then enables and adds bricks anew (a new time step, another volume renderer, another h).
  // The ray caster's brick textures are kept for the next bricks (VolumeTexturePool).
  void reset();  // (the surfaces stay)
  // Deletes the brick textures the last reset() kept that the bricks added since did not reuse
  // (call after a step's bricks are added).
  void dropSpareTextures();

  // The same with the volume's samples from any source (in situ: the simulation's arrays).
  int addBrick(const Brick& volume_brick, const GridGeometry& grid, const BrickSamples& samples,
               const Box3& particle_clip, const std::vector<glm::vec3>* particles);
  // A brick with particles only.
  int addParticleBrick(const Box3& particle_clip, const std::vector<glm::vec3>& particles);

  // Draws a brick; its GL work is timed (drawSeconds). A volume brick's image is left in its
  // target (BrickFrame::unread) for readBack().
  BrickFrame render(int handle, const Camera& cam, double slice_spacing, double near_plane,
                    double far_plane, bool want_surface);
  // Starts (overlapped) or does (serial) the read-back of a brick render() left unread: converted
  // to RGBA8 on the GPU into the pixel-buffer ring, returning at once (BrickFrame::pending), or
  // read as floats now and converted on the CPU (BrickFrame::pixels). Nothing to do otherwise.
  void readBack(BrickFrame& frame);
  // Which of the two readBack() does (true: overlapped; false: the serial pipeline, for comparison).
  void setOverlappedReadback(bool on) { overlapped_readback_ = on; }
  // The GL time of the bricks drawn since the last call (GpuTimer: timer queries), in seconds.
  double drawSeconds() { return timer_->collect(); }

 private:
  struct Handles {
    int volume = -1, particles = -1;
    bool surfaces = false;  // the subdivision surfaces' bounds meet the brick's box
    Box3 clip;              // the brick's box
    bool glow = false;
    Box3 glow_box, glow_whole;
  };
  int addHandles(Handles h, const Box3& clip);
  // This brick's subdivision surfaces, merged by depth with the particle layer `particles` (empty
  // rect: none), into the subdivision renderer's targets; returns the merged layer (empty rect:
  // neither shows in this brick).
  SurfaceLayer mergeSurfaceLayers(const Handles& h, const Camera& cam, double near_plane, double far_plane,
                                  const Rect& particles);
  std::unique_ptr<GlContext> ctx_;
  // The ray caster's brick textures between time steps (before volume_: it outlives the renderers).
  std::unique_ptr<VolumeTexturePool> textures_;
  int width_, height_;
  // The volume renderer (slicing or ray casting); null until enableVolume().
  std::unique_ptr<VolumeRenderer> volume_;
  std::unique_ptr<ParticleRenderer> metaballs_;  // particles.method: billboards or grid
  std::unique_ptr<SubdivRenderer> subdiv_;       // the scene's surfaces; null: none
  size_t surface_count_ = 0;
  Box3 surface_bounds_;
  std::unique_ptr<GlowRenderer> glow_;
  std::vector<Handles> bricks_;
  std::unique_ptr<GpuTimer> timer_;
  bool overlapped_readback_ = false;
};

// The metaball renderer's settings for a scene's particle keys.
MetaballSettings metaballSettings(const ParticleDesc& desc);

}  // namespace sortlast
