// bench_png_encode IMAGE [REPEATS]: encodes the image (read as RGB, as every frame is written)
// with each codec setting REPEATS times, round-robin so a busy machine's noise falls on all alike,
// and prints each setting's median and minimum milliseconds and its bytes. Every PNG is decoded
// again and checked pixel for pixel. The settings: libpng with zlib's default (level 6, adaptive
// filters: what files were written with before), zlib level 1 with the "sub" filter (the
// service's frames) and with "up"; libdeflate at levels 1, 2, 4 and 6 with "up" and "paeth"; JPEG
// quality 95 and 90; PPM; and the whole 8-bit frame write but the file, before and now.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/image.h"
#include "io/image_files.h"

using namespace sortlast;

// The frame read back is opaque, so any background leaves its pixels as they are.
const glm::dvec3 kBackground(0.2, 0.3, 0.4);

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_png_encode IMAGE [REPEATS]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 9;
  try {
    const ImageRGBA8 rgba = readImageRGBA8(argv[1]);
    files::Pixels8 rgb{rgba.width, rgba.height, 3,
                       std::vector<uint8_t>(size_t(rgba.width) * rgba.height * 3)};
    for (size_t i = 0; i < size_t(rgba.width) * rgba.height; ++i)
      for (int c = 0; c < 3; ++c) rgb.px[3 * i + c] = rgba.px[4 * i + c];

    struct Setting {
      std::string name;
      std::function<std::string()> encode;
      bool lossless;
      std::vector<double> ms;
      size_t bytes = 0;
    };
    using F = files::PngFilter;
    std::vector<Setting> settings = {
        {"libpng zlib 6 adaptive (old files)",
         [&] { return files::encodePng(rgb, 6, false); },
         true,
         {}},
        {"libpng zlib 1 sub (service)", [&] { return files::encodePng(rgb, 1, true); }, true, {}},
        {"libdeflate 1 up", [&] { return files::encodePngDeflate(rgb, 1, F::kUp); }, true, {}},
        {"libdeflate 2 up (files)",
         [&] { return files::encodePngDeflate(rgb, 2, F::kUp); },
         true,
         {}},
        {"libdeflate 2 paeth",
         [&] { return files::encodePngDeflate(rgb, 2, F::kPaeth); },
         true,
         {}},
        {"libdeflate 2 sub", [&] { return files::encodePngDeflate(rgb, 2, F::kSub); }, true, {}},
        {"libdeflate 4 up", [&] { return files::encodePngDeflate(rgb, 4, F::kUp); }, true, {}},
        {"libdeflate 6 up", [&] { return files::encodePngDeflate(rgb, 6, F::kUp); }, true, {}},
        {"jpeg 95 (files)", [&] { return files::encodeJpeg(rgb, 95); }, false, {}},
        {"jpeg 90 (service)", [&] { return files::encodeJpeg(rgb, 90); }, false, {}},
        {"ppm", [&] { return files::encodePpm(rgb); }, true, {}},
        // The whole write of an 8-bit frame but the file: the conversion over the background and
        // the encode, before (through a float frame, libpng at zlib's defaults) and now.
        {"old frame write (float path + libpng 6)",
         [&] {
           return files::encodePng(
               {rgba.width, rgba.height, 3, toRGB8(overBackground(toFloat(rgba), kBackground))});
         },
         true,
         {}},
        {"new frame write (opaqueRGB8 + libdeflate 2)",
         [&] {
           return files::encodePngDeflate(
               {rgba.width, rgba.height, 3, opaqueRGB8(rgba, kBackground)});
         },
         true,
         {}},
    };
    for (Setting& s : settings) {
      const std::string bytes = s.encode();
      s.bytes = bytes.size();
      if (s.lossless) {
        const files::Pixels8 back = files::decodeRGBA8(bytes, s.name);
        for (size_t i = 0; i < size_t(rgb.width) * rgb.height; ++i)
          for (int c = 0; c < 3; ++c)
            if (back.px[4 * i + c] != rgb.px[3 * i + c]) {
              std::fprintf(stderr, "%s: pixel %zu differs after decoding\n", s.name.c_str(), i);
              return 1;
            }
      }
    }
    for (int r = 0; r < repeats; ++r)
      for (Setting& s : settings) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::string bytes = s.encode();
        s.ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
      }
    std::printf("%s: %dx%d, %d repeats\n%-36s %9s %9s %10s\n", argv[1], rgb.width, rgb.height,
                repeats, "setting", "median_ms", "min_ms", "bytes");
    for (Setting& s : settings) {
      std::sort(s.ms.begin(), s.ms.end());
      std::printf("%-36s %9.1f %9.1f %10zu\n", s.name.c_str(), s.ms[s.ms.size() / 2], s.ms.front(),
                  s.bytes);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_png_encode: %s\n", e.what());
    return 1;
  }
  return 0;
}
