#pragma once
// The reference: a CPU integrator in double precision of the same emission-absorption model the
// GL renderer approximates (same trilinear field, same transfer function, same opacity
// correction), in the continuous limit of the sample spacing: each ray is cut into steps of
// `step` world units (default 1/16 voxel) and each step is composited exactly with its middle's
// colour and its optical depth by Simpson's rule (tau at its ends and middle), T *= exp(-tau h);
// a step whose end values straddle a kink of the transfer function (a point of it, or where its
// range clamps: TransferFunction::kinkValues) is cut there first, the values taken as linear
// between the ends. Both make the default step converge where the function is sharp: neghip's
// sharp preset 56.7 -> 60.0 dB against the integral at 1/256 voxel, pixels over 4/255 0.15 % ->
// none (results/accuracy/reference_convergence.md). This is what accuracy is measured against. With `shading` on, each
// step's colour is shaded (transfer/shading.h) with the gradient of the same trilinear field by
// central differences (WholeVolume::gradient), in double like the rest. `sortlast reference` and
// `--psnr` integrate by cells instead by default (reference.integrator: cells, the `cells` flag
// below): the same model to a tolerance, converged where 1/16-voxel steps are not (neghip's sharp
// function: 83 against 60 dB from the limit at 256²) and 3.5-7x faster.
#include <memory>
#include <vector>

#include "adaptive/adaptive_blocks.h"
#include "common/camera.h"
#include "common/clip.h"
#include "common/grid.h"
#include "io/image.h"
#include "transfer/shading.h"
#include "io/surface_image.h"
#include "transfer/transfer_function.h"
#include "reference/glow_reference.h"

namespace sortlast {

struct WholeVolume {
  GridGeometry grid;
  std::vector<float> samples;  // x fastest
  // Set: the field is this adaptive representation's (sampleIndex), not the samples' (which then
  // only give the transfer function its range).
  std::shared_ptr<const AdaptiveVolume> adaptive;
  // Where the volume is shown (clip.planes, clip.box): each ray's span is cut to it (clipSpan).
  ClipRegion clip;
  double at(const glm::dvec3& index) const;  // trilinear, index clamped to the grid
  // World gradient at `index`: (at(index + e_a) - at(index - e_a)) / (2 spacing_a) per axis, so
  // one-sided where index +- 1 leaves the grid (at() clamps).
  glm::dvec3 gradient(const glm::dvec3& index) const;
};

// `cells`: each ray's span integrated by integrateSegment (reference/ray_segment.h) over the whole
// volume as one brick -- each cell's crossing to a tolerance -- instead of in equal steps; where
// the field is the adaptive representation's or there is glow, the steps regardless.
ImageF renderReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                       double step, int threads, const Shading& shading = {},
                       const GlowRays* glow = nullptr, bool cells = false);

// Mixed scenes: an opaque surface (metaballs) in the volume. Per pixel the integral runs only for
// t < stop.t (the same unit-ray distance the surface reference reports; +inf: no surface) and
// `stop_colour` (premultiplied; opaque where hit, zero at misses) is composited behind what the
// volume left: rgb += transmittance * surface rgb, alpha = 1 - transmittance * (1 - surface alpha).
// Without a surface in a pixel the result is bit-identical to the overload above.
//
// `glow` (emitters, reference/glow_reference.h): their light is added along the whole ray inside the
// glow box up to the surface: in front of the volume undimmed, inside it step by step (each step's
// exact segment integral times the transmittance at the step's middle), behind it through what the
// volume left. Glow adds to rgb only (no opacity). Throws
// InputError if either image is not the camera's size.
ImageF renderReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                       double step, int threads, const SurfaceImage& stop, const ImageF& stop_colour,
                       const Shading& shading = {}, const GlowRays* glow = nullptr, bool cells = false);

}  // namespace sortlast
