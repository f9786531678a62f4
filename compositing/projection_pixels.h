#pragma once
// Partial images of the projection blend modes (render.blend: mip, minip, average, additive): what
// a ray's samples leave in one brick, combined with other bricks' by an order-free operator, so
// every strategy may group the partial images any way it likes (no visibility order needed).
//
// In float (RectImage, ImageF, a brick's float pixels) a projected pixel is four floats:
//   ValueMax / ValueMin (mip / minip): (v, 0, 0, 1) where a sample was taken, v its largest /
//     smallest value; (0, 0, 0, 0) where none was (the pixel is "absent": no sample reached it).
//   ValueSum (average): (sum of the values, 0, 0, count of the samples); absent: zero count.
//   Additive: premultiplied (sum c_i alpha_i, sum alpha_i); absent: all zero.
// combine() is the operator: max / min of v between present pixels (an absent one is the
// identity), or the channel-wise sum. All are associative and commutative, up to float rounding
// for the sums (about 2^-24 relative a sum).
//
// On the wire, 8 bytes a pixel (12 for two bounded formats, below; RLE-coded as RGBA16 is: a pixel whose bytes 6 and 7 are zero is
// a run of absent pixels, rle.h):
//   ValueMax, ValueMin, ValueSum: float32 v (or the sum) in bytes 0-3, and float32 -w in bytes
//     4-7, w = 1 (mip, minip) or the count (average). A present pixel has w > 0, so byte 7 holds
//     the sign bit: never 0, never read as a run. Exact: no rounding at all, so a value travels
//     bit for bit and the transfer function sees the same float on every rank count.
//   Additive: four IEEE halves (compositing/half.h): rgb sums and -alpha (the sign bit set, so the
//     alpha word is never 0 on a pixel that shows). 2^-11 relative per rounding; the sums are
//     clamped to 65504.
// The colouring through the transfer function happens once, on the final value (Compositor's
// CompositeOptions::colour_projection).
//
// Bounded by an opaque layer (particles or subdivision surfaces in the frame): ValueMaxBounded and
// ValueMinBounded. A brick's rays stop at its own opaque layer (the ray caster's per-brick surface
// t), but samples in a brick behind another brick's surface must not count either, and the
// layer's colour must reach the frame. So the pixel carries the layer's colour, and combine() is
// over-like, in visibility order (every strategy blends back to front; `src` is in front of
// `dst`): a front pixel with an opaque layer replaces what lies behind it; one without combines
// its value with the one behind (max / min) and keeps the layer behind. Associative, not
// commutative: grouped any way the order allows, every strategy gives the same pixels, exactly.
//   In float: (v, s, 0, flags), flags = 1 (a value v was taken) + 2 (an opaque layer whose
//     colour is s = r + 256 g + 65536 b, its 8-bit rgb, exact in float; its alpha is 1); 0: absent.
//   On the wire (8 bytes, exact): float32 v (0 without a value), the layer's r, g, b bytes, and a
//     flags byte (0x80: a value; 0x01: a layer), never 0 on a present pixel: byte 7 marks runs.
//   ValueSumBounded (average): in float (sum, s, count, flags), s and flags as above (flags 1:
//     count > 0). On the wire 12 bytes, exact: float32 sum, float32 count, the layer's r, g, b, flags.
//   AdditiveBounded: four sums and the layer do not fit four floats as floats, so each float holds
//     an integer below 2^24 (exact): p[k] = h_k + 65536 l_k, h_k the IEEE half bits of the sum k
//     (r, g, b, alpha: the wire's own rounding, 2^-11 relative, compositing/half.h), l_k the layer's
//     8-bit r, g, b for k < 3 and the flags for k = 3 (so p[3] > 0 on a present pixel). combine()
//     adds the halves in float and rounds once to half. On the wire 12 bytes: the four halves, the
//     layer's r, g, b, flags.
// The last byte of every bounded pixel on the wire is its flags, never 0 on a present pixel: a
// run is marked by zero last bytes (rle.h), 2 of 8 or 3 of 12.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "compositing/rect_image.h"

