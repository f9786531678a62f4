#include "compositing/rect_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/gtc/packing.hpp>

#include "compositing/half.h"
#include "compositing/over.h"
#include "compositing/pixel_cost.h"
#include "compositing/projection_pixels.h"
#include "compositing/rle.h"

namespace sortlast {

namespace {

// Premultiplied float to RGBA16, keeping colour <= alpha (so A = 0 implies RGB = 0).
void toRGBA16(const float* in, uint8_t* out) {
  auto q = [](float v) { return uint16_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f)); };
  uint16_t v[4];
  v[3] = q(in[3]);
  for (int c = 0; c < 3; ++c) v[c] = std::min(q(in[c]), v[3]);
  for (int c = 0; c < 4; ++c) {
    out[2 * c] = uint8_t(v[c] & 0xff);
    out[2 * c + 1] = uint8_t(v[c] >> 8);
  }
}

float fromRGBA16(const uint8_t* in) {
  return float(unsigned(in[0]) | unsigned(in[1]) << 8) / 65535.0f;
}

}  // namespace

void toEmission16(const float* in, uint8_t* out) {
  uint16_t v[4] = {0, 0, 0, 0};
  if (shows(in)) {
    // 65504: the largest finite half (radiance beyond it is far past any tone map's white).
    for (int c = 0; c < 3; ++c) v[c] = halfBits(std::clamp(in[c], 0.0f, 65504.0f));
    v[3] = halfBits(-std::clamp(1.0f - in[3], 0.0f, 1.0f)) | 0x8000u;  // -T, -0 included
  }
  for (int c = 0; c < 4; ++c) {
    out[2 * c] = uint8_t(v[c] & 0xff);
    out[2 * c + 1] = uint8_t(v[c] >> 8);
  }
}

namespace {

// Every half's decoded value, as a colour and as an alpha word: glm's decoding with the
// corrupt-stream rules applied once (NaN or Inf read as 0 / opaque, never passed on), so decoding
// is a table look-up per channel instead of a branchy conversion.
struct EmissionTables {
  float colour[65536];
  float alpha[65536];
  EmissionTables() {
    auto finite = [](float x, float fallback) { return std::isfinite(x) ? x : fallback; };
    for (uint32_t h = 0; h < 65536; ++h) {
      const float x = glm::unpackHalf1x16(uint16_t(h));
      colour[h] = std::max(finite(x, 0.0f), 0.0f);
      alpha[h] = 1.0f - std::clamp(-finite(x, -0.0f), 0.0f, 1.0f);
    }
  }
};

const EmissionTables& emissionTables() {
  static const EmissionTables t;
  return t;
}

}  // namespace

void fromEmission16(const uint8_t* in, float* out) {
  uint16_t v[4];
  for (int c = 0; c < 4; ++c) v[c] = uint16_t(unsigned(in[2 * c]) | unsigned(in[2 * c + 1]) << 8);
  if (v[3] == 0) {  // a transparent pixel (from a run)
    for (int c = 0; c < 4; ++c) out[c] = 0.0f;
    return;
  }
  const EmissionTables& t = emissionTables();
  for (int c = 0; c < 3; ++c) out[c] = t.colour[v[c]];
  out[3] = t.alpha[v[3]];
}

void blendEmissionFloats(const float* src, const Rect& r, float* dst, int dst_width, int ox, int oy) {
  const EmissionTables& t = emissionTables();
  for (int y = 0; y < r.h; ++y) {
    const float* s = src + size_t(y) * r.w * 4;
    float* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x) {
      const float* p = s + 4 * x;
      if (!shows(p)) continue;
      // toEmission16's halves of a pixel that shows, then fromEmission16's tables (its alpha word
      // is non-zero: never read as a run).
      float f[4];
      for (int c = 0; c < 3; ++c) f[c] = t.colour[halfBits(std::clamp(p[c], 0.0f, 65504.0f))];
      f[3] = t.alpha[halfBits(-std::clamp(1.0f - p[3], 0.0f, 1.0f)) | 0x8000u];
      if (shows(f)) overFloat(f, d + 4 * x);
    }
  }
}

