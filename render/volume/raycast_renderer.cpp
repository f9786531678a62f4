#include "render/volume/raycast_renderer.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/glow/glow_gl.h"
#include "render/glow/glsl_files.h"
#include "render/volume/adaptive_gpu_brick.h"
#include "render/volume/isosurface_uniforms.h"
#include "render/volume/glsl_files.h"
#include "render/volume/volume_clip.h"
#include "render/volume/volume_shading.h"

namespace sortlast {

namespace {
// The program's variants: which flags a brick's draw needs (combinations the scene refuses are
// refused again in render()).
enum RaycastVariant : unsigned {
  kAdaptive = 1,       // ADAPTIVE: the brick's adaptive blocks (addAdaptiveBrick)
  kPreintegrated = 2,  // PREINTEGRATED: transfer.preintegrated
  kShading = 4,        // SHADING: render.shading
  kGlow = 8,           // GLOW: glow emitters inside the volume
  kFloatFilter = 16,    // FLOAT_FILTER: the volume filtered in float (volume_shading.h floatFilter)
  // PROJECTION = 1 mip, 2 minip, 3 average, 4 additive (bits 5-7; raycast_projection.frag.glsl)
  kProjectionShift = 5,
  kProjectionMask = 7u << kProjectionShift,
  kMipExact = 256,     // MIP_EXACT: render.mip_exact
  kIsosurface = 512,   // ISOSURFACE (and ISO_DEBUG: kIsoDebug): render.blend: isosurface
  kIsoDebug = 1024,
  kIsoDepth = 2048,    // ISO_DEPTH: the opaque hit's t and normal (renderIsoDepth)
  kFieldsShift = 13,   // FIELDS n: several fields (flags >> kFieldsShift = n; raycast_fields.cpp)
};

// The variant bits of a projection (0: emission-absorption).
unsigned projectionBits(VolumeBlend b, bool exact) {
  const unsigned p = b == VolumeBlend::kMip       ? 1u
                     : b == VolumeBlend::kMinip   ? 2u
                     : b == VolumeBlend::kAverage ? 3u
                     : b == VolumeBlend::kAdditive ? 4u
                                                   : 0u;
  return (p << kProjectionShift) | (p != 0 && p <= 2 && exact ? unsigned(kMipExact) : 0u);
}

// Exact MIP's ray in double (raycast_projection.frag.glsl projectExact): the camera's vectors as
// setPixelRayUniforms gives them, unrounded.
void setDoublePixelRayUniforms(const GlProgram& program, const Camera& cam) {
  const glm::dvec2 s = cam.screenScale();
  program.set("u_eye_d", cam.position);
  program.set("u_forward_d", cam.forward());
  program.set("u_right_d", cam.right() * s.x);
  program.set("u_up_d", cam.trueUp() * s.y);
  program.set("u_pixel_scale_d", glm::dvec2(2.0 / cam.width, 2.0 / cam.height));
}

// The fragment shader of a variant: render/volume/raycast_march.frag.glsl describes the chunks.
ProgramSources raycastSources(unsigned v) {
  const bool glow = v & kGlow, shading = v & kShading, preint = v & kPreintegrated;
  const unsigned projection = (v & kProjectionMask) >> kProjectionShift;
  const unsigned fields = v >> kFieldsShift;
  ShaderSource fragment;
  if (projection) fragment.define("PROJECTION", std::to_string(projection));
  if (fields > 0) fragment.define("FIELDS", std::to_string(fields));
  fragment.defineIf(v & kAdaptive, "ADAPTIVE")
      .defineIf(preint, "PREINTEGRATED")
      .defineIf(shading, "SHADING")
      .defineIf(v & kFloatFilter, "FLOAT_FILTER")
      .defineIf(glow, "GLOW")
      .defineIf(v & kMipExact, "MIP_EXACT")
      .defineIf(v & kIsosurface, "ISOSURFACE")
      .defineIf(v & kIsoDebug, "ISO_DEBUG")
      .defineIf(v & kIsoDepth, "ISO_DEPTH")
      .addIf(glow, glsl::glow_segment)
      .addIf(glow, glsl::glow_emitters)
      .add(glsl::volume_filter)
      .add(glsl::value_scale)
      .addIf(shading, glsl::volume_shading)
      .add(glsl::raycast_sample_frag)
      .add(glsl::volume_clip)
      .addIf(fields > 0, glsl::raycast_fields_frag)
      .addIf(preint, glsl::preintegrated_segment)
      .addIf(glow, glsl::raycast_glow_frag)
      .addIf(projection != 0, glsl::raycast_projection_frag)
      .addIf(v & kIsosurface, glsl::raycast_isosurface_frag)
      .add(glsl::raycast_march_frag);
  return {ShaderSource().add(glsl::fullscreen_vert), fragment};
}
}  // namespace

RaycastRenderer::RaycastRenderer(const GlContext& ctx, int width, int height, int block_cells,
                                 const RaycastSettings& settings, VolumeTexturePool* pool)
    : pool_(pool),
      gl_(ctx.gl()),
      float_filter_(floatFilter(ctx.info())),
      block_cells_(std::max(1, block_cells)),
      settings_(settings),
      target_(gl_, width, height),
      table_(gl_),
      programs_(gl_, raycastSources) {
  programs_.get(float_filter_ ? kFloatFilter : 0);  // the plain program now: a driver that cannot build it fails here
  // A core-profile draw needs a vertex array, though the triangle has no attributes.
  gl_.GenVertexArrays(1, &vao_);
  gl_.check("ray caster setup");
}

RaycastRenderer::~RaycastRenderer() {
  for (auto& b : bricks_) {
    for (auto& f : b.fields) {  // (a brick of several fields has no texture of its own: 0)
      if (pool_) pool_->give(f.volume.texture, f.volume.brick.stored.size());
      else gl_.DeleteTextures(1, &f.volume.texture);
    }
    if (!b.fields.empty())
      ;
    else if (pool_ && !b.adaptive)
      pool_->give(b.volume.texture, b.volume.brick.stored.size());
    else
      gl_.DeleteTextures(1, &b.volume.texture);
    gl_.DeleteTextures(1, &b.planes);
    gl_.DeleteTextures(1, &b.skip);
    gl_.DeleteTextures(1, &b.range);
    if (b.adaptive) gl_.DeleteTextures(1, &b.lookup.table);
  }
  gl_.DeleteVertexArrays(1, &vao_);
}

void RaycastRenderer::setTransferFunction(const TransferFunction& tf, int table_size,
                                          bool preintegrated) {
  table_.set(tf, table_size, preintegrated);
}

namespace {
// Integer and single-row textures are read with texelFetch only: no filtering, no mipmaps (a
// texture without them must not ask for mipmap filtering, or it is incomplete and reads zero).
void nearest(const GlApi& gl, GLenum target) {
  gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}
}  // namespace

int RaycastRenderer::addBrick(const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples) {
  if (samples.size() != size_t(brick.stored.count()))
    throw std::logic_error("addBrick: sample count does not match the brick");
  return addBrick(brick, grid, FloatBrickSamples(samples, brick.stored));
}

int RaycastRenderer::addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) {
  GpuBrick g;
  // The texture only: the ray caster's blocks are its own (none here).
  g.volume = uploadVolumeBrick(gl_, brick, grid, samples, 0, pool_);
  g.blocks = cutBrickBlocks(brick, grid, samples, rayBlockGrid(grid, block_cells_));
  min_spacing_ = grid.minSpacing();
  volume_box_ = grid.worldBox();
  global_count_ = rayBlockGrid(grid, block_cells_).count;
  return addGpuBrick(std::move(g));
}

