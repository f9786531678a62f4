// Binary PPM (P6, maxval 255): a short text header and the RGB bytes as they are, the fastest
// frame to write (no encoding at all) and one every image tool reads.
#include <cctype>
#include <cstring>

#include "common/error.h"
#include "io/image_files.h"

namespace sortlast::files {

std::string encodePpm(const Pixels8& rgb) {
  if (rgb.width <= 0 || rgb.height <= 0 || rgb.channels != 3 ||
      rgb.px.size() != size_t(rgb.width) * rgb.height * 3)
    throw InputError("PPM: empty or inconsistent RGB image (" + std::to_string(rgb.width) + "x" +
                     std::to_string(rgb.height) + "x" + std::to_string(rgb.channels) + ")");
  std::string out =
      "P6\n" + std::to_string(rgb.width) + " " + std::to_string(rgb.height) + "\n255\n";
  out.append(reinterpret_cast<const char*>(rgb.px.data()), rgb.px.size());
  return out;
}

Pixels8 decodePpm(const std::string& bytes) {
  // The header: "P6", then width, height and maxval as decimal numbers, separated by whitespace
  // and '#' comments to the end of the line; exactly one whitespace byte before the pixels.
  size_t at = 2;
  auto number = [&](const char* what) {
    for (;;) {
      while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
      if (at < bytes.size() && bytes[at] == '#') {
        while (at < bytes.size() && bytes[at] != '\n') ++at;
        continue;
      }
      break;
    }
    long long v = 0;
    const size_t start = at;
    while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])) && v <= 1 << 20)
      v = v * 10 + (bytes[at++] - '0');
    if (at == start || v <= 0 || v > 1 << 20)
      throw InputError(std::string("PPM: bad or missing ") + what + " in the header");
    return int(v);
  };
  if (bytes.compare(0, 2, "P6") != 0) throw InputError("PPM: not a binary PPM (P6) file");
  Pixels8 img;
  img.width = number("width");
  img.height = number("height");
  const int maxval = number("maxval");
  if (maxval != 255)
    throw InputError("PPM: maxval " + std::to_string(maxval) + ": only 8-bit (255) is read");
  if (at >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[at])))
    throw InputError("PPM: no whitespace after the header");
  ++at;
  const size_t n = size_t(img.width) * size_t(img.height) * 3;
  if (bytes.size() - at < n) throw InputError("PPM: file is truncated");
  img.channels = 4;
  img.px.assign(size_t(img.width) * img.height * 4, 255);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i)
    std::memcpy(&img.px[4 * i], bytes.data() + at + 3 * i, 3);
  return img;
}

}  // namespace sortlast::files
