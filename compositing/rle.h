#pragma once
// Run-length coding of transparent pixels, the paper's Fig. 7 format: a run of N pixels with
// A = 0 becomes one pixel whose first three bytes hold N (little-endian, 24 bits) and whose other
// bytes are 0; every other pixel is copied as is. Runs longer than 2^24 - 1 are split. Since A = 0
// marks a run, the stream needs no other framing. Pixels are RGBA8 (4 bytes, the paper's
// intermediate images) or RGBA16 (8 bytes, four little-endian uint16: partial composites); the
// bounded sums of compositing/projection_pixels.h are 12 bytes, a run marked by the last 3 zero.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace sortlast {

constexpr uint32_t kMaxRun = (1u << 24) - 1;

struct RleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Large inputs (from 128 K pixels) are encoded and decoded on the pixel threads
// (common/pixel_threads.h) with exactly the bytes of the serial code: see rle.cpp.

// Appends the encoding of `pixels` (`pixel_bytes` = 4, 8 or 12 each) to `out`. `max_run` = 1 turns
// the compression off while keeping the format: each transparent pixel becomes its own marker, so
// the stream is exactly as long as the raw pixels (what "RLE off" measures).
void rleEncode(std::span<const uint8_t> pixels, std::vector<uint8_t>& out, int pixel_bytes = 4,
               uint32_t max_run = kMaxRun);
std::vector<uint8_t> rleEncode(std::span<const uint8_t> pixels, int pixel_bytes = 4,
                               uint32_t max_run = kMaxRun);

// Decodes exactly `pixel_count` pixels into `out` (pixel_bytes * pixel_count bytes). Throws
// RleError on a stream of the wrong length, a zero-length run or a run that overflows the image;
// never reads or writes out of bounds.
void rleDecode(std::span<const uint8_t> stream, size_t pixel_count, std::span<uint8_t> out,
               int pixel_bytes = 4);

// A piece of a stream and the first pixel it decodes to. Every element of a stream is one pixel or
// one run marker of `pixel_bytes` bytes, so any multiple of that is an element boundary: a cheap
// count of the pixels before each cut is all it takes to decode (or blend) the pieces in
// parallel.
struct RlePiece {
  size_t byte_begin = 0, byte_end = 0;  // in the stream
  size_t pixel_begin = 0;               // the first pixel this piece decodes to
};

// The stream cut into `parts` pieces of about equal bytes, checked as rleDecode checks it (the
// same RleError messages). The count runs in parallel over the parts.
std::vector<RlePiece> rleSplit(std::span<const uint8_t> stream, size_t pixel_count, int pixel_bytes,
                               int parts);

// Whether a stream element is a run marker (alpha 0: the last pixel_bytes / 4 bytes are 0).
inline bool rleIsRun(const uint8_t* p, int pixel_bytes) {
  if (pixel_bytes == 4) return p[3] == 0;
  if (pixel_bytes == 8) return (p[6] | p[7]) == 0;
  return (p[9] | p[10] | p[11]) == 0;  // 12: the bounded sums (compositing/projection_pixels.h)
}

// Walks one piece of a checked stream (rleSplit's): visible(first_pixel, bytes, count) for each
// stretch of visible pixels (`count` pixels at `bytes`, as they are in the image), and
// run(first_pixel, count) for each run of transparent pixels, in order.
template <class Visible, class Run>
void rleVisit(std::span<const uint8_t> stream, const RlePiece& piece, int pixel_bytes,
              Visible&& visible, Run&& run) {
  const size_t b = size_t(pixel_bytes);
  size_t o = piece.pixel_begin;
  size_t i = piece.byte_begin;
  while (i < piece.byte_end) {
    const uint8_t* e = &stream[i];
    if (rleIsRun(e, pixel_bytes)) {
      const size_t n = size_t(e[0]) | size_t(e[1]) << 8 | size_t(e[2]) << 16;
      run(o, n);
      o += n;
      i += b;
      continue;
    }
    size_t j = i + b;
    while (j < piece.byte_end && !rleIsRun(&stream[j], pixel_bytes)) j += b;
    visible(o, e, (j - i) / b);
    o += (j - i) / b;
    i = j;
  }
}

}  // namespace sortlast