int RaycastRenderer::addAdaptiveBrick(const Brick& brick, const GridGeometry& grid,
                                      const AdaptiveBrickBlocks& blocks) {
  programs_.get(kAdaptive);
  AdaptiveGpuBrick a = uploadAdaptiveBrick(gl_, brick, grid, blocks);
  volume_box_ = grid.worldBox();
  GpuBrick g;
  g.volume = std::move(a.volume);
  g.adaptive = true;
  g.lookup = {a.table, a.index_scale, a.index_offset, a.block_cells, a.atlas_inv};
  // The adaptive blocks are the DDA's: their planes and ranges, no global grid (m is their level).
  const VolumeBrick& v = g.volume;
  g.blocks.count = v.block_count;
  g.blocks.global = false;
  g.blocks.planes = v.block_planes;
  for (const VolumeBlock& blk : v.blocks) {
    g.blocks.vmin.push_back(blk.vmin);
    g.blocks.vmax.push_back(blk.vmax);
  }
  return addGpuBrick(std::move(g));
}

int RaycastRenderer::addGpuBrick(GpuBrick g) {
  const glm::ivec3 nb = g.blocks.count;
  const int width = std::max({nb.x, nb.y, nb.z}) + 1;
  // The planes as floats: a face shared with a neighbouring brick is the same double there, so
  // the same float, and both bricks compute the same ray distance for it.
  std::vector<float> planes(size_t(width) * 3, 0.0f);
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= nb[a]; ++i) planes[size_t(a) * width + i] = float(g.blocks.planes[a][size_t(i)]);
  gl_.GenTextures(1, &g.planes);
  gl_.ActiveTexture(GL_TEXTURE3);
  gl_.BindTexture(GL_TEXTURE_2D, g.planes);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, 3, 0, GL_RED, GL_FLOAT, planes.data());
  nearest(gl_, GL_TEXTURE_2D);
  gl_.GenTextures(1, &g.skip);
  gl_.ActiveTexture(GL_TEXTURE4);
  gl_.BindTexture(GL_TEXTURE_3D, g.skip);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_RG8UI, nb.x, nb.y, nb.z, 0, GL_RG_INTEGER, GL_UNSIGNED_BYTE,
                 nullptr);
  nearest(gl_, GL_TEXTURE_3D);
  std::vector<float> range(2 * g.blocks.vmin.size());
  for (size_t i = 0; i < g.blocks.vmin.size(); ++i) range[2 * i] = g.blocks.vmin[i], range[2 * i + 1] = g.blocks.vmax[i];
  gl_.GenTextures(1, &g.range);
  gl_.BindTexture(GL_TEXTURE_3D, g.range);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_RG32F, nb.x, nb.y, nb.z, 0, GL_RG, GL_FLOAT, range.data());
  nearest(gl_, GL_TEXTURE_3D);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.check("ray caster brick upload");
  bricks_.push_back(std::move(g));
  return int(bricks_.size()) - 1;
}

