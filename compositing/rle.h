#pragma once
// Run-length coding of transparent pixels, the paper's Fig. 7 format: a run of N pixels with
// A = 0 becomes one pixel whose first three bytes hold N (little-endian, 24 bits) and whose other
// bytes are 0; every other pixel is copied as is. Runs longer than 2^24 - 1 are split. Since A = 0
// marks a run, the stream needs no other framing. Pixels are RGBA8 (4 bytes, the paper's
// intermediate images) or RGBA16 (8 bytes, four little-endian uint16: partial composites).
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace sortlast {

constexpr uint32_t kMaxRun = (1u << 24) - 1;

struct RleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Appends the encoding of `pixels` (`pixel_bytes` = 4 or 8 each) to `out`. `max_run` = 1 turns
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

}  // namespace sortlast
