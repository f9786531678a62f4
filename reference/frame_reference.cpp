#include "reference/frame_reference.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <thread>

#include "common/error.h"
#include "io/particles.h"
#include "io/volume_source.h"
#include "reference/projection_reference.h"
#include "reference/isosurface_reference.h"
#include "scene/isosurface_scene.h"

namespace sortlast {

namespace {

// Where the particles' field can be non-zero: their bounds grown by `reach` (h, or the
// anisotropic reach bound: the box the GL session frames, so both frame the same camera).
// Empty: lo > hi.
Box3 reachOf(const MetaballModel& m, double reach) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{glm::dvec3(inf), glm::dvec3(-inf)};
  for (const glm::dvec3& p : m.positions) b.lo = glm::min(b.lo, p - reach), b.hi = glm::max(b.hi, p + reach);
  return b;
}

// Glow where there is no volume: the whole ray inside the glow box, undimmed, up to the surface.
void addGlowOnly(ImageF& img, const Camera& cam, const GlowRays& g, const SurfaceImage* stop) {
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const size_t pixel = size_t(y) * cam.width + x;
      const double t_stop = stop && stop->hit(pixel) ? double(stop->t[pixel]) : HUGE_VAL;
      const CameraRay ray = cam.pixelRay(x, y);  // from the eye, or the eye plane (orthographic)
      const glm::dvec3 r = g.radiance(ray.origin, ray.direction, 0.0, t_stop);
      for (int k = 0; k < 3; ++k) img.px[4 * pixel + k] += float(r[k]);
    }
}

// The tone map on the final frame's premultiplied rgb (alpha kept; the background goes behind
// later, untouched).
void applyToneMap(ImageF& img, const GlowSpec& g) {
  if (g.tone_map == ToneMap::kNone) return;
  for (size_t i = 0; i < img.px.size(); i += 4)
    for (int k = 0; k < 3; ++k) img.px[i + k] = float(toneMap(g, img.px[i + k]));
}

}  // namespace

FrameReference::FrameReference(Scene scene, int threads)
    : colour_(scene.particles.colour),
      threads_(threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()))) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  bounds_ = {glm::dvec3(inf), glm::dvec3(-inf)};
  if (scene.particles.enabled()) {
    MetaballModel m;
    ParticleSet set = loadParticles(scene.particles);
    // particles.smoothing: auto as the GL session chooses it (the same count over the same set).
    resolveAutoSmoothing(scene.particles,
                         scene.particles.smoothing == Smoothing::kAuto
                             ? countNeighbours(set.positions, scene.particles.influenceRadius())
                             : NeighbourCount{});
    for (const glm::vec3& p : set.positions) m.positions.emplace_back(p);
    m.h = scene.particles.influenceRadius();
    m.threshold = scene.particles.threshold;
    // The same kernels as the GL bricks compute: each depends on its neighbourhood only.
    // Each field is evaluated around its kernel's smoothed centre.
    if (scene.particles.anisotropicOn()) {
      m.kernels = computeAnisotropicKernels(set.positions, m.h, scene.particles.anisotropic);
      for (size_t i = 0; i < m.kernels.size(); ++i) m.positions[i] = glm::dvec3(m.kernels[i].centre);
    }
    bounds_ = reachOf(m, scene.particles.reach());
    balls_ = std::move(m);
  }
  if (scene.hasFields()) {
    // Every field whole, its transfer function over its own data range; the box the session's
    // layout cuts (fieldsGrid), so both frame the same camera.
    for (FieldSpec& f : scene.fields) {
      try {
        validateVolume(f.volume);
      } catch (const InputError& e) {
        throw InputError(fieldMessage(e.what(), f.name));
      }
      FieldInput in{{f.volume.grid, readWholeVolume(f.volume)}, {}};
      auto [lo, hi] = presentRange(in.vol.samples, f.volume.file);
      in.tf = f.shownTransfer().build(lo, hi, f.volume.grid.minSpacing());  // hidden: opacity 0
      fields_.push_back(std::move(in));
    }
    const GridGeometry all = fieldsGrid(scene.fields);  // with the grids the files gave
    fields_step_ = scene.reference.step * all.minSpacing();
    fields_clip_ = scene.clip;
    bounds_ = all.worldBox();
  } else if (scene.hasVolume()) {
    validateVolume(scene.volume);
    VolumeInput in{{scene.volume.grid, {}}, {}, 0.0};
    in.vol.samples = readWholeVolume(scene.volume);
    if (scene.reference.field == ReferenceField::kAdaptive) {
      AdaptiveOptions options;
      options.blocks_per_axis = scene.adaptive.blocks;
      options.tolerance = scene.adaptive.tolerance;
      options.threads = threads_;
      in.vol.adaptive = std::make_shared<const AdaptiveVolume>(
          buildAdaptive(scene.volume.grid, in.vol.samples, options));
    }
    auto [lo, hi] = presentRange(in.vol.samples, scene.volume.file);
    in.tf = scene.transfer.build(lo, hi, scene.volume.grid.minSpacing());
    in.step = scene.reference.step * scene.volume.grid.minSpacing();
    in.vol.clip = scene.clip;
    in.shading = scene.render.shading;
    in.blend = scene.render.projection() ? scene.render.blend : VolumeBlend::kComposite;
    in.mip_exact = scene.render.mip_exact;
    in.cells = scene.reference.integrator == ReferenceIntegrator::kCells;
    if (scene.render.blend == VolumeBlend::kIsosurface) {
      in.isovalues = scene.render.isovalues;
      for (const std::string& w : isovalueRangeWarnings(in.isovalues, lo, hi)) std::fprintf(stderr, "%s\n", w.c_str());
    }
    bounds_ = unite(bounds_, in.vol.grid.worldBox());
    volume_ = std::move(in);
  }
  if (!scene.surfaces.empty()) {
    subdiv_.emplace(scene.surfaces);
    const Box3 s = surfacesDomain(scene.surfaces);  // as the render session's layout takes it
    bounds_ = unite(bounds_, s);
  }
  glow_ = scene.glow;
  if (glow_.enabled()) {
    // The scene refuses emitters alone without a box, so one of the two exists.
    glow_box_ = glow_.box.value_or(bounds_);
    bounds_ = unite(bounds_, glow_box_);
  }
}

