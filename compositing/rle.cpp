#include "compositing/rle.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace sortlast {

namespace {

// Pixels of B bytes; alpha is the last B / 4 bytes.
template <size_t B>
bool transparent(const uint8_t* p) {
  for (size_t i = B - B / 4; i < B; ++i)
    if (p[i] != 0) return false;
  return true;
}

template <size_t B>
void encode(std::span<const uint8_t> px, std::vector<uint8_t>& out, uint32_t max_run) {
  const size_t n = px.size() / B;
  size_t i = 0;
  while (i < n) {
    if (!transparent<B>(&px[B * i])) {
      // Copy the whole stretch of visible pixels at once.
      size_t j = i + 1;
      while (j < n && !transparent<B>(&px[B * j])) ++j;
      out.insert(out.end(), px.begin() + B * i, px.begin() + B * j);
      i = j;
      continue;
    }
    size_t j = i + 1;
    while (j < n && transparent<B>(&px[B * j]) && j - i < max_run) ++j;
    uint32_t run = uint32_t(j - i);
    uint8_t marker[B] = {uint8_t(run & 0xff), uint8_t((run >> 8) & 0xff),
                         uint8_t((run >> 16) & 0xff)};
    out.insert(out.end(), marker, marker + B);
    i = j;
  }
}

template <size_t B>
void decode(std::span<const uint8_t> s, size_t pixel_count, std::span<uint8_t> out) {
  if (out.size() < B * pixel_count) throw RleError("RLE decode: output buffer too small");
  if (s.size() % B != 0)
    throw RleError("RLE decode: stream length " + std::to_string(s.size()) +
                   " is not a multiple of " + std::to_string(B));
  size_t o = 0;  // pixels written
  for (size_t i = 0; i < s.size(); i += B) {
    if (!transparent<B>(&s[i])) {
      if (o >= pixel_count) throw RleError("RLE decode: stream holds more pixels than the image");
      std::memcpy(&out[B * o], &s[i], B);
      ++o;
      continue;
    }
    size_t run = size_t(s[i]) | size_t(s[i + 1]) << 8 | size_t(s[i + 2]) << 16;
    if (run == 0) throw RleError("RLE decode: zero-length run at byte " + std::to_string(i));
    if (run > pixel_count - o)
      throw RleError("RLE decode: run of " + std::to_string(run) + " at byte " + std::to_string(i) +
                     " overflows the image (" + std::to_string(pixel_count - o) + " pixels left)");
    std::memset(&out[B * o], 0, B * run);
    o += run;
  }
  if (o != pixel_count)
    throw RleError("RLE decode: stream holds " + std::to_string(o) + " pixels, image has " +
                   std::to_string(pixel_count));
}

void checkPixelBytes(int pixel_bytes) {
  if (pixel_bytes != 4 && pixel_bytes != 8)
    throw std::invalid_argument("RLE: pixels are 4 or 8 bytes, not " + std::to_string(pixel_bytes));
}

}  // namespace

void rleEncode(std::span<const uint8_t> px, std::vector<uint8_t>& out, int pixel_bytes,
               uint32_t max_run) {
  checkPixelBytes(pixel_bytes);
  if (max_run < 1 || max_run > kMaxRun)
    throw std::invalid_argument("RLE: max_run must be in [1, 2^24 - 1]");
  if (pixel_bytes == 4)
    encode<4>(px, out, max_run);
  else
    encode<8>(px, out, max_run);
}

std::vector<uint8_t> rleEncode(std::span<const uint8_t> px, int pixel_bytes, uint32_t max_run) {
  std::vector<uint8_t> out;
  out.reserve(px.size() / 8);
  rleEncode(px, out, pixel_bytes, max_run);
  return out;
}

void rleDecode(std::span<const uint8_t> s, size_t pixel_count, std::span<uint8_t> out,
               int pixel_bytes) {
  checkPixelBytes(pixel_bytes);
  if (pixel_bytes == 4)
    decode<4>(s, pixel_count, out);
  else
    decode<8>(s, pixel_count, out);
}

}  // namespace sortlast