namespace sortlast {

inline bool isBoundedProjection(WireFormat f) {
  return f == WireFormat::ValueMaxBounded || f == WireFormat::ValueMinBounded ||
         f == WireFormat::ValueSumBounded || f == WireFormat::AdditiveBounded;
}
inline bool isProjection(WireFormat f) {
  return f == WireFormat::ValueMax || f == WireFormat::ValueMin || f == WireFormat::ValueSum ||
         f == WireFormat::Additive || isBoundedProjection(f);
}

// The bounded formats' float flags and the layer's packed colour (r + 256 g + 65536 b).
inline constexpr float kBoundedValue = 1.0f, kBoundedLayer = 2.0f;
// Flags (1: a value, 2: a layer) of a bounded float pixel: p[3], or p[3]'s high bits (additive).
inline int boundedFlags(WireFormat f, const float* p) {
  return f == WireFormat::AdditiveBounded ? int(uint32_t(p[3]) >> 16) : int(p[3]);
}
inline bool boundedHasValue(WireFormat f, const float* p) { return (boundedFlags(f, p) & 1) != 0; }
inline bool boundedHasLayer(WireFormat f, const float* p) { return (boundedFlags(f, p) & 2) != 0; }
// The layer's 8-bit rgb packed as r + 256 g + 65536 b (0 without a layer).
inline uint32_t boundedLayer(WireFormat f, const float* p) {
  if (f != WireFormat::AdditiveBounded) return uint32_t(p[1]);
  return (uint32_t(p[0]) >> 16) | (uint32_t(p[1]) >> 16) << 8 | (uint32_t(p[2]) >> 16) << 16;
}
// AdditiveBounded: the four sums of a float pixel (0 where a half is not finite, a corrupt one),
// and the pixel of sums `sum`, layer `layer` and flags `flags` (each sum rounded to half).
void additiveBoundedSums(const float* p, float* sum);
void packAdditiveBounded(const float* sum, uint32_t layer, int flags, float* p);

// dst = dst (op) src, in float, for projection format `f`.
inline void combineProjected(WireFormat f, const float* src, float* dst) {
  if (isBoundedProjection(f)) {  // src in front of dst
    if (boundedHasLayer(f, src)) {  // the front layer hides all behind it
      for (int c = 0; c < 4; ++c) dst[c] = src[c];
      return;
    }
    if (!boundedHasValue(f, src)) return;  // absent: the identity
    const bool back_layer = boundedHasLayer(f, dst);
    const float flags = kBoundedValue + (back_layer ? kBoundedLayer : 0.0f);
    if (f == WireFormat::AdditiveBounded) {  // the sums add; the layer behind stays
      float a[4], b[4];
      additiveBoundedSums(src, a);
      additiveBoundedSums(dst, b);
      for (int c = 0; c < 4; ++c) b[c] += a[c];
      packAdditiveBounded(b, boundedLayer(f, dst), int(flags), dst);
      return;
    }
    if (f == WireFormat::ValueSumBounded) {  // (sum, layer, count, flags): sum and count add
      dst[0] += src[0];
      dst[2] += src[2];
    } else if (!boundedHasValue(f, dst)) {
      dst[0] = src[0];
    } else {
      dst[0] = f == WireFormat::ValueMaxBounded ? (src[0] > dst[0] ? src[0] : dst[0])
                                                : (src[0] < dst[0] ? src[0] : dst[0]);
    }
    dst[3] = flags;
    return;
  }
  if (f == WireFormat::ValueMax || f == WireFormat::ValueMin) {
    if (!(src[3] > 0.0f)) return;  // absent: the identity
    if (!(dst[3] > 0.0f)) {
      for (int c = 0; c < 4; ++c) dst[c] = src[c];
      return;
    }
    dst[0] = f == WireFormat::ValueMax ? (src[0] > dst[0] ? src[0] : dst[0])
                                       : (src[0] < dst[0] ? src[0] : dst[0]);
    return;
  }
  for (int c = 0; c < 4; ++c) dst[c] += src[c];
}

// Whether a float projected pixel is present (encodes as a pixel, not a run).
inline bool projectedPresent(WireFormat f, const float* p) {
  return f == WireFormat::Additive ? shows(p) : p[3] > 0.0f;
}

// One float pixel to / from the wire (pixelBytes(f): 8 or 12 bytes). toProjected of an absent pixel writes zeros; a
// corrupt pixel (non-finite, or w <= 0 for the value formats) decodes as absent.
void toProjected(WireFormat f, const float* in, uint8_t* out);
void fromProjected(WireFormat f, const uint8_t* in, float* out);

// Float pixels (4 a pixel, row 0 first) to format `f` and RLE in one pass, appended to `out`
// (an absent pixel is part of a run).
void encodeProjected(WireFormat f, std::span<const float> px, std::vector<uint8_t>& out,
                     uint32_t max_run);

// `n` wire pixels, all present (a stretch between runs), decoded and combined into `d`.
void combineWireRow(WireFormat f, const uint8_t* s, size_t n, float* d);
// Float rectangle `r` of `src` combined into `dst` (dst_width wide, pixel (0, 0) at (ox, oy)).
void combineRectF(WireFormat f, const float* src, const Rect& r, float* dst, int dst_width, int ox,
                  int oy);

}  // namespace sortlast
