#include "compositing/rle.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace sortlast {

void rleEncode(std::span<const uint8_t> px, std::vector<uint8_t>& out) {
  const size_t n = px.size() / 4;
  size_t i = 0;
  while (i < n) {
    if (px[4 * i + 3] != 0) {
      // Copy the whole stretch of visible pixels at once.
      size_t j = i + 1;
      while (j < n && px[4 * j + 3] != 0) ++j;
      out.insert(out.end(), px.begin() + 4 * i, px.begin() + 4 * j);
      i = j;
      continue;
    }
    size_t j = i + 1;
    while (j < n && px[4 * j + 3] == 0 && j - i < kMaxRun) ++j;
    uint32_t run = uint32_t(j - i);
    out.push_back(uint8_t(run & 0xff));
    out.push_back(uint8_t((run >> 8) & 0xff));
    out.push_back(uint8_t((run >> 16) & 0xff));
    out.push_back(0);
    i = j;
  }
}

std::vector<uint8_t> rleEncode(std::span<const uint8_t> px) {
  std::vector<uint8_t> out;
  out.reserve(px.size() / 8);
  rleEncode(px, out);
  return out;
}

void rleDecode(std::span<const uint8_t> s, size_t pixel_count, std::span<uint8_t> out) {
  if (out.size() < 4 * pixel_count) throw RleError("RLE decode: output buffer too small");
  if (s.size() % 4 != 0)
    throw RleError("RLE decode: stream length " + std::to_string(s.size()) + " is not a multiple of 4");
  size_t o = 0;  // pixels written
  for (size_t i = 0; i < s.size(); i += 4) {
    if (s[i + 3] != 0) {
      if (o >= pixel_count) throw RleError("RLE decode: stream holds more pixels than the image");
      std::memcpy(&out[4 * o], &s[i], 4);
      ++o;
      continue;
    }
    size_t run = size_t(s[i]) | size_t(s[i + 1]) << 8 | size_t(s[i + 2]) << 16;
    if (run == 0) throw RleError("RLE decode: zero-length run at byte " + std::to_string(i));
    if (run > pixel_count - o)
      throw RleError("RLE decode: run of " + std::to_string(run) + " at byte " + std::to_string(i) +
                     " overflows the image (" + std::to_string(pixel_count - o) + " pixels left)");
    std::memset(&out[4 * o], 0, 4 * run);
    o += run;
  }
  if (o != pixel_count)
    throw RleError("RLE decode: stream holds " + std::to_string(o) + " pixels, image has " +
                   std::to_string(pixel_count));
}

}  // namespace sortlast
