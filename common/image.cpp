#include "common/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "common/error.h"

namespace sortlast {

void toRGBA8(const float* in, uint8_t* out) {
  auto q = [](float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  out[3] = q(in[3]);
  for (int c = 0; c < 3; ++c) out[c] = std::min(q(in[c]), out[3]);
}

ImageRGBA8 toRGBA8(const ImageF& img) {
  ImageRGBA8 out(img.width, img.height);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) toRGBA8(&img.px[4 * i], &out.px[4 * i]);
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

void writeImage(const std::string& path, const ImageF& img, const glm::dvec3& bg) {
  auto ext = std::filesystem::path(path).extension().string();
  bool is_float = ext == ".exr";
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError("output " + path + ": no image writer for this file extension");
  OIIO::ImageSpec spec(img.width, img.height, 3, is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  std::vector<float> rgb = overBackground(img, bg);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) || !out->close())
    throw InputError("output " + path + ": " + out->geterror());
}

void writeImage(const std::string& path, const ImageRGBA8& img, const glm::dvec3& bg) {
  writeImage(path, toFloat(img), bg);
}

std::string frameFileName(const std::string& out, int frame, int frames) {
  if (frames <= 1) return out;
  std::filesystem::path p(out);
  char num[16];
  std::snprintf(num, sizeof num, "_%04d", frame);
  return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

ImageRGBA8 readImageRGBA8(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError("image " + path + ": cannot open (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  int w = spec.width, h = spec.height, nc = spec.nchannels;
  // A float file (an .exr frame) is first read as stored: a NaN or Inf would otherwise become a
  // plausible 0 or 255 in the 8-bit conversion, and comparisons would pass over it.
  if (spec.format.is_floating_point()) {
    std::vector<float> f(size_t(w) * h * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, f.data()))
      throw InputError("image " + path + ": " + in->geterror());
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < f.size(); ++i)
      if (!std::isfinite(f[i]) && bad++ == 0) first = i / size_t(nc);
    if (bad)
      throw InputError("image " + path + ": " + std::to_string(bad) + " non-finite values (NaN or Inf), the first at pixel (" +
                       std::to_string(first % size_t(w)) + ", " + std::to_string(first / size_t(w)) + ")");
  }
  std::vector<uint8_t> raw(size_t(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, raw.data()))
    throw InputError("image " + path + ": " + in->geterror());
  ImageRGBA8 img(w, h);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 4; ++c)
      img.px[4 * i + c] = c < nc ? raw[i * nc + c] : (c == 3 ? 255 : raw[i * nc]);
  return img;
}

ImageChannels readImageChannels(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError("image " + path + ": cannot open (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  ImageChannels img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.names = spec.channelnames;
  img.px.resize(size_t(img.width) * img.height * img.channels);
  if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.px.data()))
    throw InputError("image " + path + ": " + in->geterror());
  return img;
}

}  // namespace sortlast
