#include "io/image_encode.h"

#include <string>
#include <vector>

#include "common/error.h"
#include "io/image_files.h"

// The PNG of a served frame, 512² engine CT frame (bench/output/run: bench_png_encode, 15
// repeats, 2-core development machine with other builds running), median ms and bytes:
//   libpng, zlib level 1, "sub" row filter (before)   8.0 ms  116 KB
//   libdeflate level 2, "up" row filter (now)           2.6 ms   76 KB
//   libpng with zlib's defaults (level 6, adaptive)    30.0 ms   77 KB
//   JPEG quality 90                                     0.5 ms   21 KB
// libdeflate's is faster and smaller, so the service encodes as the files do.

namespace sortlast {

std::string encodeImage(const ImageRGBA8& img, const glm::dvec3& background,
                        const std::string& format, int quality) {
  bool png = format == "png";
  if (!png && format != "jpeg")
    throw InputError("image format \"" + format + "\": expected \"png\" or \"jpeg\"");
  if (!png && (quality < 1 || quality > 100))
    throw InputError("jpeg quality " + std::to_string(quality) + ": expected 1 to 100");

  // Same compositing and the same rounding as writeImage, so a PNG served equals the PNG file
  // `sortlast render` writes.
  files::Pixels8 rgb{img.width, img.height, 3, opaqueRGB8(img, background)};
  try {
    // The frame is on the interactive path: libdeflate at level 2 (timings at the top).
    return png ? files::encodePngDeflate(rgb) : files::encodeJpeg(rgb, quality);
  } catch (const InputError& e) {
    throw InputError("encoding " + format + ": " + e.what());
  }
}

}  // namespace sortlast
