#pragma once
// What a volume renderer returns per brick, and the opaque surface layer it may be handed: shared
// by the slicing and ray-casting renderers (worker/slicing_renderer.h, worker/raycast_renderer.h).
#include "common/camera.h"
#include "common/image.h"

namespace sortlast {

struct RenderedBrick {
  Rect rect;  // empty: nothing to draw (invisible under the transfer function, or off screen)
  ImageRGBA8 pixels;  // rect.w x rect.h
};

// An opaque surface already rendered in the same brick (worker/metaball_renderer.h): its colour
// (RGBA32F, premultiplied) and (t, normal) textures, valid over `rect`. The volume renderer ends
// its rays at t and puts what they gathered over the surface colour, so the brick image holds
// both in the right order.
struct SurfaceLayer {
  unsigned colour_texture = 0;
  unsigned surface_texture = 0;
  Rect rect;
};

}  // namespace sortlast