std::pair<std::vector<float>, std::vector<float>> RaycastRenderer::globalRangesPart(
    const GridGeometry& grid) const {
  const RayBlockGrid rg = rayBlockGrid(grid, block_cells_);
  std::pair<std::vector<float>, std::vector<float>> part{std::vector<float>(rg.size(), FLT_MAX),
                                                          std::vector<float>(rg.size(), -FLT_MAX)};
  for (const GpuBrick& g : bricks_)
    if (g.blocks.global) mergeGrownRanges(g.blocks, rg, part.first, part.second);
  return part;
}

void RaycastRenderer::setGlobalRanges(std::vector<float> vmin, std::vector<float> vmax) {
  global_min_ = std::move(vmin);
  global_max_ = std::move(vmax);
  ++ranges_version_;
}

void RaycastRenderer::classify(GpuBrick& g, float delta) {
  std::vector<double> iso;
  for (const Isovalue& v : settings_.isovalues) iso.push_back(v.value);
  const ClassKey key{table_.version() + field_tables_version_, ranges_version_, delta, settings_.adaptive_step,
                     settings_.adaptive_tolerance, int(settings_.blend) * 2 + (settings_.mip_exact ? 1 : 0), iso};
  if (key == g.classified) return;
  const bool projection_counts_all = settings_.blend == VolumeBlend::kMip ||
                                     settings_.blend == VolumeBlend::kMinip ||
                                     settings_.blend == VolumeBlend::kAverage;
  const BrickBlocks& b = g.blocks;
  const size_t n = b.vmin.size();
  std::vector<unsigned char> visible(n);
  g.any = false;
  g.bound = {glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (int z = 0; z < b.count.z; ++z)
    for (int y = 0; y < b.count.y; ++y)
      for (int x = 0; x < b.count.x; ++x) {
        const size_t i = b.index({x, y, z});
        // Pre-integrated segments reach up to delta/2 <= one voxel beyond the block
        // (render/volume/raycast_march.frag.glsl): the whole block's range grown by one sample
        // holds their ends.
        // mip, minip and average count every sample whatever its opacity: no block is empty
        // for them (a block holds samples where vmin <= vmax). Additive adds c a, exactly zero
        // where the table's opacity is: its empty blocks are skipped as emission-absorption's.
        // Isosurfaces: a block (grown by one sample) whose range holds no isovalue. Several
        // fields: empty under every field's transfer function.
        const bool counts_all = projection_counts_all;
        visible[i] = (!g.fields.empty() ? fieldsVisible(g, i)
                      : counts_all ? b.vmin[i] <= b.vmax[i]
                      : !iso.empty() && b.global ? isoVisible(settings_.isovalues, b.grown_min[i], b.grown_max[i])
                      : table_.preintegrated() && b.global ? table_.visible(b.grown_min[i], b.grown_max[i])
                                                           : table_.visible(b.vmin[i], b.vmax[i]))
                         ? 1 : 0;
        if (!visible[i]) continue;
        g.any = true;
        const glm::ivec3 c(x, y, z);
        for (int a = 0; a < 3; ++a) {
          g.bound.lo[a] = std::min(g.bound.lo[a], b.planes[a][size_t(c[a])]);
          g.bound.hi[a] = std::max(g.bound.hi[a], b.planes[a][size_t(c[a]) + 1]);
        }
      }
  // Adaptive steps need the whole blocks' ranges (the same m in every brick sharing a block).
  const StepRule* rule = nullptr;
  if (settings_.adaptive_step && b.global && !global_min_.empty() && !projecting() && g.fields.empty()) {
    ClassKey rk{table_.version(), 0, delta, true, settings_.adaptive_tolerance, 0, {}};
    if (!rule_ || !(rk == rule_key_)) {
      rule_ = std::make_unique<StepRule>(table_.entries(), table_.rangeLo(), table_.rangeHi(), delta,
                                         settings_.adaptive_tolerance,
                                         StepRule::maxMultiple(delta, min_spacing_),
                                         table_.function().scale());
      rule_key_ = rk;
    }
    rule = rule_.get();
  }
  auto globalIndex = [&](const glm::ivec3& c) {
    return size_t(c.x) + size_t(global_count_.x) * (size_t(c.y) + size_t(global_count_.y) * c.z);
  };
  // Class: 0 empty, else 1 + log2 m.
  std::vector<unsigned char> cls(n);
  for (int z = 0; z < b.count.z; ++z)
    for (int y = 0; y < b.count.y; ++y)
      for (int x = 0; x < b.count.x; ++x) {
        const size_t i = b.index({x, y, z});
        if (!visible[i]) continue;
        const size_t gi = rule ? globalIndex(b.first + glm::ivec3(x, y, z)) : 0;
        cls[i] = (unsigned char)(1 + (rule ? rule->level(global_min_[gi], global_max_[gi]) : 0));
      }
  const std::vector<unsigned char> reach = classReach(b.count, cls);
  std::vector<unsigned char> texels(2 * n);
  for (size_t i = 0; i < n; ++i) {
    // The ADAPTIVE variant reads each block's own samples: its rays sample one block at a time.
    // mip / minip (sampled) ask per block whether it can change the ray's result: one at a time.
    const bool per_block = (settings_.blend == VolumeBlend::kMip || settings_.blend == VolumeBlend::kMinip) &&
                           !settings_.mip_exact;
    texels[2 * i] = (!b.global || per_block) && cls[i] ? 1 : reach[i];
    texels[2 * i + 1] = cls[i];
  }
  gl_.ActiveTexture(GL_TEXTURE4);
  gl_.BindTexture(GL_TEXTURE_3D, g.skip);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, b.count.x, b.count.y, b.count.z, GL_RG_INTEGER,
                    GL_UNSIGNED_BYTE, texels.data());
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.check("ray caster block classification");
  g.classified = key;
}

