#pragma once
// Image operations of the swap strategies, apart from blending (IceT's layout): a partial
// composite held as a float image of one rectangle of the frame; cropping it, finding its active
// (not transparent) pixels, and packaging a part of it for the wire (rectangle + RLE stream).
//
// Partial composites travel as RGBA16 (four little-endian uint16 per pixel): blending in float
// and rounding only to 1/65535 between rounds keeps every grouping of the blends within a few
// thousandths of an 8-bit step of the exact result, so every strategy rounds the frame to the
// same RGBA8 value within 1 (RGBA8 partials would add up to half a step per round). The finished
// parts sent to rank 0 are final values and travel as RGBA8.
#include <cstdint>
#include <span>
#include <vector>

#include "common/camera.h"
#include "io/image.h"
#include "compositing/brick_image.h"

namespace sortlast {

struct RectImage {
  Rect rect;              // in frame pixels; empty: no pixels
  std::vector<float> px;  // rect.w * rect.h premultiplied RGBA pixels, row 0 first
  RectImage() = default;
  explicit RectImage(const Rect& r) : rect(r), px(size_t(r.area()) * 4, 0.0f) {}  // transparent
  // Pixel (x, y) in frame coordinates.
  float* at(int x, int y) { return &px[(size_t(y - rect.y) * rect.w + size_t(x - rect.x)) * 4]; }
  const float* at(int x, int y) const {
    return &px[(size_t(y - rect.y) * rect.w + size_t(x - rect.x)) * 4];
  }
};

Rect intersect(const Rect& a, const Rect& b);  // an empty rectangle if they do not overlap
// Whether non-empty `inner` lies inside `outer`. In 64 bits: a rectangle from a message may hold
// any int32, and x + w could overflow int.
bool contains(const Rect& outer, const Rect& inner);
Rect unionOf(const Rect& a, const Rect& b);    // bounding rectangle; empty operands are ignored

// Bounding rectangle of the pixels with A > 0 inside `within` (empty if there are none).
Rect activeRect(const RectImage& img, const Rect& within);
// The pixels of `img` inside `r` (which is clipped to img.rect).
RectImage crop(const RectImage& img, const Rect& r);

// Emission: scenes with glow (docs/glow.md), whose pixels carry light without opacity (colour
// above alpha, and above 1 before the final tone map). Four IEEE half floats: premultiplied rgb
// unclamped (up to 65504) and the transmittance T = 1 - alpha stored negated, so the alpha word
// is never 0 on a pixel that shows anything (the RLE marks runs by A = 0) and T keeps its relative
// precision (2^-11) near 0, where it dims bright glow behind dense material.
// ValueMax, ValueMin, ValueSum, Additive: the projection blend modes' partial images
// (compositing/projection_pixels.h), combined by max, min or sum instead of over;
// ValueMaxBounded, ValueMinBounded, ValueSumBounded, AdditiveBounded: the four bounded by an
// opaque layer, which carry it; the last two need 12 bytes a pixel (a sum and a count, or four
// sums, and the layer's rgb and flags).
enum class WireFormat { RGBA8, RGBA16, Emission, ValueMax, ValueMin, ValueSum, Additive, ValueMaxBounded,
                        ValueMinBounded, ValueSumBounded, AdditiveBounded };
inline int pixelBytes(WireFormat f) {
  if (f == WireFormat::RGBA8) return 4;
  return f == WireFormat::ValueSumBounded || f == WireFormat::AdditiveBounded ? 12 : 8;
}

// Whether a float pixel shows anything: alpha > 0, or (emission) light without opacity. Without
// emission colour <= alpha, so this is alpha > 0.
inline bool shows(const float* p) { return p[3] > 0.0f || p[0] > 0.0f || p[1] > 0.0f || p[2] > 0.0f; }

// One premultiplied float pixel to / from the Emission wire format (8 bytes).
void toEmission16(const float* in, uint8_t* out);
void fromEmission16(const uint8_t* in, float* out);
// Float pixels (RGBA, premultiplied) to the Emission format and RLE in one pass, appended to
// `out`: the same bytes as toEmission16 on each pixel and then rleEncode(..., 8, max_run), without
// the intermediate buffer (a transparent pixel is one that does not show).
void encodeEmission(std::span<const float> px, std::vector<uint8_t>& out, uint32_t max_run);
// Float pixels of rectangle `r` (RGBA, premultiplied, row 0 first) blended over `dst` (a float
// image dst_width wide whose pixel (0, 0) is at (ox, oy)) as their encoding would be: a pixel
// that does not show is a run (skipped); one that shows is rounded to the Emission format's halves
// and back (toEmission16 then fromEmission16, the same bits) and, if it still shows, blended over.
void blendEmissionFloats(const float* src, const Rect& r, float* dst, int dst_width, int ox, int oy);

// `img`'s pixels inside `part`, shrunk to their active rectangle, rounded to `format` and
// RLE-encoded (`rle` false: with runs of 1, as long as the raw pixels); `id` goes into the brick
// id field. A transparent part gives an empty rectangle and no bytes.
BrickImage encodePart(const RectImage& img, const Rect& part, int id, WireFormat format,
                      bool rle = true);
// Decodes a part sent in `format`, which must lie inside `within` (what the receiver expects:
// checked before allocating, so a corrupt rectangle cannot ask for gigabytes). Throws RleError if
// malformed or outside `within`.
RectImage decodePart(const BrickImage& b, WireFormat format, const Rect& within);
// A final part of the frame as rank 0's frame will hold it, raw (no RLE, no header), so that rank 0
// only has to put it in place: every pixel of `bound` (which must contain img.rect: throws
// std::logic_error otherwise), row 0 first, zero outside img.rect. `rgba8`: 4 bytes a pixel, the
// bytes encodePart(format RGBA8) and pastePart give. With `exact` (format RGBA16 or Emission, for
// a float frame), also `exact`: 4 floats a pixel (16 bytes), each pixel rounded to `format` and
// decoded back as decodePart would, and `rgba8` that float pixel rounded to RGBA8 as toRGBA8(ImageF)
// would. Done where the part was composited, so rank 0 decodes nothing.
struct RawPart {
  Rect rect;
  std::vector<uint8_t> rgba8;
  std::vector<uint8_t> exact;  // empty for format RGBA8
};
RawPart rawFinalPart(const RectImage& img, const Rect& bound, WireFormat format);
// Decodes an RGBA8 part into `frame` (a plain copy: parts do not overlap). Throws RleError if
// malformed or outside the frame.
void pastePart(const BrickImage& b, ImageRGBA8& frame);
// Copies a decoded part into a float frame. Throws RleError if it lies outside the frame.
void pastePart(const RectImage& part, ImageF& frame);

}  // namespace sortlast
