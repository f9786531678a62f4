#include "render/brick_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/scene.h"

namespace sortlast {

VolumeMethod volumeMethod(const Scene& scene) {
  VolumeMethod m;
  m.raycast = scene.render.raycast();
  m.raycast_settings.ert_threshold = scene.render.ert_threshold;
  m.raycast_settings.own_resolution_steps = scene.adaptive.steps == AdaptiveSteps::kOwn;
  m.shading = scene.render.shading;
  m.raycast_settings.adaptive_step = scene.render.adaptive_step;
  m.raycast_settings.adaptive_tolerance = scene.render.adaptive_step_tolerance;
  m.ray_block_cells = scene.render.ray_block_cells;
  if (scene.render.projection()) {
    m.raycast_settings.blend = scene.render.blend;
    m.raycast_settings.mip_exact = scene.render.mip_exact;
    // The session's projectionBounded (session/projection_frame.h), a layer above this one.
    m.raycast_settings.bounded = scene.particles.enabled() || !scene.surfaces.empty();
    m.slicing_settings.bounded = m.raycast_settings.bounded;
    m.slicing_settings.blend = scene.render.blend;  // (the scene refuses mip_exact with slicing)
  }
  if (scene.render.blend == VolumeBlend::kIsosurface) m.raycast_settings.isovalues = scene.render.isovalues;
  return m;
}

MetaballSettings metaballSettings(const ParticleDesc& desc) {
  MetaballSettings s;
  s.h = desc.influenceRadius();
  s.threshold = desc.threshold;
  s.step = desc.step * s.h;
  s.max_samples = desc.max_samples;
  // Anisotropic kernels reach up to max(splash, surface) scale times as far along a ray: the cap
  // (on samples where F > 0) grows alike, or it runs out before thin parts (measured at 96 on
  // the splash at 512^2: 58 holes against 0 round; scaled by 1.5: 1).
  if (desc.anisotropicOn())
    s.max_samples = int(std::ceil(desc.max_samples *
                                  std::max(desc.anisotropic.splash_scale, desc.anisotropic.surface_scale)));
  s.refine_iterations = desc.refine_iterations;
  s.cull = desc.cull;
  s.samples_per_pass = desc.samples_per_pass;
  s.colour = desc.colour;
  s.method = desc.method;
  s.anisotropic = desc.anisotropicOn();
  s.anisotropic_params = desc.anisotropic;
  s.slice_spacing = desc.slice_spacing;
  return s;
}

BrickRenderer::BrickRenderer(const std::string& backend, int width, int height,
                             const DeviceRequest& device)
    : ctx_(createGlContext(backend, device)),
      textures_(std::make_unique<VolumeTexturePool>(ctx_->gl())),
      width_(width),
      height_(height),
      // llvmpipe's queries do not time its draws: a fence bounds them there (gpu_timer.h).
      timer_(std::make_unique<GpuTimer>(ctx_->gl(), ctx_->info().device < 0)) {}

void BrickRenderer::enableVolume(const TransferFunction& tf, int table_size, int block_cells,
                                 const VolumeMethod& method, bool preintegrated) {
  if (method.raycast)
    volume_ = std::make_unique<RaycastRenderer>(*ctx_, width_, height_, method.ray_block_cells,
                                                method.raycast_settings, textures_.get());
  else
    volume_ = std::make_unique<SlicingRenderer>(*ctx_, width_, height_, block_cells, method.slicing_settings);
  volume_->setTransferFunction(tf, table_size, preintegrated);
  volume_->setShading(method.shading);
  // The image stays in the target until readBack(): the draw's timer ends before any read-back.
  volume_->setDeferredReadback(true);
}

void BrickRenderer::readBack(BrickFrame& frame) {
  if (!frame.unread) return;
  if (overlapped_readback_)
    frame.pending = frame.unread->readAsync(frame.rect);
  else
    frame.pixels = frame.unread->finish(frame.rect);
  frame.unread = nullptr;
}

void BrickRenderer::enableParticles(const MetaballSettings& settings) {
  if (settings.method == ParticleMethod::kGrid)
    metaballs_ = std::make_unique<MetaballGridRenderer>(*ctx_, width_, height_, settings);
  else if (settings.method == ParticleMethod::kSlices)
    metaballs_ = std::make_unique<MetaballSlicesRenderer>(*ctx_, width_, height_, settings);
  else
    metaballs_ = std::make_unique<MetaballRenderer>(*ctx_, width_, height_, settings);
}

void BrickRenderer::enableSurfaces(const std::vector<SurfaceSpec>& surfaces) {
  if (surfaces.empty() || (subdiv_ && surface_count_ == surfaces.size())) return;
  subdiv_ = std::make_unique<SubdivRenderer>(*ctx_, width_, height_);
  for (const SurfaceSpec& s : surfaces) subdiv_->addSurface(SubdivSurface(*s.mesh), s.level, s.shading);
  surface_count_ = surfaces.size();
  surface_bounds_ = surfacesBounds(surfaces);
}

int BrickRenderer::addHandles(Handles h, const Box3& clip) {
  h.clip = clip;
  // Closed boxes: surfaces that only touch the brick's face are the brick's too.
  h.surfaces = subdiv_ && !isEmpty(intersect(clip, surface_bounds_));
  bricks_.push_back(h);
  return int(bricks_.size()) - 1;
}

void BrickRenderer::enableGlow() { glow_ = std::make_unique<GlowRenderer>(ctx_->gl(), width_, height_); }

void BrickRenderer::setGlowEmitters(const std::vector<GlowEmitter>& emitters, double eps, double intensity) {
  if (glow_) glow_->setEmitters(emitters, eps, intensity);
}

void BrickRenderer::setBrickGlow(int handle, const Box3& box, const Box3& whole) {
  Handles& h = bricks_.at(size_t(handle));
  h.glow = true;
  h.glow_box = box;
  h.glow_whole = whole;
}

void BrickRenderer::setImageSize(int width, int height) {
  width_ = width;
  height_ = height;
  if (subdiv_) subdiv_->resize(width, height);
  if (glow_) glow_->resize(width, height);
  if (volume_) volume_->resize(width, height);
  if (metaballs_) metaballs_->resize(width, height);
}

void BrickRenderer::setTransferFunction(const TransferFunction& tf, int table_size, bool preintegrated) {
  if (volume_) volume_->setTransferFunction(tf, table_size, preintegrated);
}

void BrickRenderer::setVolumeMethodSettings(const VolumeMethod& method) {
  if (!volume_) return;
  if (RaycastRenderer* ray = volume_->raycaster()) ray->setSettings(method.raycast_settings);
  if (SlicingRenderer* slicing = volume_->slicer()) slicing->setSettings(method.slicing_settings);
  volume_->setShading(method.shading);
}

std::optional<BrickRenderer::BlockRanges> BrickRenderer::blockRangesPart(const GridGeometry& grid) const {
  const RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr;
  if (!ray) return std::nullopt;
  return ray->globalRangesPart(grid);
}

void BrickRenderer::setBlockRanges(BlockRanges ranges) {
  if (RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr)
    ray->setGlobalRanges(std::move(ranges.first), std::move(ranges.second));
}

void BrickRenderer::setMetaballSettings(const MetaballSettings& settings) {
  if (metaballs_) metaballs_->setSettings(settings);
}

void BrickRenderer::dropSpareTextures() { textures_->dropSpares(); }

void BrickRenderer::reset() {
  bricks_.clear();
  metaballs_.reset();
  glow_.reset();
  volume_.reset();
}

int BrickRenderer::addBrick(const Brick* volume_brick, const GridGeometry* grid,
                            const std::vector<float>* samples, const Box3& particle_clip,
                            const std::vector<glm::vec3>* particles,
                            const AdaptiveBrickBlocks* adaptive) {
  Handles h;
  if (volume_brick && adaptive) {
    RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr;
    if (!ray) throw std::logic_error("adaptive bricks need the ray caster (enableVolume)");
    h.volume = ray->addAdaptiveBrick(*volume_brick, *grid, *adaptive);
  } else if (volume_brick && volume_) {
    h.volume = volume_->addBrick(*volume_brick, *grid, *samples);
  }
  if (particles && metaballs_) h.particles = metaballs_->addBrick(particle_clip, *particles);
  return addHandles(h, particle_clip);
}

int BrickRenderer::addBrick(const Brick& volume_brick, const GridGeometry& grid,
                            const BrickSamples& samples, const Box3& particle_clip,
                            const std::vector<glm::vec3>* particles) {
  Handles h;
  if (volume_) h.volume = volume_->addBrick(volume_brick, grid, samples);
  if (particles && metaballs_) h.particles = metaballs_->addBrick(particle_clip, *particles);
  return addHandles(h, particle_clip);
}

void BrickRenderer::setFieldTransfers(const std::vector<TransferFunction>& tfs, const std::vector<int>& table_sizes) {
  RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr;
  if (!ray) throw std::logic_error("several fields need the ray caster (enableVolume)");
  ray->setFieldTransfers(tfs, table_sizes);
}

int BrickRenderer::addFieldsBrick(const Brick& brick, const GridGeometry& grid,
                                  const std::vector<FieldBrickPart>& parts, const Box3& clip) {
  RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr;
  if (!ray) throw std::logic_error("several fields need the ray caster (enableVolume)");
  Handles h;
  h.volume = ray->addFieldsBrick(brick, grid, parts);
  return addHandles(h, clip);
}

int BrickRenderer::addParticleBrick(const Box3& particle_clip, const std::vector<glm::vec3>& particles) {
  Handles h;
  if (metaballs_) h.particles = metaballs_->addBrick(particle_clip, particles);
  return addHandles(h, particle_clip);
}

SurfaceLayer BrickRenderer::mergeSurfaceLayers(const Handles& h, const Camera& cam, double near_plane,
                                               double far_plane, const Rect& particles) {
  SurfaceLayer under;
  if (!particles.empty()) under = {metaballs_->colourTexture(), metaballs_->surfaceTexture(), particles};
  if (!h.surfaces) return under;
  // Where this brick's part of the surfaces can show: the limit surface lies in the control
  // points' bounds. A pixel whose Newton steps stop short of its ray (within the coarse mesh's
  // deviation of a silhouette) may show a limit point just outside that projection: 2 pixels more.
  const Box3 part = intersect(h.clip, surface_bounds_);
  Rect r = screenRectOf(cam, part);
  if (r.empty()) return under;
  const int x0 = std::max(0, r.x - 2), y0 = std::max(0, r.y - 2);
  r = {x0, y0, std::min(cam.width, r.x + r.w + 2) - x0, std::min(cam.height, r.y + r.h + 2) - y0};
  const Rect region = particles.empty() ? r : unite(r, particles);
  subdiv_->draw(cam, h.clip, near_plane, far_plane, particles.empty() ? nullptr : &under, &region);
  return {subdiv_->colourTexture(), subdiv_->surfaceTexture(), region};
}

namespace {

// The surface floats cover the particle rectangle; re-cut them to the brick image's rectangle.
void recutSurface(std::vector<float>& surface, const Rect& from, const Rect& to) {
  if (surface.empty() || to == from) return;
  std::vector<float> cut(size_t(to.area()) * 4, 0.0f);
  for (size_t i = 0; i < cut.size(); i += 4) cut[i] = 1e30f;
  for (int y = 0; y < from.h; ++y)
    for (int x = 0; x < from.w; ++x) {
      size_t src = 4 * (size_t(y) * from.w + x);
      size_t dst = 4 * (size_t(y + from.y - to.y) * to.w + (x + from.x - to.x));
      for (int c = 0; c < 4; ++c) cut[dst + c] = surface[src + c];
    }
  surface = std::move(cut);
}

// The isosurface's opaque hits (t, normal; t = 1e30: none) into the brick's surface floats
// (rect `to`; empty: no particle or subdivision surface in the brick), the nearer per pixel. The
// rays end at the opaque layer, so a hit is never behind it.
void mergeIsoDepth(std::vector<float>& surface, const Rect& to, const RenderedBrick& iso) {
  if (iso.rect != to) throw std::logic_error("isosurface depth: not the brick image's rectangle");
  if (surface.empty()) {
    surface.assign(size_t(to.area()) * 4, 0.0f);
    for (size_t i = 0; i < surface.size(); i += 4) surface[i] = 1e30f;
  }
  for (size_t i = 0; i < surface.size(); i += 4)
    if (iso.pixels_f[i] < surface[i])
      for (int c = 0; c < 4; ++c) surface[i + c] = iso.pixels_f[i + c];
}

// The opaque layer's RGBA8 pixels as a bounded projection's partial pixels without a value
// (compositing/projection_pixels.h: (0, r + 256 g + 65536 b, 0, 2) where it is hit, else absent;
// additive: each rgb byte and the flags 2 times 65536, the half sums 0), the bytes the ray caster
// packs (raycast_projection.frag.glsl projectionPixel).
std::vector<float> boundedLayerPixels(const ImageRGBA8& layer, VolumeBlend blend) {
  std::vector<float> out(layer.px.size(), 0.0f);
  for (size_t i = 0; i < out.size(); i += 4)
    if (layer.px[i + 3] > 0) {
      if (blend == VolumeBlend::kAdditive) {
        for (int c = 0; c < 3; ++c) out[i + c] = 65536.0f * float(layer.px[i + c]);
        out[i + 3] = 65536.0f * 2.0f;
        continue;
      }
      out[i + 1] = float(uint32_t(layer.px[i]) | uint32_t(layer.px[i + 1]) << 8 | uint32_t(layer.px[i + 2]) << 16);
      out[i + 3] = 2.0f;
    }
  return out;
}

}  // namespace

BrickFrame BrickRenderer::render(int handle, const Camera& cam, double slice_spacing,
                                 double near_plane, double far_plane, bool want_surface) {
  const Handles& h = bricks_.at(size_t(handle));
  // The GL work of this brick, up to (not including) its read-back: draw_s.
  struct TimedScope {
    GpuTimer& t;
    explicit TimedScope(GpuTimer& timer) : t(timer) { t.begin(); }
    ~TimedScope() { t.end(); }
  };
  std::optional<TimedScope> timed(std::in_place, *timer_);
  BrickFrame out;
  SurfaceBrick surface;
  if (h.particles >= 0) {
    surface = metaballs_->render(h.particles, cam, near_plane, far_plane, want_surface);
    out.particle_rounds = surface.rounds;
    out.surface = std::move(surface.surface);
  }
  // The opaque layer: the particles' alone, or merged with the subdivision surfaces'.
  const SurfaceLayer layer = mergeSurfaceLayers(h, cam, near_plane, far_plane, surface.rect);
  const bool merged = h.surfaces && !layer.rect.empty();
  if (merged) {
    // What the particle renderer read back is superseded by the merged targets.
    surface.rect = layer.rect;
    out.surface.clear();
    subdiv_->read(layer.rect, h.volume < 0 ? &surface.pixels : nullptr, want_surface ? &out.surface : nullptr);
  }
  const SurfaceLayer* opaque = surface.rect.empty() ? nullptr : &layer;
  if (glow_ && h.volume < 0) {
    if (h.glow) {
      GlowBrickImage g = glow_->render(h.glow_box, h.glow_whole, cam, opaque);
      recutSurface(out.surface, surface.rect, g.rect);
      out.rect = g.rect;
      out.pixels_f = std::move(g.pixels);
    } else {
      out.rect = surface.rect;
      out.pixels_f = toFloat(surface.pixels).px;
    }
    return out;
  }
  if (h.volume < 0) {
    out.rect = surface.rect;
    const RaycastRenderer* ray = volume_ ? volume_->raycaster() : nullptr;
    const SlicingRenderer* slicer = volume_ ? volume_->slicer() : nullptr;
    const VolumeBlend blend = ray ? ray->settings().blend : slicer ? slicer->settings().blend : VolumeBlend::kComposite;
    if (blend != VolumeBlend::kComposite && blend != VolumeBlend::kIsosurface)  // a bounded projection's: the layer alone
      out.pixels_f = boundedLayerPixels(surface.pixels, blend);
    else
      out.pixels = std::move(surface.pixels);
    return out;
  }
  // Glow in a volume brick: the ray caster integrates it (the session refuses slicing).
  std::optional<GlowPass> glow;
  if (glow_) glow = glow_->pass(h.glow ? h.glow_box : noBox(), h.glow_whole);
  // An isosurface's opaque hit is a surface too (--surface-out): its depth pass goes first, as
  // render() leaves its image in the target the pass draws into.
  RaycastRenderer* iso_ray = want_surface ? volume_->raycaster() : nullptr;
  RenderedBrick iso_depth;
  if (iso_ray && iso_ray->isosurfaces()) iso_depth = iso_ray->renderIsoDepth(h.volume, cam, slice_spacing, opaque);
  RenderedBrick rb;
  if (glow) {
    RaycastRenderer* ray = volume_->raycaster();
    if (!ray) throw std::logic_error("glow in a slicing brick");
    rb = ray->render(h.volume, cam, slice_spacing, near_plane, far_plane, opaque, &*glow);
  } else {
    rb = volume_->render(h.volume, cam, slice_spacing, near_plane, far_plane, opaque);
  }
  // The surface floats cover the layer's rectangle; re-cut them to the brick image's rectangle.
  recutSurface(out.surface, surface.rect, rb.rect);
  if (!iso_depth.rect.empty()) mergeIsoDepth(out.surface, rb.rect, iso_depth);
  out.rect = rb.rect;
  out.pixels = std::move(rb.pixels);
  out.pixels_f = std::move(rb.pixels_f);
  out.unread = rb.unread;
  return out;
}

}  // namespace sortlast