void encodeEmission(std::span<const float> px, std::vector<uint8_t>& out, uint32_t max_run) {
  if (max_run < 1 || max_run > kMaxRun)
    throw std::invalid_argument("RLE: max_run must be in [1, 2^24 - 1]");
  const size_t n = px.size() / 4, start = out.size();
  out.resize(start + n * 8);  // the most it can take: each pixel or run marker is 8 bytes
  uint8_t* o = out.data() + start;
  size_t i = 0;
  while (i < n) {
    if (shows(&px[4 * i])) {  // toEmission16 makes its alpha word non-zero: not a run
      toEmission16(&px[4 * i], o);
      o += 8;
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < n && !shows(&px[4 * j]) && j - i < max_run) ++j;
    const uint32_t run = uint32_t(j - i);
    const uint8_t marker[8] = {uint8_t(run & 0xff), uint8_t((run >> 8) & 0xff),
                               uint8_t((run >> 16) & 0xff)};
    std::memcpy(o, marker, 8);
    o += 8;
    i = j;
  }
  out.resize(size_t(o - out.data()));
}

Rect intersect(const Rect& a, const Rect& b) {
  if (a.empty() || b.empty()) return {};
  // Ends in 64 bits (x + w of a rectangle near INT_MAX overflows int); the result's corner and
  // size are no larger than the operands', so they fit in int again.
  long long x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  long long x1 = std::min(1LL * a.x + a.w, 1LL * b.x + b.w);
  long long y1 = std::min(1LL * a.y + a.h, 1LL * b.y + b.h);
  if (x1 <= x0 || y1 <= y0) return {};
  return {int(x0), int(y0), int(x1 - x0), int(y1 - y0)};
}

bool contains(const Rect& outer, const Rect& inner) {
  return !outer.empty() && !inner.empty() && inner.x >= outer.x && inner.y >= outer.y &&
         1LL * inner.x + inner.w <= 1LL * outer.x + outer.w &&
         1LL * inner.y + inner.h <= 1LL * outer.y + outer.h;
}

Rect unionOf(const Rect& a, const Rect& b) {
  if (a.empty()) return b.empty() ? Rect{} : b;
  if (b.empty()) return a;
  return unite(a, b);
}

