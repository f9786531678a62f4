#pragma once
// `sortlast compare A B`: how far two images are apart — PSNR over RGB, the largest per-channel
// difference and where it is — and, on request, a difference image. Used by the tests to hold
// renders to stated bounds, and by users to check a shortcut against the reference.
#include <string>

#include "io/image.h"
#include "io/surface_image.h"

namespace sortlast {

struct ImageDifference {
  double psnr_db = 0.0;  // infinity when identical
  int max_diff = 0;      // largest |a - b| over RGBA channels, in 1/255
  int worst_x = 0, worst_y = 0;
  double mean_abs = 0.0;
  // Pixels whose largest channel difference exceeds 4/255 (the accuracy goal's bound: at most
  // 0.1 % of pixels), and their share of all pixels.
  long long over4 = 0;
  double over4_share = 0.0;
};

ImageDifference compareImages(const ImageRGBA8& a, const ImageRGBA8& b);  // throws on size mismatch

// Two images compared value by value in float (`sortlast compare --float`): a value passes when
// |a - b| <= abs_tol + rel_tol * max(|a|, |b|); two NaNs, or two infinities of one sign, are equal.
// With both tolerances 0 it passes only on identical values (bit-identity checks of whole frames).
struct FloatDifference {
  double max_abs = 0.0;             // largest |a - b| (infinity where one value is not finite)
  double max_rel = 0.0;             // largest |a - b| / max(|a|, |b|)
  int worst_x = 0, worst_y = 0, worst_channel = 0;  // where max_abs is
  long long values_differing = 0;   // values not identical
  long long values_over = 0;        // values outside the tolerance
};
// Throws InputError when the sizes or channel counts differ.
FloatDifference compareFloatImages(const ImageChannels& a, const ImageChannels& b, double abs_tol,
                                   double rel_tol);
// Pixels where some channel differs by more than `tolerance`.
long long countPixelsOver(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance);
// Per pixel 1 within `radius` pixels (Chebyshev) of a silhouette of `s`: a pixel whose hit or miss
// differs from a 4-neighbour's, or whose depth differs from a hit 4-neighbour's by more than
// `depth_jump` of the nearer (one surface in front of another). Colour comparisons of surfaces
// leave these out where the two renderers' coverage is known to differ (docs/subdivision.md).
std::vector<uint8_t> silhouetteBand(const SurfaceImage& s, int radius, double depth_jump = 0.05);
// `a` takes `b`'s values where `mask` is set, so compareImages and countPixelsOver see no
// difference there (PSNR then counts those pixels as equal). Returns the pixels masked.
long long maskPixels(ImageRGBA8& a, const ImageRGBA8& b, const std::vector<uint8_t>& mask);
ImageRGBA8 differenceImage(const ImageRGBA8& a, const ImageRGBA8& b, int gain);
// A premultiplied image composited over `background` and rounded, opaque: what a PNG written by
// writeImage holds, so in-process comparisons agree with comparing the written files.
ImageRGBA8 opaqueOver(const ImageF& img, const glm::dvec3& background);

}  // namespace sortlast
