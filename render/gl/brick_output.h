#pragma once
// What a volume renderer returns per brick, and the opaque surface layer it may be handed: shared
// by the slicing and ray-casting renderers (render/volume/slicing_renderer.h, render/volume/raycast_renderer.h).
#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"

namespace sortlast {

class FloatTarget;

struct RenderedBrick {
  Rect rect;  // empty: nothing to draw (invisible under the transfer function, or off screen)
  ImageRGBA8 pixels;  // rect.w x rect.h
  // Deferred read-back (FloatTarget::setDeferred): `pixels` stays empty and this target still
  // holds the brick's image, for the caller to start reading (FloatTarget::readAsync) once the
  // brick's GL work is issued and timed.
  FloatTarget* unread = nullptr;
  std::vector<float> pixels_f;  // instead, with a GlowPass: premultiplied RGBA floats, unrounded
};

// Glow emitters to integrate along the rays of a brick (render/glow/glow_renderer.h): the emitters'
// texture (render/glow/glow_gl.h), their core radius and intensity, and the brick's part `box` of the
// glow box `whole` (lo > hi: none in this brick). A renderer given one reads its image back in
// float (light without opacity, above 1 before the tone map).
struct GlowPass {
  unsigned emitters = 0;
  int count = 0;
  float eps = 0.01f, intensity = 1.0f;
  Box3 box, whole;
};

// An opaque surface already rendered in the same brick (render/particles/metaball_renderer.h): its colour
// (RGBA32F, premultiplied) and (t, normal) textures, valid over `rect`. The volume renderer ends
// its rays at t and puts what they gathered over the surface colour, so the brick image holds
// both in the right order.
struct SurfaceLayer {
  unsigned colour_texture = 0;
  unsigned surface_texture = 0;
  Rect rect;
};

}  // namespace sortlast
