#pragma once
// The CPU reference of a scene's frames: what `sortlast reference` writes and what
// `render --psnr` measures each frame against. Holds the whole volume and every particle in one
// process (it is a measuring instrument, not the product).
//
// Volume only: the emission-absorption integral (of the original samples, or with
// reference.field: adaptive of the adaptive-sampling field the ray caster's adaptive blocks hold). Particles only: the metaball surface, rays
// clipped to the particles' bounds grown by h. Both: the volume integrated up to the surface, the
// surface composited behind it. Glow emitters: their light along each ray inside the glow box, in
// front of the volume, inside it (dimmed step by step) and behind it, up to the surface.
// Subdivision surfaces (reference/surface_reference.h): an opaque layer merged by depth with the
// metaball surface; the volume and glow end at the nearer of the two, and so do the projections
// (reference/projection_reference.h, their colour over the layer's). Isosurfaces: the surface
// image (`surface`) also holds their opaque hits, the nearer per pixel.
#include <optional>

#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"
#include "scene/scene.h"
#include "io/surface_image.h"
#include "reference/fields_reference.h"
#include "reference/metaball_reference.h"
#include "reference/reference.h"
#include "reference/surface_reference.h"

namespace sortlast {

class FrameReference {
 public:
  // Loads the scene's data; throws InputError on bad input. `threads` <= 0: all cores.
  FrameReference(Scene scene, int threads);  // a copy: reading a VTK file fills in its grid

  // The scene's domain: the volume box grown to hold the particles' reach (the render job frames
  // and bricks the same box).
  const Box3& bounds() const { return bounds_; }
  bool hasVolume() const { return volume_.has_value() || !fields_.empty(); }
  bool hasParticles() const { return balls_.has_value(); }

  bool hasGlow() const { return glow_.enabled(); }
  bool hasSurfaces() const { return subdiv_.has_value(); }

  // One view, premultiplied. `surface` (scenes with particles or surfaces): also the surface image.
  // `surface_stats`: the subdivision reference's error figures of this view. `frame`:
  // the orbit frame, for the emitters' animation. With emitters, their glow is added
  // (reference/reference.h) and the result tone-mapped (glow.tone_map): the final frame.
  ImageF render(const Camera& cam, SurfaceImage* surface = nullptr, int frame = 0,
               SurfaceReferenceStats* surface_stats = nullptr) const;

 private:
  struct VolumeInput {
    WholeVolume vol;
    TransferFunction tf;
    double step = 0.0;  // world units
    Shading shading;    // render.shading*
    VolumeBlend blend = VolumeBlend::kComposite;  // a projection: reference/projection_reference.h
    bool mip_exact = false;
    std::vector<Isovalue> isovalues;  // render.blend: isosurface (reference/isosurface_reference.h)
    bool cells = false;               // reference.integrator: cells
  };
  std::optional<VolumeInput> volume_;
  // Several fields (`volumes`): their mixture (reference/fields_reference.h) instead of volume_.
  std::vector<FieldInput> fields_;
  double fields_step_ = 0.0;
  ClipRegion fields_clip_;  // clip.planes, clip.box
  std::optional<MetaballModel> balls_;
  std::optional<SurfaceReference> subdiv_;
  glm::dvec3 colour_{1.0};
  GlowSpec glow_;
  Box3 glow_box_;  // glow.box, or the volume's and particles' bounds
  Box3 bounds_;
  int threads_ = 1;
};

}  // namespace sortlast
