#pragma once
// `sortlast compare A B`: how far two images are apart — PSNR over RGB, the largest per-channel
// difference and where it is — and, on request, a difference image. Used by the tests to hold
// renders to stated bounds, and by users to check a shortcut against the reference.
#include <string>

#include "common/image.h"

namespace sortlast {

struct ImageDifference {
  double psnr_db = 0.0;  // infinity when identical
  int max_diff = 0;      // largest |a - b| over RGBA channels, in 1/255
  int worst_x = 0, worst_y = 0;
  double mean_abs = 0.0;
};

ImageDifference compareImages(const ImageRGBA8& a, const ImageRGBA8& b);  // throws on size mismatch
// Pixels where some channel differs by more than `tolerance`.
long long countPixelsOver(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance);
ImageRGBA8 differenceImage(const ImageRGBA8& a, const ImageRGBA8& b, int gain);
// A premultiplied image composited over `background` and rounded, opaque: what a PNG written by
// writeImage holds, so in-process comparisons agree with comparing the written files.
ImageRGBA8 opaqueOver(const ImageF& img, const glm::dvec3& background);

}  // namespace sortlast
