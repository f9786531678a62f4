#include "compositing/blend.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/pixel_threads.h"
#include "compositing/over.h"
#include "compositing/pixel_cost.h"
#include "compositing/projection_pixels.h"
#include "compositing/rle.h"

namespace sortlast {

namespace {

// Pixels a thread blends at least: 32 K pixels, about 0.04 ms of decode and blend on one core of
// the 2-core development machine (bench/pixels: 4.45 ms for 4 M pixels). Not tuned by a sweep.
constexpr size_t kBlendGrain = size_t(1) << 15;

// One row segment of `n` visible pixels blended over `d`. The pixels come from a stretch of
// visible pixels in an RLE stream (every alpha non-zero, or for Emission an alpha word non-zero),
// so the kernels need no test for runs and the RGBA8 ones vectorise.
inline void blendRow8(const uint8_t* s, size_t n, uint8_t* d) {
  for (size_t x = 0; x < n; ++x) overRGBA8(s + 4 * x, d + 4 * x);
}

inline void blendRow8(const uint8_t* s, size_t n, float* d) {
  for (size_t x = 0; x < n; ++x) {
    float f[4];
    for (int c = 0; c < 4; ++c) f[c] = s[4 * x + c] / 255.0f;
    overFloat(f, d + 4 * x);
  }
}

// Emission pixels (8 bytes) decoded and blended in one pass: the same values and the same blends
// as fromEmission16 into a buffer and blending the pixels that show.
inline void blendRowEmission(const uint8_t* s, size_t n, float* d) {
  for (size_t x = 0; x < n; ++x) {
    float f[4];
    fromEmission16(s + 8 * x, f);
    if (shows(f)) overFloat(f, d + 4 * x);
  }
}

void blendRectF(const float* src, const Rect& r, float* dst, int dst_width, int ox, int oy) {
  for (int y = 0; y < r.h; ++y) {
    const float* s = src + size_t(y) * r.w * 4;
    float* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x)
      if (shows(s + 4 * x)) overFloat(s + 4 * x, d + 4 * x);
  }
}

// f(band) over bands of whole rows of `r` (the same rectangle, fewer rows), in parallel: bands are
// disjoint in the destination, and every pixel gets the same blends in the same order.
template <class F>
void forRowBands(const Rect& r, F&& f) {
  const size_t rows = size_t(r.h);
  const size_t rows_per_grain = std::max<size_t>(1, kBlendGrain / size_t(std::max(r.w, 1)));
  parallelFor(rows, rows_per_grain, [&](size_t b, size_t e) {
    f(Rect{r.x, r.y + int(b), r.w, int(e - b)});
  });
}

// A brick image's RLE stream decoded straight into the blend: each stretch of visible pixels is
// blended where it lands, runs are skipped (over a transparent pixel changes nothing, and the
// serial code skipped them too), so there is no decoded copy of the image. The stream is checked
// whole (rleSplit) before a pixel is blended, as decoding it first did; its pieces are blended in
// parallel (they cover disjoint pixels).
template <class Pixel>
void decodeBlend(const BrickImage& b, int bytes, WireFormat format, Pixel* dst, const Rect& dst_rect) {
  const Rect& r = b.rect;
  const std::vector<RlePiece> pieces =
      rleSplit(b.rle, size_t(r.area()), bytes, pixelParts(size_t(r.area()), kBlendGrain));
  const size_t w = size_t(r.w);
  parallelParts(int(pieces.size()), [&](int p) {
    rleVisit(
        b.rle, pieces[size_t(p)], bytes,
        [&](size_t o, const uint8_t* s, size_t n) {
          while (n > 0) {  // the stretch cut at the ends of the rectangle's rows
            const size_t y = o / w, x = o % w, len = std::min(n, w - x);
            Pixel* d = dst + (size_t(r.y - dst_rect.y) + y) * size_t(dst_rect.w) * 4 +
                       (size_t(r.x - dst_rect.x) + x) * 4;
            if constexpr (std::is_same_v<Pixel, float>) {
              if (format == WireFormat::Emission)
                blendRowEmission(s, len, d);
              else if (isProjection(format))
                combineWireRow(format, s, len, d);
              else
                blendRow8(s, len, d);
            } else {
              blendRow8(s, len, d);
            }
            s += len * size_t(bytes);
            o += len;
            n -= len;
          }
        },
        [](size_t, size_t) {});
  });
}

// Decodes each brick image and blends it into `dst` (a frame or a rectangle image). Brick images
// are RGBA8, or (glow scenes) WireFormat::Emission, blended in float.
template <class Pixel>
void blendBricks(const std::vector<const BrickImage*>& images, Pixel* dst, const Rect& dst_rect,
                 WireFormat format = WireFormat::RGBA8) {
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    if (r.empty()) continue;
    if (!contains(dst_rect, r))
      throw RleError("brick " + std::to_string(b->brick_id) + ": rectangle outside the frame");
    if (!b->emission.empty()) {
      if (format != WireFormat::Emission || b->emission.size() != size_t(r.area()) * 4)
        throw std::logic_error("brick " + std::to_string(b->brick_id) + ": unencoded pixels");
      if constexpr (std::is_same_v<Pixel, float>)
        forRowBands(r, [&](const Rect& band) {
          blendEmissionFloats(b->emission.data() + size_t(band.y - r.y) * size_t(r.w) * 4, band,
                              dst, dst_rect.w, dst_rect.x, dst_rect.y);
        });
      else
        throw std::logic_error("emission brick images blend in float only");
      continue;
    }
    const int bytes = pixelBytes(format);
    chargePixels(std::is_same_v<Pixel, float> ? PixelWork::DecodeBlend8 : PixelWork::DecodeBlendInto8,
                 r.area(), bytes);
    if (format != WireFormat::RGBA8) {
      if (format != WireFormat::Emission && !isProjection(format))
        throw std::logic_error("brick images: RGBA8, Emission or a projection format");
      if constexpr (!std::is_same_v<Pixel, float>)
        throw std::logic_error("emission brick images blend in float only");
    }
    decodeBlend(*b, bytes, format, dst, dst_rect);
  }
}

}  // namespace

