#pragma once
// What `--surface-out` (render and reference) writes: the frame's opaque surface, t and normal per
// pixel (io/surface_image.h), the nearest of the particles' metaball surface, the subdivision
// surfaces and the isosurfaces' opaque hits (a semi-transparent isovalue is not a surface there).
#include "scene/scene.h"

namespace sortlast {

// Whether the scene has such a surface: particles, subdivision surfaces, or render.blend: isosurface.
inline bool hasSurfaceImage(const Scene& s) {
  return s.particles.enabled() || !s.surfaces.empty() || s.render.blend == VolumeBlend::kIsosurface;
}

}  // namespace sortlast
