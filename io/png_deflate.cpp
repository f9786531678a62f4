// PNG written by us through libdeflate: the rows filtered here, one zlib stream (libdeflate's
// zlib_compress) in one IDAT chunk, chunk CRCs by libdeflate_crc32. libpng drives zlib, whose
// deflate is several times slower than libdeflate's at equal size (bench/output/run, a 1024²
// engine frame, median of 9, 2-core machine: zlib level 6 with adaptive filters 100 ms and
// 211 KB, libdeflate level 2 with "up" 12.6 ms and 202 KB; levels above 2 buy a few per cent of
// bytes for 20-140 % more time). Reading stays with libpng (io/image_files.cpp).
#include <libdeflate.h>

#include <cstdlib>
#include <cstring>
#include <memory>

#include "common/error.h"
#include "io/image_files.h"

namespace sortlast::files {

namespace {

void putBigEndian32(std::string& s, uint32_t v) {
  const char b[4] = {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  s.append(b, 4);
}

// Length, type, data, and the CRC of type and data (PNG spec 5.3).
void putChunk(std::string& out, const char* type, const void* data, size_t n) {
  putBigEndian32(out, uint32_t(n));
  const size_t at = out.size();
  out.append(type, 4);
  out.append(static_cast<const char*>(data), n);
  putBigEndian32(out, libdeflate_crc32(0, out.data() + at, n + 4));
}

uint8_t paethPredictor(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// One row filtered (PNG spec 9.2): its type byte, then the bytes. `prev` is the row above (zeros
// for the first row), `bpp` bytes per pixel. One loop per type, so each vectorises.
void filterRow(PngFilter f, const uint8_t* row, const uint8_t* prev, size_t n, size_t bpp,
               uint8_t* out) {
  out[0] = uint8_t(f == PngFilter::kNone  ? 0
                   : f == PngFilter::kSub ? 1
                   : f == PngFilter::kUp  ? 2
                                          : 4);
  uint8_t* d = out + 1;
  switch (f) {
    case PngFilter::kNone:
      std::memcpy(d, row, n);
      break;
    case PngFilter::kSub:
      std::memcpy(d, row, bpp);
      for (size_t i = bpp; i < n; ++i) d[i] = uint8_t(row[i] - row[i - bpp]);
      break;
    case PngFilter::kUp:
      for (size_t i = 0; i < n; ++i) d[i] = uint8_t(row[i] - prev[i]);
      break;
    case PngFilter::kPaeth:
      for (size_t i = 0; i < bpp; ++i) d[i] = uint8_t(row[i] - prev[i]);
      for (size_t i = bpp; i < n; ++i)
        d[i] = uint8_t(row[i] - paethPredictor(row[i - bpp], prev[i], prev[i - bpp]));
      break;
  }
}

}  // namespace

std::string encodePngDeflate(const Pixels8& img, int level, PngFilter filter) {
  if (img.width <= 0 || img.height <= 0 || img.channels < 3 || img.channels > 4 ||
      img.px.size() != size_t(img.width) * img.height * img.channels)
    throw InputError("empty or inconsistent image (" + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + "x" + std::to_string(img.channels) + ")");
  if (level < 0 || level > 12)
    throw InputError("PNG: libdeflate level " + std::to_string(level) + ": expected 0 to 12");
  const size_t bpp = size_t(img.channels), stride = size_t(img.width) * bpp;
  std::vector<uint8_t> filtered((stride + 1) * size_t(img.height));
  const std::vector<uint8_t> zeros(stride, 0);
  for (size_t y = 0; y < size_t(img.height); ++y)
    filterRow(filter, &img.px[y * stride], y ? &img.px[(y - 1) * stride] : zeros.data(), stride,
              bpp, &filtered[y * (stride + 1)]);

  std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(level), libdeflate_free_compressor);
  if (!compressor) throw InputError("PNG: out of memory (libdeflate)");
  std::vector<uint8_t> z(libdeflate_zlib_compress_bound(compressor.get(), filtered.size()));
  const size_t zn = libdeflate_zlib_compress(compressor.get(), filtered.data(), filtered.size(),
                                             z.data(), z.size());
  if (zn == 0) throw InputError("PNG: libdeflate could not compress the image");

  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  putBigEndian32(ihdr, uint32_t(img.width));
  putBigEndian32(ihdr, uint32_t(img.height));
  // Bit depth 8; colour type 2 (RGB) or 6 (RGBA); deflate, adaptive filtering, no interlace.
  ihdr += {char(8), char(img.channels == 4 ? 6 : 2), char(0), char(0), char(0)};
  putChunk(out, "IHDR", ihdr.data(), ihdr.size());
  putChunk(out, "IDAT", z.data(), zn);
  putChunk(out, "IEND", "", 0);
  return out;
}

}  // namespace sortlast::files