void blendBackToFront(const std::vector<const BrickImage*>& images, ImageRGBA8& frame) {
  blendBricks(images, frame.px.data(), Rect{0, 0, frame.width, frame.height});
}

void blendBackToFront(const std::vector<const BrickImage*>& images, ImageF& frame, WireFormat format) {
  blendBricks(images, frame.px.data(), Rect{0, 0, frame.width, frame.height}, format);
}

RectImage blendBackToFront(const std::vector<const BrickImage*>& images, WireFormat format) {
  Rect all;
  for (const BrickImage* b : images) all = unionOf(all, b->rect);
  RectImage out(all);
  chargePixels(PixelWork::Copy, all.area());  // the new image's zero fill
  blendBricks(images, out.px.data(), all, format);
  return out;
}

RectImage blendBackToFront(const std::vector<const RectImage*>& layers, WireFormat format) {
  Rect all;
  for (const RectImage* l : layers) all = unionOf(all, l->rect);
  RectImage out(all);
  chargePixels(PixelWork::Copy, all.area());  // the new image's zero fill
  for (const RectImage* l : layers) chargePixels(PixelWork::BlendFloat, l->rect.area());
  for (const RectImage* l : layers)
    if (!l->rect.empty())
      forRowBands(l->rect, [&](const Rect& band) {
        if (isProjection(format))
          combineRectF(format, l->at(band.x, band.y), band, out.px.data(), all.w, all.x, all.y);
        else
          blendRectF(l->at(band.x, band.y), band, out.px.data(), all.w, all.x, all.y);
      });
  return out;
}

}  // namespace sortlast