Rect activeRect(const RectImage& img, const Rect& within) {
  const Rect r = intersect(img.rect, within);
  chargePixels(PixelWork::Scan, r.area());
  int x0 = r.x + r.w, x1 = r.x - 1, y0 = r.y + r.h, y1 = r.y - 1;
  for (int y = r.y; y < r.y + r.h; ++y) {
    const float* row = img.at(r.x, y);
    int first = -1, last = -1;
    for (int x = 0; x < r.w; ++x)
      if (shows(row + 4 * x)) {
        if (first < 0) first = x;
        last = x;
      }
    if (first < 0) continue;
    x0 = std::min(x0, r.x + first);
    x1 = std::max(x1, r.x + last);
    y0 = std::min(y0, y);
    y1 = y;
  }
  if (x1 < x0) return {};
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

RectImage crop(const RectImage& img, const Rect& r) {
  RectImage out(intersect(img.rect, r));
  chargePixels(PixelWork::Copy, out.rect.area());
  for (int y = out.rect.y; y < out.rect.y + out.rect.h; ++y)
    std::memcpy(out.at(out.rect.x, y), img.at(out.rect.x, y),
                size_t(out.rect.w) * 4 * sizeof(float));
  return out;
}

BrickImage encodePart(const RectImage& img, const Rect& part, int id, WireFormat format, bool rle) {
  BrickImage b;
  b.brick_id = id;
  b.rect = activeRect(img, part);
  if (b.rect.empty()) return b;
  const size_t bytes = size_t(pixelBytes(format));
  chargePixels(PixelWork::Encode, b.rect.area(), int(bytes));
  std::vector<uint8_t> px(size_t(b.rect.area()) * bytes);
  uint8_t* o = px.data();
  for (int y = b.rect.y; y < b.rect.y + b.rect.h; ++y) {
    const float* row = img.at(b.rect.x, y);
    for (int x = 0; x < b.rect.w; ++x, o += bytes)
      if (format == WireFormat::RGBA8)
        toRGBA8(row + 4 * x, o);
      else if (format == WireFormat::Emission)
        toEmission16(row + 4 * x, o);
      else if (isProjection(format))
        toProjected(format, row + 4 * x, o);
      else
        toRGBA16(row + 4 * x, o);
  }
  b.rle = rleEncode(px, int(bytes), rle ? kMaxRun : 1);
  return b;
}

RawPart rawFinalPart(const RectImage& img, const Rect& bound, WireFormat format) {
  RawPart out;
  out.rect = bound;
  if (bound.empty()) return out;
  if (!img.rect.empty() && !contains(bound, img.rect))
    throw std::logic_error("final part: the composite lies outside its part of the frame");
  const size_t n = size_t(bound.area());
  chargePixels(PixelWork::Fill8, bound.area());  // the zero fill of the new buffer
  out.rgba8.assign(n * 4, 0);
  if (isProjection(format))
    throw std::logic_error("final part: a projection's parts are coloured before they are made");
  const bool exact = format != WireFormat::RGBA8;
  if (exact) {
    chargePixels(PixelWork::Copy, bound.area());  // the float buffer's zero fill
    out.exact.assign(n * 16, 0);                  // all-zero bytes: 0.0f
  }
  const Rect& r = img.rect;
  if (exact) {  // through the wire format and back, as the RLE path's encode and decode
    chargePixels(PixelWork::Encode, r.area(), 8);
    chargePixels(PixelWork::Decode, r.area(), 8);
  }
  chargePixels(PixelWork::Round8, r.area());
  for (int y = r.y; y < r.y + r.h; ++y) {
    const float* src = img.at(r.x, y);
    const size_t o = size_t(y - bound.y) * size_t(bound.w) + size_t(r.x - bound.x);
    for (int x = 0; x < r.w; ++x) {
      const float* p = src + 4 * x;
      uint8_t* d8 = &out.rgba8[4 * (o + size_t(x))];
      if (!exact) {
        toRGBA8(p, d8);
        continue;
      }
      float d[4];
      uint8_t wire[8];
      if (format == WireFormat::Emission) {
        toEmission16(p, wire);
        fromEmission16(wire, d);
      } else {
        toRGBA16(p, wire);
        for (int c = 0; c < 4; ++c) d[c] = fromRGBA16(wire + 2 * c);
      }
      toRGBA8(d, d8);
      std::memcpy(&out.exact[16 * (o + size_t(x))], d, 16);
    }
  }
  return out;
}

RectImage decodePart(const BrickImage& b, WireFormat format, const Rect& within) {
  if (b.rect.empty()) {
    if (!b.rle.empty()) throw RleError("image part: empty rectangle with a non-empty stream");
    return {};
  }
  if (!contains(within, b.rect))
    throw RleError("image part: rectangle outside the region it belongs to");
  const int bytes = pixelBytes(format);
  chargePixels(PixelWork::Decode, b.rect.area(), bytes);
  std::vector<uint8_t> px(size_t(b.rect.area()) * size_t(bytes));
  rleDecode(b.rle, size_t(b.rect.area()), px, bytes);
  RectImage out(b.rect);
  if (format == WireFormat::Emission)
    for (size_t i = 0; i < size_t(b.rect.area()); ++i) fromEmission16(&px[8 * i], &out.px[4 * i]);
  else if (isProjection(format))
    for (size_t i = 0; i < size_t(b.rect.area()); ++i) fromProjected(format, &px[size_t(bytes) * i], &out.px[4 * i]);
  else if (format == WireFormat::RGBA16)
    for (size_t i = 0; i < out.px.size(); ++i) out.px[i] = fromRGBA16(&px[2 * i]);
  else
    for (size_t i = 0; i < out.px.size(); ++i) out.px[i] = px[i] / 255.0f;
  return out;
}

void pastePart(const RectImage& part, ImageF& frame) {
  const Rect& r = part.rect;
  if (r.empty()) return;
  if (!contains(Rect{0, 0, frame.width, frame.height}, r))
    throw RleError("image part: rectangle outside the frame");
  chargePixels(PixelWork::Copy, r.area());
  for (int y = 0; y < r.h; ++y)
    std::memcpy(&frame.px[(size_t(r.y + y) * frame.width + size_t(r.x)) * 4], part.at(r.x, r.y + y),
                size_t(r.w) * 4 * sizeof(float));
}

void pastePart(const BrickImage& b, ImageRGBA8& frame) {
  const Rect& r = b.rect;
  if (r.empty()) {
    if (!b.rle.empty()) throw RleError("image part: empty rectangle with a non-empty stream");
    return;
  }
  if (!contains(Rect{0, 0, frame.width, frame.height}, r))
    throw RleError("image part: rectangle outside the frame");
  chargePixels(PixelWork::DecodeRGBA8, r.area());
  std::vector<uint8_t> px(size_t(r.area()) * 4);
  rleDecode(b.rle, size_t(r.area()), px);
  for (int y = 0; y < r.h; ++y)
    std::memcpy(frame.at(r.x, r.y + y), &px[size_t(y) * r.w * 4], size_t(r.w) * 4);
}

}  // namespace sortlast
