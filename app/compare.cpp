#include "app/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "common/error.h"

namespace sortlast {

ImageDifference compareImages(const ImageRGBA8& a, const ImageRGBA8& b) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("compare: image sizes differ (" + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + ")");
  ImageDifference d;
  double se = 0.0, sa = 0.0;
  size_t n = size_t(a.width) * a.height;
  for (size_t i = 0; i < n; ++i) {
    int largest = 0;
    for (int c = 0; c < 4; ++c) {
      int diff = std::abs(int(a.px[4 * i + c]) - int(b.px[4 * i + c]));
      if (c < 3) se += double(diff) * diff;
      sa += diff;
      largest = std::max(largest, diff);
      if (diff > d.max_diff) {
        d.max_diff = diff;
        d.worst_x = int(i % a.width);
        d.worst_y = int(i / a.width);
      }
    }
    d.over4 += largest > 4;
  }
  d.over4_share = n ? double(d.over4) / double(n) : 0.0;
  double mse = se / (3.0 * n);
  d.psnr_db = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
  d.mean_abs = sa / (4.0 * n);
  return d;
}

FloatDifference compareFloatImages(const ImageChannels& a, const ImageChannels& b, double abs_tol,
                                   double rel_tol) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw InputError("compare: images differ in shape (" + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + "x" + std::to_string(a.channels) + " vs " +
                     std::to_string(b.width) + "x" + std::to_string(b.height) + "x" +
                     std::to_string(b.channels) + " channels)");
  FloatDifference d;
  for (size_t i = 0; i < a.px.size(); ++i) {
    const double x = a.px[i], y = b.px[i];
    if (x == y || (std::isnan(x) && std::isnan(y))) continue;
    const double diff = std::abs(x - y);  // infinity or NaN where one value is not finite
    const double scale = std::max(std::abs(x), std::abs(y));
    const bool finite = std::isfinite(diff);
    ++d.values_differing;
    if (!finite || diff > abs_tol + rel_tol * scale) ++d.values_over;
    const double abs_d = finite ? diff : std::numeric_limits<double>::infinity();
    d.max_rel = std::max(d.max_rel, finite ? diff / scale : abs_d);
    if (abs_d > d.max_abs || d.values_differing == 1) {
      d.max_abs = abs_d;
      const size_t pixel = i / size_t(a.channels);
      d.worst_x = int(pixel % size_t(a.width));
      d.worst_y = int(pixel / size_t(a.width));
      d.worst_channel = int(i % size_t(a.channels));
    }
  }
  return d;
}

long long countPixelsOver(const ImageRGBA8& a, const ImageRGBA8& b, int tolerance) {
  long long n = 0;
  for (size_t i = 0; i < a.px.size(); i += 4) {
    bool over = false;
    for (int c = 0; c < 4; ++c) over |= std::abs(int(a.px[i + c]) - int(b.px[i + c])) > tolerance;
    n += over;
  }
  return n;
}

std::vector<uint8_t> silhouetteBand(const SurfaceImage& s, int radius, double depth_jump) {
  const int W = s.width, H = s.height;
  std::vector<uint8_t> edge(size_t(W) * H, 0), band(size_t(W) * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + x;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= W || ny[k] >= H) continue;
        const size_t j = size_t(ny[k]) * W + nx[k];
        if (s.hit(i) != s.hit(j) ||
            (s.hit(i) && std::abs(double(s.t[i]) - s.t[j]) > depth_jump * std::min(s.t[i], s.t[j])))
          edge[i] = 1;
      }
    }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!edge[size_t(y) * W + x]) continue;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < W && v < H) band[size_t(v) * W + u] = 1;
        }
    }
  return band;
}

long long maskPixels(ImageRGBA8& a, const ImageRGBA8& b, const std::vector<uint8_t>& mask) {
  if (a.px.size() != b.px.size() || mask.size() * 4 != a.px.size())
    throw InputError("compare: the mask's surface image is not the images' size");
  long long n = 0;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      std::copy_n(&b.px[4 * i], 4, &a.px[4 * i]);
      ++n;
    }
  return n;
}

ImageRGBA8 differenceImage(const ImageRGBA8& a, const ImageRGBA8& b, int gain) {
  ImageRGBA8 out(a.width, a.height);
  for (size_t i = 0; i < out.px.size(); i += 4) {
    for (int c = 0; c < 3; ++c)
      out.px[i + c] = uint8_t(std::min(255, gain * std::abs(int(a.px[i + c]) - int(b.px[i + c]))));
    out.px[i + 3] = 255;
  }
  return out;
}

ImageRGBA8 opaqueOver(const ImageF& img, const glm::dvec3& background) {
  ImageRGBA8 out(img.width, img.height);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    const float* p = &img.px[4 * i];
    for (int c = 0; c < 3; ++c) {
      float v = std::clamp(p[c] + (1.0f - p[3]) * float(background[c]), 0.0f, 1.0f);
      out.px[4 * i + c] = uint8_t(std::lround(v * 255.0f));
    }
    out.px[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace sortlast
