#pragma once
// Run-length coding of transparent pixels in RGBA8 images, the paper's Fig. 7 format: a run of N
// pixels with A = 0 becomes one 4-byte pixel whose first three bytes hold N (little-endian, 24
// bits) and whose fourth byte is 0; every other pixel is copied as is. Runs longer than 2^24 - 1
// are split. Since A = 0 marks a run, the stream needs no other framing.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace sortlast {

constexpr uint32_t kMaxRun = (1u << 24) - 1;

struct RleError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Appends the encoding of `pixels` (4 bytes each) to `out`.
void rleEncode(std::span<const uint8_t> pixels, std::vector<uint8_t>& out);
std::vector<uint8_t> rleEncode(std::span<const uint8_t> pixels);

// Decodes exactly `pixel_count` pixels into `out` (4 * pixel_count bytes). Throws RleError on a
// stream of the wrong length, a zero-length run or a run that overflows the image; never reads or
// writes out of bounds.
void rleDecode(std::span<const uint8_t> stream, size_t pixel_count, std::span<uint8_t> out);

}  // namespace sortlast
