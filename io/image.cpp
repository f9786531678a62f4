#include "io/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"
#include "common/pixel_threads.h"
#include "io/image_files.h"

namespace sortlast {

namespace {

// std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f) as a uint8_t, for every float, without the
// call, so loops over it vectorise (with -fno-trapping-math, io/CMakeLists.txt: GCC otherwise
// keeps the float-to-int conversion scalar in case it traps). t is in [0, 255], so truncation is
// floor and t - floor(t) is exact; lround rounds halves away from zero, i.e. up. NaN: the
// comparison sends it to 0, as lround's "integer indefinite" (0x80...0) cast to uint8_t gives 0
// (checked over every float bit pattern, tests/unit/pixel_parallel_test.cpp).
inline uint8_t quantise(float v) {
  float c = v > 0.0f ? v : 0.0f;
  c = c < 1.0f ? c : 1.0f;
  const float t = c * 255.0f;
  const int r = int(t);
  return uint8_t(r + int(t - float(r) >= 0.5f));
}

inline void toRGBA8Pixels(const float* in, uint8_t* out, size_t pixels) {
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t a = quantise(in[4 * i + 3]);
    out[4 * i + 0] = std::min(quantise(in[4 * i + 0]), a);
    out[4 * i + 1] = std::min(quantise(in[4 * i + 1]), a);
    out[4 * i + 2] = std::min(quantise(in[4 * i + 2]), a);
    out[4 * i + 3] = a;
  }
}

// Pixels a thread converts at least: 64 K pixels, about 0.34 ms on one core of the 2-core
// development machine (bench/pixels: 5.45 ms a 1024^2 frame), so a thread's wake-up is small
// beside its part. Not tuned by a sweep.
constexpr size_t kConvertGrain = 1 << 16;

}  // namespace

void toRGBA8(const float* in, uint8_t* out) { toRGBA8Pixels(in, out, 1); }

void toRGBA8(const float* in, uint8_t* out, size_t pixels) {
  parallelFor(pixels, kConvertGrain,
              [&](size_t b, size_t e) { toRGBA8Pixels(in + 4 * b, out + 4 * b, e - b); });
}

ImageRGBA8 toRGBA8(const ImageF& img) {
  ImageRGBA8 out(img.width, img.height);
  toRGBA8(img.px.data(), out.px.data(), size_t(img.width) * img.height);
  return out;
}

ImageF toFloat(const ImageRGBA8& img) {
  ImageF out(img.width, img.height);
  for (size_t i = 0; i < out.px.size(); ++i) out.px[i] = img.px[i] / 255.0f;
  return out;
}

std::vector<float> overBackground(const ImageF& img, const glm::dvec3& bg) {
  std::vector<float> rgb(size_t(img.width) * img.height * 3);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    float a = img.px[4 * i + 3];
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = img.px[4 * i + c] + (1.0f - a) * float(bg[c]);
  }
  return rgb;
}

std::vector<uint8_t> toRGB8(const std::vector<float>& rgb) {
  std::vector<uint8_t> out(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i)
    out[i] = std::isnan(rgb[i]) ? 0 : uint8_t(std::clamp(std::roundf(rgb[i] * 255.0f), 0.0f, 255.0f));
  return out;
}

namespace {

// One channel of an 8-bit premultiplied pixel over the background, rounded: the operations of
// toFloat, overBackground and toRGB8, in their order.
uint8_t overBackground8(uint8_t value, uint8_t alpha, float background) {
  const float v = value / 255.0f + (1.0f - alpha / 255.0f) * background;
  return std::isnan(v) ? 0 : uint8_t(std::clamp(std::roundf(v * 255.0f), 0.0f, 255.0f));
}

}  // namespace

std::vector<uint8_t> opaqueRGB8(const ImageRGBA8& img, const glm::dvec3& bg) {
  const size_t n = size_t(img.width) * img.height;
  std::vector<uint8_t> out(n * 3);
  const float b[3] = {float(bg[0]), float(bg[1]), float(bg[2])};
  // A channel's result depends on its (value, alpha) pair alone: from 64 Ki pixels on, a table of
  // every pair per channel (196,608 conversions) is cheaper than converting each pixel (at 1024²,
  // 3.1 million; the direct loop took ~20 ms there, bench/output).
  if (n < 65536) {
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) out[3 * i + c] = overBackground8(img.px[4 * i + c], img.px[4 * i + 3], b[c]);
    return out;
  }
  std::vector<uint8_t> table(3 * 65536);
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 256; ++a)
      for (int v = 0; v < 256; ++v) table[size_t(c) * 65536 + size_t(a) * 256 + size_t(v)] = overBackground8(uint8_t(v), uint8_t(a), b[c]);
  for (size_t i = 0; i < n; ++i) {
    const size_t a = size_t(img.px[4 * i + 3]) * 256;
    for (int c = 0; c < 3; ++c) out[3 * i + c] = table[size_t(c) * 65536 + a + img.px[4 * i + c]];
  }
  return out;
}