ImageF FrameReference::render(const Camera& cam, SurfaceImage* surface_out, int frame,
                              SurfaceReferenceStats* surface_stats) const {
  std::optional<GlowRays> glow;
  if (glow_.enabled()) glow.emplace(glow_, glow_box_, frame);
  const GlowRays* g = glow ? &*glow : nullptr;
  ImageF out(cam.width, cam.height);
  // The opaque layer: metaballs and subdivision surfaces, the nearer per pixel.
  std::optional<SurfaceImage> surface;
  ImageF colour;
  if (balls_) {
    surface = referenceSurface(*balls_, cam, bounds_, threads_);
    colour = shadeSurfaceFloat(*surface, cam, colour_);
  }
  if (subdiv_) {
    SurfaceImage s;
    ImageF c;
    subdiv_->render(cam, threads_, s, c, surface_stats);
    if (surface)
      mergeNearest(*surface, colour, s, c);
    else
      surface = std::move(s), colour = std::move(c);
  }
  if (!fields_.empty())  // the scene refuses particles, surfaces and glow with several fields
    return renderFieldsReference(fields_, bounds_, cam, fields_step_, threads_, fields_clip_);
  if (volume_ && !volume_->isovalues.empty()) {
    SurfaceImage iso;
    out = renderIsosurfaceReference(volume_->vol, volume_->isovalues, volume_->shading, cam, threads_,
                                    surface ? &*surface : nullptr, surface ? &colour : nullptr,
                                    surface_out ? &iso : nullptr);
    if (surface_out) {
      // The opaque hits lie in front of the layer (the rays end there): the nearer per pixel.
      if (surface)
        for (size_t i = 0; i < iso.t.size(); ++i)
          if (iso.hit(i) && !(surface->t[i] <= iso.t[i])) surface->t[i] = iso.t[i], surface->normal[i] = iso.normal[i];
      *surface_out = surface ? std::move(*surface) : std::move(iso);
    }
  } else if (!surface) {
    if (volume_ && volume_->blend != VolumeBlend::kComposite)  // the scene refuses glow with it
      out = renderProjectionReference(volume_->vol, volume_->tf, cam, volume_->step, threads_,
                                      volume_->blend, volume_->mip_exact);
    else if (volume_)
      out = renderReference(volume_->vol, volume_->tf, cam, volume_->step, threads_, volume_->shading, g, volume_->cells);
    else if (g)
      addGlowOnly(out, cam, *g, nullptr);
  } else {
    if (volume_ && volume_->blend != VolumeBlend::kComposite) {  // a projection, bounded by the layer
      out = renderProjectionReference(volume_->vol, volume_->tf, cam, volume_->step, threads_, volume_->blend,
                                      volume_->mip_exact, &*surface, &colour);
    } else if (volume_) {
      out = renderReference(volume_->vol, volume_->tf, cam, volume_->step, threads_, *surface, colour,
                            volume_->shading, g, volume_->cells);
    } else {
      out = std::move(colour);
      if (g) addGlowOnly(out, cam, *g, &*surface);
    }
    if (surface_out) *surface_out = std::move(*surface);
  }
  if (g) applyToneMap(out, glow_);
  return out;
}

}  // namespace sortlast
