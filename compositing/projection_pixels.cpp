#include "compositing/projection_pixels.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <glm/gtc/packing.hpp>

#include "compositing/half.h"
#include "compositing/rle.h"

namespace sortlast {

void additiveBoundedSums(const float* p, float* sum) {
  for (int c = 0; c < 4; ++c) {
    const float x = glm::unpackHalf1x16(uint16_t(uint32_t(p[c]) & 0xffffu));
    sum[c] = std::isfinite(x) ? std::max(x, 0.0f) : 0.0f;
  }
}

void packAdditiveBounded(const float* sum, uint32_t layer, int flags, float* p) {
  const uint32_t high[4] = {layer & 0xffu, (layer >> 8) & 0xffu, (layer >> 16) & 0xffu, uint32_t(flags) & 0xffu};
  for (int c = 0; c < 4; ++c)
    p[c] = float(uint32_t(halfBits(std::clamp(sum[c], 0.0f, 65504.0f))) + 65536u * high[c]);
}

namespace {

// The layer's rgb and the flags byte of a bounded pixel's wire form, at `out` (4 bytes).
void putLayerAndFlags(WireFormat f, const float* in, uint8_t* out) {
  const bool value = boundedHasValue(f, in), layer = boundedHasLayer(f, in);
  if (layer) {
    const uint32_t s = std::min(boundedLayer(f, in), 16777215u);
    out[0] = uint8_t(s & 0xff), out[1] = uint8_t((s >> 8) & 0xff), out[2] = uint8_t(s >> 16);
  }
  out[3] = uint8_t((value ? 0x80 : 0) | (layer ? 0x01 : 0));
}

}  // namespace

void toProjected(WireFormat f, const float* in, uint8_t* out) {
  std::memset(out, 0, size_t(pixelBytes(f)));
  if (!projectedPresent(f, in)) return;
  if (f == WireFormat::ValueSumBounded) {  // float32 sum, float32 count, rgb, flags
    if (boundedHasValue(f, in)) std::memcpy(out, &in[0], 4), std::memcpy(out + 4, &in[2], 4);
    putLayerAndFlags(f, in, out + 8);
    return;
  }
  if (f == WireFormat::AdditiveBounded) {  // four halves, rgb, flags
    for (int c = 0; c < 4; ++c) {
      const uint32_t h = uint32_t(in[c]) & 0xffffu;
      out[2 * c] = uint8_t(h & 0xff), out[2 * c + 1] = uint8_t(h >> 8);
    }
    putLayerAndFlags(f, in, out + 8);
    return;
  }
  if (isBoundedProjection(f)) {
    const bool value = boundedHasValue(f, in), layer = boundedHasLayer(f, in);
    if (value) std::memcpy(out, &in[0], 4);
    if (layer) {
      const uint32_t s = uint32_t(std::clamp(in[1], 0.0f, 16777215.0f));
      out[4] = uint8_t(s & 0xff), out[5] = uint8_t((s >> 8) & 0xff), out[6] = uint8_t(s >> 16);
    }
    out[7] = uint8_t((value ? 0x80 : 0) | (layer ? 0x01 : 0));
    return;
  }
  if (f == WireFormat::Additive) {
    uint16_t v[4];
    for (int c = 0; c < 3; ++c) v[c] = halfBits(std::clamp(in[c], 0.0f, 65504.0f));
    v[3] = uint16_t(halfBits(std::clamp(in[3], 0.0f, 65504.0f)) | 0x8000u);  // -alpha, -0 included
    for (int c = 0; c < 4; ++c) {
      out[2 * c] = uint8_t(v[c] & 0xff);
      out[2 * c + 1] = uint8_t(v[c] >> 8);
    }
    return;
  }
  const float w = -in[3];  // < 0: the sign bit lands in byte 7 (little-endian)
  std::memcpy(out, &in[0], 4);
  std::memcpy(out + 4, &w, 4);
}

void fromProjected(WireFormat f, const uint8_t* in, float* out) {
  for (int c = 0; c < 4; ++c) out[c] = 0.0f;
  if (rleIsRun(in, pixelBytes(f))) return;  // a run's pixel: absent
  if (f == WireFormat::ValueSumBounded || f == WireFormat::AdditiveBounded) {
    const bool layer = in[11] & 0x01;
    bool value = in[11] & 0x80;
    const uint32_t s = uint32_t(in[8]) | uint32_t(in[9]) << 8 | uint32_t(in[10]) << 16;
    if (f == WireFormat::ValueSumBounded) {
      float sum, count;
      std::memcpy(&sum, in, 4);
      std::memcpy(&count, in + 4, 4);
      value = value && std::isfinite(sum) && std::isfinite(count) && count > 0.0f;  // corrupt: none
      if (value) out[0] = sum, out[2] = count;
      if (layer) out[1] = float(s);
      out[3] = (value ? kBoundedValue : 0.0f) + (layer ? kBoundedLayer : 0.0f);
      return;
    }
    float sum[4] = {0, 0, 0, 0};
    if (value) {
      float h[4];
      for (int c = 0; c < 4; ++c) h[c] = float(uint32_t(in[2 * c]) | uint32_t(in[2 * c + 1]) << 8);
      additiveBoundedSums(h, sum);  // a non-finite half (corrupt) reads as 0
    }
    packAdditiveBounded(sum, layer ? s : 0u, (value ? 1 : 0) | (layer ? 2 : 0), out);
    return;
  }
  if (isBoundedProjection(f)) {
    const bool value = in[7] & 0x80, layer = in[7] & 0x01;
    float v;
    std::memcpy(&v, in, 4);
    if (value && std::isfinite(v)) out[0] = v, out[3] += kBoundedValue;  // corrupt v: no value
    if (layer) {
      out[1] = float(uint32_t(in[4]) | uint32_t(in[5]) << 8 | uint32_t(in[6]) << 16);
      out[3] += kBoundedLayer;
    }
    return;
  }
  if (f == WireFormat::Additive) {
    for (int c = 0; c < 4; ++c) {
      const uint16_t h = uint16_t(unsigned(in[2 * c]) | unsigned(in[2 * c + 1]) << 8);
      float x = glm::unpackHalf1x16(c == 3 ? uint16_t(h & 0x7fffu) : h);
      out[c] = std::isfinite(x) ? std::max(x, 0.0f) : 0.0f;
    }
    return;
  }
  float v, w;
  std::memcpy(&v, in, 4);
  std::memcpy(&w, in + 4, 4);
  w = -w;
  if (!std::isfinite(v) || !std::isfinite(w) || !(w > 0.0f)) return;  // corrupt: absent
  out[0] = v;
  out[3] = w;
}

void encodeProjected(WireFormat f, std::span<const float> px, std::vector<uint8_t>& out,
                     uint32_t max_run) {
  if (!isProjection(f)) throw std::logic_error("encodeProjected: not a projection format");
  if (max_run < 1 || max_run > kMaxRun)
    throw std::invalid_argument("RLE: max_run must be in [1, 2^24 - 1]");
  const size_t n = px.size() / 4, start = out.size(), bytes = size_t(pixelBytes(f));
  out.resize(start + n * bytes);
  uint8_t* o = out.data() + start;
  size_t i = 0;
  while (i < n) {
    if (projectedPresent(f, &px[4 * i])) {
      toProjected(f, &px[4 * i], o);
      o += bytes;
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < n && !projectedPresent(f, &px[4 * j]) && j - i < max_run) ++j;
    const uint32_t run = uint32_t(j - i);
    const uint8_t marker[12] = {uint8_t(run & 0xff), uint8_t((run >> 8) & 0xff),
                                uint8_t((run >> 16) & 0xff)};
    std::memcpy(o, marker, bytes);
    o += bytes;
    i = j;
  }
  out.resize(size_t(o - out.data()));
}

void combineWireRow(WireFormat f, const uint8_t* s, size_t n, float* d) {
  const size_t bytes = size_t(pixelBytes(f));
  for (size_t x = 0; x < n; ++x) {
    float p[4];
    fromProjected(f, s + bytes * x, p);
    combineProjected(f, p, d + 4 * x);
  }
}

void combineRectF(WireFormat f, const float* src, const Rect& r, float* dst, int dst_width, int ox,
                  int oy) {
  for (int y = 0; y < r.h; ++y) {
    const float* s = src + size_t(y) * r.w * 4;
    float* d = dst + (size_t(r.y - oy + y) * dst_width + size_t(r.x - ox)) * 4;
    for (int x = 0; x < r.w; ++x) combineProjected(f, s + 4 * x, d + 4 * x);
  }
}

}  // namespace sortlast