RenderedBrick RaycastRenderer::render(int handle, const Camera& cam, double spacing,
                                      double /*near_plane*/, double /*far_plane*/,
                                      const SurfaceLayer* surface, const GlowPass* glow) {
  GpuBrick& g = bricks_.at(size_t(handle));
  const VolumeBrick& b = g.volume;
  RenderedBrick out;
  const unsigned projection = projectionBits(settings_.blend, settings_.mip_exact);
  // Every projection is bounded by an opaque layer (raycast_projection.frag.glsl); average's and
  // additive's pixels take the bounded format only where the frame has a layer (settings_.bounded).
  if (projection && (glow || g.adaptive || shading_.enabled ||
                     (surface && !surface->rect.empty() && !settings_.bounded &&
                      (settings_.blend == VolumeBlend::kAverage || settings_.blend == VolumeBlend::kAdditive))))
    throw std::logic_error("ray caster: a projection with glow, adaptive blocks or shading, or a surface "
                           "in a frame not drawn in the bounded formats");
  const bool preint = table_.preintegrated() && !projection;  // segments mean nothing to a projection
  if (preint && g.adaptive)  // the scene refuses this (transfer.preintegrated with adaptive.tolerance)
    throw std::logic_error("ray caster: pre-integration of adaptive bricks is not supported");
  const bool iso = !settings_.isovalues.empty();
  if (iso && (g.adaptive || preint || (glow && glow->count > 0)))  // the scene refuses these (scene/isosurface_scene.h)
    throw std::logic_error("ray caster: isosurfaces with adaptive bricks, pre-integration or glow");
  classify(g, float(spacing));
  Rect r = g.any ? clippedRectOf(cam, g.bound, clip_) : Rect{};
  // Glow: the whole of the brick's part of the glow box, empty blocks and all.
  const bool glowing = glow && glow->count > 0 && hasVolume(glow->box);
  if (glowing) {
    if (g.adaptive) throw std::logic_error("ray caster: glow in an adaptive brick");
    const Rect gr = screenRectOf(cam, glow->box);
    if (!gr.empty()) r = r.empty() ? gr : unite(r, gr);
  }
  const bool has_surface = surface && !surface->rect.empty();
  if (has_surface) r = r.empty() ? surface->rect : unite(r, surface->rect);
  if (r.empty()) return out;

  // The depth pass's pixels are (t, normal), not colours: nothing is copied under them; a
  // projection's carry the layer's colour packed (the shader writes it, also where the brick has
  // no volume).
  target_.begin(r, has_surface && !iso_depth_pass_ && !projection ? surface : nullptr);
  if (g.any || glowing || (projection && has_surface)) {
    if (!projection && !settings_.iso_debug && !iso_depth_pass_) {
      gl_.Enable(GL_BLEND);
      gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // the ray's colour over the surface's
    }
    // Adaptive blocks cannot be shaded (raycast_sample.frag.glsl sampleAt); the scene refuses it.
    if (g.adaptive && shading_.enabled)
      throw std::logic_error("ray caster: gradient shading of an adaptive brick");
    const unsigned fields = g.fields.empty() ? 0u : unsigned(field_tables_.size());
    if (fields > 0 && (preint || shading_.enabled || glowing || settings_.adaptive_step))
      throw std::logic_error("ray caster: several fields with pre-integration, shading, glow or adaptive steps");
    const GlProgram& program =
        programs_.get((g.adaptive ? kAdaptive : 0) | (preint ? kPreintegrated : 0) |
                      (shading_.enabled && !iso ? kShading : 0) | (float_filter_ ? kFloatFilter : 0) |
                      (glowing ? kGlow : 0) | projection | (iso ? kIsosurface : 0) |
                      (settings_.iso_debug ? kIsoDebug : 0) | (iso_depth_pass_ ? kIsoDepth : 0) |
                      (fields << kFieldsShift));
    gl_.UseProgram(program);
    setPixelRayUniforms(program, cam);
    if (projection & kMipExact) {
      setDoublePixelRayUniforms(program, cam);
      // The brick's own box and the texel index map in double: the span and the cell walk
      // (raycast_projection.frag.glsl projectExact).
      glm::dvec3 lo, hi;
      for (int a = 0; a < 3; ++a) lo[a] = g.blocks.planes[a].front(), hi[a] = g.blocks.planes[a].back();
      program.set("u_box_lo_d", lo);
      program.set("u_box_hi_d", hi);
      program.set("u_index_scale_d", b.index_scale);
      program.set("u_index_offset_d", b.index_offset);
    }
    setClipUniforms(program, clip_);
    if (g.adaptive) {
      program.set("u_index_scale", g.lookup.index_scale);
      program.set("u_index_offset", g.lookup.index_offset);
      program.set("u_block_cells", g.lookup.block_cells);
      program.set("u_atlas_inv", g.lookup.atlas_inv);
      program.set("u_blocks", 5);
      program.set("u_own_steps", settings_.own_resolution_steps ? 1 : 0);
      gl_.ActiveTexture(GL_TEXTURE5);
      gl_.BindTexture(GL_TEXTURE_3D, g.lookup.table);
    } else {
      program.set("u_tex_scale", b.tex_scale);
      program.set("u_tex_offset", b.tex_offset);
    }
    program.set("u_delta", float(spacing));
    // Where rays enter and leave the whole volume: the span's end segments (raycast_march.frag.glsl
    // stepsLength) and the isosurfaces' first and last intervals.
    program.set("u_vol_lo", glm::vec3(volume_box_.lo));
    program.set("u_vol_hi", glm::vec3(volume_box_.hi));
    // Isosurfaces: a ray stops at an opaque hit only (isoHit makes its opacity exactly 1).
    program.set("u_ert", iso ? 1.0f : settings_.ert_threshold < 1.0 ? float(settings_.ert_threshold) : 2.0f);
    program.set("u_volume", 0);
    program.set("u_surface", 2);
    program.set("u_planes", 3);
    program.set("u_skip", 4);
    program.set("u_has_surface", has_surface ? 1 : 0);
    table_.use(program);
    if (fields > 0) useFields(program, g);
    if (preint) table_.usePreintegrated(program, spacing);  // segments delta long
    if (shading_.enabled && !iso) setShadingUniforms(program, shading_, b, table_.function());
    if (iso) setIsosurfaceUniforms(program, settings_.isovalues, shading_, b, volume_box_);
    if (has_surface) {
      const Rect& sr = surface->rect;
      program.set("u_surface_rect", glm::ivec4(sr.x, sr.y, sr.w, sr.h));
      gl_.ActiveTexture(GL_TEXTURE2);
      gl_.BindTexture(GL_TEXTURE_2D, surface->surface_texture);
    }
    if (glowing) {
      program.set("u_glow_lo", glm::vec3(glow->box.lo));
      program.set("u_glow_hi", glm::vec3(glow->box.hi));
      program.set("u_glow_hi_open", glm::vec3(glm::lessThan(glow->box.hi, glow->whole.hi)));
      program.set("u_glow_intensity", glow->intensity);
      bindGlowEmitters(gl_, program, *glow, 7);  // 6: the pre-integration table
    }
    gl_.ActiveTexture(GL_TEXTURE3);
    gl_.BindTexture(GL_TEXTURE_2D, g.planes);
    gl_.ActiveTexture(GL_TEXTURE4);
    gl_.BindTexture(GL_TEXTURE_3D, g.skip);
    if (settings_.blend == VolumeBlend::kMip || settings_.blend == VolumeBlend::kMinip) {
      program.set("u_block_range", 12);
      gl_.ActiveTexture(GL_TEXTURE12);
      gl_.BindTexture(GL_TEXTURE_3D, g.range);
    }
    if (projection) {
      program.set("u_bounded", settings_.bounded ? 1 : 0);
      program.set("u_surface_colour", 13);
      gl_.ActiveTexture(GL_TEXTURE13);
      gl_.BindTexture(GL_TEXTURE_2D, has_surface ? surface->colour_texture : 0u);
    }
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, b.texture);
    gl_.BindVertexArray(vao_);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    gl_.Disable(GL_BLEND);
  }
  out.rect = r;
  // A projection's pixels are values and sums, the debug and depth passes' t and normals: float.
  if (glow || projection || settings_.iso_debug || iso_depth_pass_)
    out.pixels_f = target_.finishFloat(r);
  else
    target_.finish(r, out);
  return out;
}

RenderedBrick RaycastRenderer::renderIsoDepth(int handle, const Camera& cam, double spacing,
                                              const SurfaceLayer* surface) {
  if (settings_.isovalues.empty()) throw std::logic_error("renderIsoDepth: no isovalues");
  struct Pass {  // the flag is reset however render() leaves
    bool& on;
    explicit Pass(bool& f) : on(f) { on = true; }
    ~Pass() { on = false; }
  } pass(iso_depth_pass_);
  RenderedBrick out = render(handle, cam, spacing, 0.0, 0.0, surface, nullptr);
  for (size_t i = 0; i < out.pixels_f.size(); i += 4)
    if (out.pixels_f[i] == 0.0f) out.pixels_f[i] = 1e30f;  // no opaque hit: the surface images' miss
  return out;
}

}  // namespace sortlast
