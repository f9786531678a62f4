#pragma once
// The reference of isosurfaces (render.blend: isosurface; transfer/isosurface.h), in double: per
// ray, every crossing of every isovalue by the trilinear field of the whole volume, exactly.
//
// Along a ray the trilinear interpolant restricted to one cell is a cubic in t. The ray is cut at
// every cell face it crosses; per cell, the cubic's coefficients (the product of the three
// linear weights per corner), its derivative's roots split the cell's segment into monotone
// pieces, and a piece holds a crossing exactly when "value >= isovalue" differs at its two ends
// (the predicate carried from one piece to the next, never evaluated twice at a shared end, so a
// crossing on a cell face is counted once). The crossing is bisected on its piece to the last
// bit of t (about 1e-15 relative; at least 1e-12 world units). So the reference sees every
// crossing, also two of one isovalue closer than the ray caster's sample step, which the ray
// caster misses (render/volume/raycast_isosurface.frag.glsl): that difference is the ray caster's
// error, measured, not hidden.
//
// The hits are composited front to back (each isovalue's colour shaded with the exact gradient of
// the interpolant in the hit's cell, transfer/isosurface.h) up to the first opaque one, the ray's
// end at the volume's far face or the opaque surface layer's t, whose colour goes behind, as in
// reference/reference.h. The volume's clip region (WholeVolume::clip) cuts the span first: the
// search starts at the clip entry, whose side of each isovalue is the starting one (no surface on
// the cut face), as the ray caster's.
#include <vector>

#include "common/camera.h"
#include "io/image.h"
#include "io/surface_image.h"
#include "reference/reference.h"
#include "transfer/isosurface.h"

namespace sortlast {

struct IsoHit {
  double t = 0.0;          // unit-ray distance from the origin
  glm::dvec3 gradient{0};  // world gradient of the trilinear interpolant at the hit
  int iso = 0;             // which isovalue
};

// Every crossing of `isovalues` along o + t d (d unit) for t in [ta, tb] (inside the volume's
// box), nearest first; stops after the first hit of an opaque isovalue. Not for adaptive fields.
std::vector<IsoHit> isoCrossings(const WholeVolume& vol, const std::vector<Isovalue>& isovalues,
                                 const glm::dvec3& o, const glm::dvec3& d, double ta, double tb);

// The image: premultiplied RGBA. `stop` / `stop_colour` (both or neither): the opaque surface
// layer, as reference/reference.h's second overload (throws InputError on a size mismatch).
// `opaque` (optional): the camera's size, per pixel the opaque hit that ends the ray (t, outward
// unit normal: down the gradient, towards lower values), a miss where none does; in front of
// `stop` wherever both are, so the nearer of the two is it (--surface-out).
ImageF renderIsosurfaceReference(const WholeVolume& vol, const std::vector<Isovalue>& isovalues,
                                 const Shading& shading, const Camera& cam, int threads,
                                 const SurfaceImage* stop = nullptr, const ImageF* stop_colour = nullptr,
                                 SurfaceImage* opaque = nullptr);

}  // namespace sortlast
