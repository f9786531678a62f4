#pragma once
// GPU ray casting of bricks, in OpenGL 4.5 core: the alternative to 3D-texture slicing
// (render/volume/slicing_renderer.h) with the same inputs and outputs. Each pixel's ray is clipped
// to the brick's box and sampled front to back on a lattice shared by all bricks
// (render/volume/raycast_march.frag.glsl has the rules that keep brick faces seam-free), with the
// slicing renderer's trilinear texture, transfer-function table and opacity correction, so both
// converge to the same reference.
//
// What ray casting adds: early ray termination (a ray stops once its opacity reaches
// `ert_threshold`; it can only act inside a brick, as later bricks are drawn apart), empty-space
// skipping along the ray over fine blocks (render/volume/ray_blocks.h: blocks whose values all map to
// zero opacity under the current transfer function are jumped, many at once by their distance to
// the nearest non-empty block, reclassified whenever the function changes), and the brick's
// rectangle covers only the non-empty blocks; and adaptive steps (RaycastSettings::adaptive_step:
// a block takes every m-th lattice sample, m from its value range and the transfer function,
// render/volume/step_rule.h). m must not depend on the decomposition, so it is chosen from the whole
// block's range, which the ranks reduce: globalRangesPart() on every rank, the min and max over
// ranks to setGlobalRanges(); until then every block takes m = 1.
//
// Adaptive sampling: a brick added with addAdaptiveBrick() is drawn from its adaptive blocks
// (adaptive/adaptive_brick.h) with a variant of the program: the blocks are the adaptive ones, each
// read at its own resolution and sampled at it (render/volume/raycast_march.frag.glsl has the rule;
// or at every lattice step: RaycastSettings::own_resolution_steps); the renderer's block_cells does
// not apply to such a brick.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adaptive/adaptive_brick.h"
#include "common/brick.h"
#include "common/camera.h"
#include "scene/sections.h"
#include "transfer/isosurface.h"
#include "transfer/shading.h"
#include "transfer/transfer_function.h"
#include "render/gl/brick_output.h"
#include "render/gl/float_target.h"
#include "render/gl/gl_context.h"
#include "render/gl/program_cache.h"
#include "render/volume/field_bricks.h"
#include "render/volume/ray_blocks.h"
#include "render/volume/step_rule.h"
#include "render/volume/transfer_table.h"
#include "render/volume/volume_brick.h"
#include "render/volume/volume_renderer.h"

namespace sortlast {

struct RaycastSettings {
  double ert_threshold = 0.999;  // stop a ray at this opacity, in (0, 1]; 1: never stop early
  // Adaptive bricks: a block at level L takes every 2^L-th lattice sample (true), or every one.
  bool own_resolution_steps = true;
  // Plain bricks: a block takes every m-th lattice sample (render/volume/step_rule.h), m <= 8, the
  // largest with m delta osc <= adaptive_tolerance.
  bool adaptive_step = false;
  double adaptive_tolerance = 0.02;
  // render.blend: a projection (mip, minip, average, additive) or emission-absorption (composite);
  // a projection's image comes back in float (RenderedBrick::pixels_f, its pixels
  // compositing/projection_pixels.h's), every lattice sample taken, none stopping early.
  VolumeBlend blend = VolumeBlend::kComposite;
  bool mip_exact = false;  // mip / minip: the exact extremum along each ray (render.mip_exact)
  // A projection in a frame with an opaque layer (particles or subdivision surfaces): the pixels
  // take the bounded formats (compositing/projection_pixels.h), in every brick, layer or not.
  bool bounded = false;
  // render.blend: isosurface: these isovalues' crossings instead of the emission-absorption
  // integral (render/volume/raycast_isosurface.frag.glsl); empty: the integral. With iso_debug
  // (tests), each pixel gets the first hit's (t, unit gradient) in float instead (t = 0: none).
  std::vector<Isovalue> isovalues;
  bool iso_debug = false;
};

class RaycastRenderer : public VolumeRenderer {
 public:
  // block_cells: cells per axis of the skipping (and step) blocks, aligned to the volume.
  // pool (optional, outliving this renderer): where the bricks' textures come from and go back to.
  RaycastRenderer(const GlContext& ctx, int width, int height, int block_cells,
                  const RaycastSettings& settings, VolumeTexturePool* pool = nullptr);
  ~RaycastRenderer() override;
  RaycastRenderer(const RaycastRenderer&) = delete;
  RaycastRenderer& operator=(const RaycastRenderer&) = delete;

