#pragma once
// Image codecs, one library each: PNG (libpng reads; libdeflate writes, io/png_deflate.cpp;
// libpng's encodePng is kept for the benchmark that compares them), JPEG (libjpeg-turbo), OpenEXR (OpenEXR) and binary PPM (ours: no library). The one
// place that knows file formats; io/image.h (frames), io/surface_image.h (surface images)
// and io/image_encode.h (the service's in-memory frames) call it.
//
// Why not OpenImageIO, which this replaced: Debian 12's build of it loads 260 shared libraries
// (GDAL, OpenCV, DCMTK, FFmpeg, ...), and every process that links it pays for them at start:
// 0.40 s of CPU for a program that does nothing, on each rank of every job, where these three
// libraries cost 0.01 s. Only PNG, JPEG and EXR were ever used.
#include <cstdint>
#include <string>
#include <vector>

#include "io/image.h"

namespace sortlast::files {

enum class Format { png, jpeg, exr, ppm, other };
// By the file name's extension, case-insensitive: .png, .jpg/.jpeg, .exr, .ppm.
Format formatOf(const std::string& path);

// 8-bit pixels, `channels` (3: RGB, 4: RGBA) interleaved, row 0 at the top.
struct Pixels8 {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> px;
};

// PNG through libpng with zlib `level` (0-9; 6 is zlib's and libpng's default) and, with
// `sub_filter`, only the cheap "sub" row filter instead of libpng's adaptive choice: how files and
// served frames were written before encodePngDeflate (bench/output compares them).
std::string encodePng(const Pixels8& img, int level = 6, bool sub_filter = false);
// PNG through libdeflate at `level` (0-12, its scale), every row with one filter (io/png_deflate.cpp
// has the measurements that chose level 2 and "up" for files).
enum class PngFilter { kNone, kSub, kUp, kPaeth };
std::string encodePngDeflate(const Pixels8& img, int level = 2, PngFilter filter = PngFilter::kUp);
// Binary PPM (P6, 8-bit) of an RGB image, and read back as RGBA (A = 255).
std::string encodePpm(const Pixels8& rgb);
Pixels8 decodePpm(const std::string& bytes);
// Baseline JPEG of an RGB image, quality 1-100, 4:2:0 chroma (libjpeg's defaults).
std::string encodeJpeg(const Pixels8& rgb, int quality);
// A PNG, JPEG or binary PPM file (by its first bytes, whatever its name) as 8-bit RGBA: grey is replicated,
// a missing alpha is 255, 16-bit samples keep their high byte, palettes are expanded.
Pixels8 decodeRGBA8(const std::string& bytes, const std::string& name_for_errors);

// OpenEXR, 32-bit float channels (names given in the pixel order of `px`), ZIP compression.
void writeExr(const std::string& path, int width, int height, const std::vector<std::string>& names,
              const std::vector<float>& px);
// Every channel converted to float; R, G, B, A first (those present), then the others in the
// file's (alphabetical) order.
ImageChannels readExr(const std::string& path);

// Whole files; throw InputError naming `what` and the path.
std::string readFile(const std::string& path, const std::string& what);
void writeFile(const std::string& path, const std::string& bytes, const std::string& what);

}  // namespace sortlast::files
