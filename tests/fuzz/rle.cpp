// libFuzzer target: the RLE decoder (compositing/rle.h) for one pixel format, PIXEL_BYTES = 4
// (RGBA8) or 8 (RGBA16), set by tests/fuzz/CMakeLists.txt.
// Input: 2 bytes of pixel count (12 bits, little-endian, the high 4 bits ignored: what the
// receiver's rectangle says; up to 4095 keeps each input fast, and runs still overflow it), then
// the stream. The decoder must either throw RleError or fill exactly that many pixels; what it decodes
// must survive encoding and decoding again unchanged.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "compositing/rle.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  constexpr int B = PIXEL_BYTES;
  if (size < 2) return 0;
  const size_t pixels = size_t(data[0]) | size_t(data[1] & 0x0f) << 8;
  std::span<const uint8_t> stream(data + 2, size - 2);
  std::vector<uint8_t> out(pixels * B, 0xAB);
  try {
    rleDecode(stream, pixels, out, B);
  } catch (const RleError&) {
    return 0;
  }
  // Decoded: re-encode (also with runs of 1, "RLE off") and decode again.
  for (uint32_t max_run : {kMaxRun, 1u, 3u}) {
    std::vector<uint8_t> again = rleEncode(out, B, max_run);
    std::vector<uint8_t> back(out.size());
    rleDecode(again, pixels, back, B);
    if (back != out) std::abort();
  }
  return 0;
}