  // With `preintegrated`, rays composite pre-integrated segments
  // (render/volume/raycast_march.frag.glsl).
  void setTransferFunction(const TransferFunction& tf, int table_size, bool preintegrated = false) override;
  // A new image size for the next frames (the bricks' textures stay).
  void resize(int width, int height) override { target_.resize(width, height); }
  void setDeferredReadback(bool on) override { target_.setDeferred(on); }
  // Early ray termination and adaptive stepping can change between frames.
  void setSettings(const RaycastSettings& settings) { settings_ = settings; }
  bool projecting() const { return settings_.blend != VolumeBlend::kComposite; }
  const RaycastSettings& settings() const { return settings_; }
  bool isosurfaces() const { return !settings_.isovalues.empty(); }
  // Gradient shading (transfer/shading.h) for the next frames; not for adaptive bricks.
  void setShading(const Shading& shading) override { shading_ = shading; }
  // Uploads a brick's stored samples (x fastest); returns a handle for render().
  int addBrick(const Brick& brick, const GridGeometry& grid, const std::vector<float>& samples) override;
  int addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) override;
  // Uploads the adaptive blocks a brick draws; returns a handle for render().
  int addAdaptiveBrick(const Brick& brick, const GridGeometry& grid,
                       const AdaptiveBrickBlocks& blocks);

  // Several fields (render/volume/field_bricks.h; render/volume/raycast_fields.cpp): their
  // transfer functions for the next frames (one table each, in the scene's order), and a brick of
  // the layout's grid `grid` holding their parts, drawn with the FIELDS variant of the program
  // (raycast_fields.frag.glsl: the mixture per sample). Not with pre-integration, shading,
  // adaptive steps or glow (the scene refuses them).
  void setFieldTransfers(const std::vector<TransferFunction>& tfs, const std::vector<int>& table_sizes);
  int addFieldsBrick(const Brick& brick, const GridGeometry& grid, const std::vector<FieldBrickPart>& parts);

  // This rank's part of the block ranges adaptive steps need, over the volume's block grid (x
  // fastest; +/-FLT_MAX where it holds no sample): the min of `first` and the max of `second`
  // over all ranks go to setGlobalRanges().
  std::pair<std::vector<float>, std::vector<float>> globalRangesPart(const GridGeometry& grid) const;
  void setGlobalRanges(std::vector<float> vmin, std::vector<float> vmax);

  // Renders one brick for `cam` with samples `spacing` world units apart along every ray. The
  // depth range is not needed (rays are not rasterised); it is taken so both volume renderers
  // have one call. Rays end at `surface`, whose colour goes behind what they gathered.
  // With `glow`, the rays also integrate the emitters inside glow->box (the GLOW variant of the
  // program, render/volume/raycast_glow.frag.glsl), the rectangle covers that box, and the image
  // comes back in float.
  RenderedBrick render(int handle, const Camera& cam, double spacing, double near_plane,
                       double far_plane, const SurfaceLayer* surface, const GlowPass* glow);
  // The same without glow (the volume renderers' common call).
  RenderedBrick render(int handle, const Camera& cam, double spacing, double near_plane,
                       double far_plane, const SurfaceLayer* surface = nullptr) override {
    return render(handle, cam, spacing, near_plane, far_plane, surface, nullptr);
  }
  RaycastRenderer* raycaster() override { return this; }
  // Isosurfaces (settings' isovalues), for --surface-out: the brick's rays drawn again (the same
  // rectangle, surface and crossings as render()'s) with the ISO_DEPTH variant, whose pixels
  // (pixels_f) are (t, outward unit normal) of the opaque isovalue hit that ends the ray in this
  // brick, t = 1e30 where none does. A second draw: only when a surface image is asked for. Call
  // it before render(), whose image a deferred read-back leaves in the same target.
  RenderedBrick renderIsoDepth(int handle, const Camera& cam, double spacing, const SurfaceLayer* surface);

