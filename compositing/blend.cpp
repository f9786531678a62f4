#include "compositing/blend.h"

#include <stdexcept>
#include <string>
#include <type_traits>

#include "compositing/over.h"
#include "compositing/pixel_cost.h"
#include "compositing/rle.h"

namespace sortlast {

namespace {

// The pixels of rectangle `r` (row 0 first) blended over the same pixels of a destination whose
// row stride is `dst_width` pixels and whose first pixel is frame pixel (ox, oy).
void blendRect8(const uint8_t* src, const Rect& r, uint8_t* dst, int dst_width, int ox, int oy) {
  for (int y = 0; y < r.h; ++y) {
    const uint8_t* s = src + size_t(y) * r.w * 4;
    uint8_t* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x)
      if (s[4 * x + 3] != 0) overRGBA8(s + 4 * x, d + 4 * x);
  }
}

void blendRect8(const uint8_t* src, const Rect& r, float* dst, int dst_width, int ox, int oy) {
  for (int y = 0; y < r.h; ++y) {
    const uint8_t* s = src + size_t(y) * r.w * 4;
    float* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x)
      if (s[4 * x + 3] != 0) {
        float f[4];
        for (int c = 0; c < 4; ++c) f[c] = s[4 * x + c] / 255.0f;
        overFloat(f, d + 4 * x);
      }
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

// Emission pixels (8 bytes) decoded and blended in one pass, without an intermediate float
// image: the same values and the same blends as fromEmission16 into a buffer and blendRectF.
void blendRectEmission(const uint8_t* src, const Rect& r, float* dst, int dst_width, int ox, int oy) {
  for (int y = 0; y < r.h; ++y) {
    const uint8_t* s = src + size_t(y) * r.w * 8;
    float* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x) {
      if (s[8 * x + 6] == 0 && s[8 * x + 7] == 0) continue;  // a transparent pixel (from a run)
      float f[4];
      fromEmission16(s + 8 * x, f);
      if (shows(f)) overFloat(f, d + 4 * x);
    }
  }
}

// Decodes each brick image and blends it into `dst` (a frame or a rectangle image). Brick images
// are RGBA8, or (glow scenes) WireFormat::Emission, blended in float.
template <class Pixel>
void blendBricks(const std::vector<const BrickImage*>& images, Pixel* dst, const Rect& dst_rect,
                 WireFormat format = WireFormat::RGBA8) {
  std::vector<uint8_t> pixels;
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    if (r.empty()) continue;
    if (!contains(dst_rect, r))
      throw RleError("brick " + std::to_string(b->brick_id) + ": rectangle outside the frame");
    if (!b->emission.empty()) {
      if (format != WireFormat::Emission || b->emission.size() != size_t(r.area()) * 4)
        throw std::logic_error("brick " + std::to_string(b->brick_id) + ": unencoded pixels");
      if constexpr (std::is_same_v<Pixel, float>)
        blendEmissionFloats(b->emission.data(), r, dst, dst_rect.w, dst_rect.x, dst_rect.y);
      else
        throw std::logic_error("emission brick images blend in float only");
      continue;
    }
    const int bytes = pixelBytes(format);
    chargePixels(std::is_same_v<Pixel, float> ? PixelWork::DecodeBlend8 : PixelWork::DecodeBlendInto8,
                 r.area(), bytes);
    pixels.resize(size_t(r.area()) * size_t(bytes));
    rleDecode(b->rle, size_t(r.area()), pixels, bytes);
    if (format == WireFormat::RGBA8) {
      blendRect8(pixels.data(), r, dst, dst_rect.w, dst_rect.x, dst_rect.y);
    } else if constexpr (std::is_same_v<Pixel, float>) {
      if (format != WireFormat::Emission) throw std::logic_error("brick images: RGBA8 or Emission");
      blendRectEmission(pixels.data(), r, dst, dst_rect.w, dst_rect.x, dst_rect.y);
    } else {
      throw std::logic_error("emission brick images blend in float only");
    }
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

RectImage blendBackToFront(const std::vector<const RectImage*>& layers) {
  Rect all;
  for (const RectImage* l : layers) all = unionOf(all, l->rect);
  RectImage out(all);
  chargePixels(PixelWork::Copy, all.area());  // the new image's zero fill
  for (const RectImage* l : layers) chargePixels(PixelWork::BlendFloat, l->rect.area());
  for (const RectImage* l : layers)
    if (!l->rect.empty()) blendRectF(l->px.data(), l->rect, out.px.data(), all.w, all.x, all.y);
  return out;
}

}  // namespace sortlast