void checkOutputFormat(const std::string& path) {
  if (files::formatOf(path) == files::Format::other)
    throw InputError("output " + path + ": no image writer for this file extension (.png, .jpg, .ppm or .exr; movies: .mp4 or .webm)");
  if (files::formatOf(path) == files::Format::exr && !build::kExr) refuseMissingFeature(Feature::kExr, "output " + path);
}

namespace {

// Runs `write`, its error named with the output file once ("output PATH: ...").
template <class Write>
void namingOutput(const std::string& path, Write&& write) {
  try {
    write();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("output ", 0) == 0) throw;
    throw InputError("output " + path + ": " + what);
  }
}

// An 8-bit file of the opaque RGB frame, by the extension (PNG, JPEG or PPM).
void writeEncoded(const std::string& path, const files::Pixels8& rgb) {
  const files::Format format = files::formatOf(path);
  // PNG through libdeflate (level 2, "up" rows): 7-8x faster than libpng's zlib defaults at
  // about their size (io/png_deflate.cpp). JPEG at quality 95 (4:2:0 chroma, libjpeg's
  // default), where artefacts are hard to see; PPM as it is.
  const std::string bytes = format == files::Format::png    ? files::encodePngDeflate(rgb)
                            : format == files::Format::jpeg ? files::encodeJpeg(rgb, kJpegFileQuality)
                                                            : files::encodePpm(rgb);
  files::writeFile(path, bytes, "output");
}

}  // namespace

void writeImage(const std::string& path, const ImageF& img, const glm::dvec3& bg) {
  checkOutputFormat(path);
  namingOutput(path, [&] {
    if constexpr (build::kExr) {
      if (files::formatOf(path) == files::Format::exr)
        return files::writeExr(path, img.width, img.height, {"R", "G", "B"}, overBackground(img, bg));
    }
    writeEncoded(path, {img.width, img.height, 3, toRGB8(overBackground(img, bg))});
  });
}

void writeImage(const std::string& path, const ImageRGBA8& img, const glm::dvec3& bg) {
  if (files::formatOf(path) == files::Format::exr) return writeImage(path, toFloat(img), bg);
  checkOutputFormat(path);
  namingOutput(path, [&] { writeEncoded(path, {img.width, img.height, 3, opaqueRGB8(img, bg)}); });
}

std::string frameFileName(const std::string& out, int frame, int frames) {
  if (frames <= 1) return out;
  std::filesystem::path p(out);
  char num[16];
  std::snprintf(num, sizeof num, "_%04d", frame);
  return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

namespace {

// Reads a PNG, JPEG, PPM or EXR file (told apart by their first bytes) as float channels: 8-bit files
// as value / 255, named R, G, B, A.
ImageChannels readAnyImage(const std::string& path) {
  try {
    const std::string bytes = files::readFile(path, "image");
    if (bytes.compare(0, 4, std::string("\x76\x2f\x31\x01", 4)) == 0) {  // EXR's magic
      if constexpr (build::kExr) return files::readExr(path);
      refuseMissingFeature(Feature::kExr, "image " + path);
    }
    files::Pixels8 p = files::decodeRGBA8(bytes, "");
    ImageChannels img;
    img.width = p.width;
    img.height = p.height;
    img.channels = 4;
    img.names = {"R", "G", "B", "A"};
    img.px.resize(p.px.size());
    for (size_t i = 0; i < p.px.size(); ++i) img.px[i] = p.px[i] / 255.0f;
    return img;
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("image ", 0) == 0) throw;
    throw InputError("image " + path + ": " + what);
  }
}

}  // namespace

ImageRGBA8 readImageRGBA8(const std::string& path) {
  const ImageChannels f = readAnyImage(path);
  const int w = f.width, h = f.height, nc = f.channels;
  // A NaN or Inf in a float file (an .exr frame) would become a plausible 0 or 255 in the 8-bit
  // conversion, and comparisons would pass over it.
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < f.px.size(); ++i)
    if (!std::isfinite(f.px[i]) && bad++ == 0) first = i / size_t(nc);
  if (bad)
    throw InputError("image " + path + ": " + std::to_string(bad) + " non-finite values (NaN or Inf), the first at pixel (" +
                     std::to_string(first % size_t(w)) + ", " + std::to_string(first / size_t(w)) + ")");
  // 8-bit values come back exactly (k / 255 * 255 rounds to k); float ones are rounded as toRGB8.
  const std::vector<uint8_t> raw = toRGB8(f.px);
  ImageRGBA8 img(w, h);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 4; ++c)
      img.px[4 * i + c] = c < nc ? raw[i * nc + c] : (c == 3 ? 255 : raw[i * nc]);
  return img;
}

ImageChannels readImageChannels(const std::string& path) { return readAnyImage(path); }

}  // namespace sortlast