 private:
  // The adaptive lookup's per-brick inputs (render/volume/adaptive_gpu_brick.h).
  struct AdaptiveInputs {
    unsigned table = 0;
    glm::vec3 index_scale, index_offset, block_cells, atlas_inv;
  };
  // What a brick's skip texture was classified for: it is redone when any of these changes.
  struct ClassKey {
    int table_version = -1, ranges_version = -1;
    float delta = 0.0f;
    bool adaptive_step = false;
    double tolerance = 0.0;
    int blend = 0;
    std::vector<double> isovalues;
    bool operator==(const ClassKey&) const = default;
  };
  VolumeTexturePool* pool_ = nullptr;
  // One field's part of a brick: its texture and transform, and its range per block of the brick.
  struct FieldGpu {
    int field = 0;
    VolumeBrick volume;
    Box3 box;  // the field's world box
    std::vector<float> vmin, vmax;
  };
  struct GpuBrick {
    VolumeBrick volume;  // several fields: no texture (0), the brick alone
    std::vector<FieldGpu> fields;
    BrickBlocks blocks;
    unsigned planes = 0;  // block planes: R32F, (largest block count + 1) x 3
    unsigned skip = 0;    // per block: RG8UI (distance to the nearest non-empty block, log2 m)
    unsigned range = 0;   // per block: RG32F (vmin, vmax), what mip / minip jump blocks by
    ClassKey classified;  // what `skip`, `any` and `bound` hold now
    bool any = false;     // some block is not empty
    Box3 bound;           // the box around the non-empty blocks
    bool adaptive = false;
    AdaptiveInputs lookup;  // adaptive bricks only
  };

  // The block planes and skip textures of a brick whose volume and blocks are set.
  int addGpuBrick(GpuBrick g);
  // Classifies the brick's blocks for the current table, spacing and settings, if not done yet.
  void classify(GpuBrick& g, float delta);
  // Several fields (raycast_fields.cpp): whether block i is non-empty under some field's table,
  // and the FIELDS program's textures and uniforms for brick g.
  bool fieldsVisible(const GpuBrick& g, size_t i) const;
  void useFields(const GlProgram& program, const GpuBrick& g) const;

  const GlApi& gl_;
  bool float_filter_;  // volume_shading.h: floatFilter
  int block_cells_;
  RaycastSettings settings_;
  Shading shading_;
  double min_spacing_ = 0.0;  // of the volume's grid (the step rule's cap)
  Box3 volume_box_;           // the volume's world box (where rays enter and leave it)
  glm::ivec3 global_count_{0};  // the volume's block grid
  std::vector<float> global_min_, global_max_;  // whole blocks, grown by one sample; empty: not yet
  int ranges_version_ = 0;
  std::unique_ptr<StepRule> rule_;  // for rule_key_'s table, spacing and tolerance
  ClassKey rule_key_;
  FloatTarget target_;
  bool iso_depth_pass_ = false;  // renderIsoDepth() is drawing: the ISO_DEPTH variant
  TransferTable table_;
  std::vector<std::unique_ptr<TransferTable>> field_tables_;  // several fields: one each
  int field_tables_version_ = 0;  // the sum of their versions: changes when any changes
  // The program's variants (raycast_renderer.cpp's recipe: kAdaptive, kPreintegrated, kShading,
  // kGlow): the plain one linked with the renderer, the adaptive one with the first adaptive brick,
  // the others when first drawn.
  ProgramCache programs_;
  unsigned vao_ = 0;
  std::vector<GpuBrick> bricks_;
};

}  // namespace sortlast
