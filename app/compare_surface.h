#pragma once
#include <cstdint>
#include <vector>
// `sortlast compare-surface REF.exr TEST.exr`: how far a rendered surface is from the reference
// surface, pixel by pixel — which pixels are hit in one and not the other (holes, extra hits),
// how far apart the hit depths are, and by what angle the normals differ. Colour comparison
// cannot tell a surface in the wrong place from one in the right place shaded alike; this can.
#include <cmath>

#include "io/surface_image.h"

namespace sortlast {

struct SurfaceDifference {
  long long both = 0;                       // pixels hit in both images
  long long holes = 0;                      // hit in the reference, missed in the test
  long long extra = 0;                      // hit in the test, missed in the reference
  long long edges_ignored = 0;              // silhouette pixels left out (with ignore_edges)
  long long creases_ignored = 0;            // crease pixels left out (with crease_deg)
  double depth_max = 0.0, depth_rms = 0.0;  // |t_ref - t_test| over `both`, world units
  double normal_max_deg = 0.0, normal_mean_deg = 0.0;  // angle between normals over `both`
  long long depth_outliers = 0;             // pixels of `both` whose depth error exceeds the tolerance
  // Where the worst of each is (-1: none), so a failure can be looked at.
  int worst_depth_x = -1, worst_depth_y = -1;
  int worst_normal_x = -1, worst_normal_y = -1;
  int first_hole_x = -1, first_hole_y = -1, first_extra_x = -1, first_extra_y = -1;
};

// A silhouette pixel: one of its 4 neighbours in `ref` (inside the image) differs from it in hit
// or miss. There sampling legitimately differs between renderers.
bool isSilhouettePixel(const SurfaceImage& ref, int x, int y);

// Throws InputError when the sizes differ. With `ignore_edges`, silhouette pixels of the reference
// count nowhere. A zero or non-finite normal in either image counts as 180 degrees off.
// `depth_tolerance`: depth errors above it count as outliers (a surface found on the wrong layer:
// a thin sliver in front missed, the one behind hit), which a max or RMS alone cannot separate
// from a small error everywhere.
// `ignore` (per pixel, non-zero: left out, counted as edges), e.g. compare.h's silhouetteBand.
// `crease_deg`: pixels whose reference normal turns by more than that from a 4-neighbour's (a
// crease, a normal discontinuity: a pixel on it may show either side) count nowhere either.
SurfaceDifference compareSurfaces(const SurfaceImage& ref, const SurfaceImage& test,
                                  bool ignore_edges, double depth_tolerance = INFINITY,
                                  double crease_deg = INFINITY,
                                  const std::vector<uint8_t>* ignore = nullptr);

}  // namespace sortlast
