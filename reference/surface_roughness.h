#pragma once
// A surface roughness figure from a rendered surface image (measure smoothness, not
// just speed): the angle between the normals of neighbouring pixels, over every pair of 4-
// neighbours (right and down) that both hit and whose depths are continuous. A flat or gently
// curved surface gives angles near 0 (a sphere of radius r seen across n pixels about
// 180 / (pi n) degrees a pair); the bumps of round metaballs on a fluid surface give several
// degrees. Silhouettes and occlusion edges are left out by the depth test, so the figure is about
// the surface's own relief. Pure CPU: unit-tested on synthetic images.
#include "io/surface_image.h"

namespace sortlast {

struct RoughnessOptions {
  // A pair is continuous when |t_p - t_q| <= max_depth_jump * min(t_p, t_q) (relative: a pixel's
  // footprint grows with distance; 0.02 admits surfaces tilted up to about 84 degrees at 256^2
  // and a 30 degree field of view).
  double max_depth_jump = 0.02;
  // Pixels [x0, x1) x [y0, y1) (row 0 = top) only; x1 or y1 <= 0: to the image's edge.
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  // Smallest piece counted (pixels): single stray pixels of a silhouette are not pieces.
  int min_piece_pixels = 4;
};

struct Roughness {
  long long pairs = 0;      // continuous neighbour pairs measured
  double rms_deg = 0.0;     // RMS angle between their normals (degrees): the roughness figure
  double mean_deg = 0.0;    // mean angle (degrees)
  double p95_deg = 0.0;     // 95th percentile (degrees)
  // Depth t over the region's hit pixels (relief: with the camera square to a flat surface,
  // t_max - t_min is its height range), and at the region's centre pixel (inf: a miss).
  double t_min = 0.0, t_max = 0.0, t_centre = 0.0;
  // Connected pieces of the surface in the region: groups of hit pixels joined through
  // continuous 4-neighbour pairs (the test above), each of at least min_piece_pixels. Droplets
  // and sheets that smoothing lets vanish, or merges, change this count.
  long long pieces = 0;
};

// Throws InputError if the region is empty or outside the image, or max_depth_jump is not > 0.
Roughness surfaceRoughness(const SurfaceImage& img, const RoughnessOptions& options);

}  // namespace sortlast
