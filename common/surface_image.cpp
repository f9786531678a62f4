#include "common/surface_image.h"

#include <OpenImageIO/imageio.h>

#include <array>
#include <limits>

#include "common/error.h"

namespace sortlast {

namespace {
// EXR keeps channels sorted by name, so the order written is not the order read back: the
// reader looks them up by these names.
const std::array<std::string, 4> kChannels = {"t", "nx", "ny", "nz"};
}  // namespace

SurfaceImage::SurfaceImage(int w, int h)
    : width(w),
      height(h),
      t(size_t(w) * h, std::numeric_limits<float>::infinity()),
      normal(size_t(w) * h, glm::vec3(0.0f)) {}

void writeSurfaceImage(const std::string& path, const SurfaceImage& img) {
  size_t n = size_t(img.width) * img.height;
  if (img.width <= 0 || img.height <= 0 || img.t.size() != n || img.normal.size() != n)
    throw InputError("surface output " + path + ": empty or inconsistent surface image");
  auto out = OIIO::ImageOutput::create(path);
  if (!out)
    throw InputError("surface output " + path + ": no image writer for this file extension");
  if (std::string(out->format_name()) != "openexr")
    throw InputError("surface output " + path + ": must be an OpenEXR file (.exr)");
  OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames.assign(kChannels.begin(), kChannels.end());
  spec.alpha_channel = -1;
  std::vector<float> px(4 * n);
  for (size_t i = 0; i < n; ++i) {
    bool hit = img.hit(i);
    px[4 * i] = hit ? img.t[i] : std::numeric_limits<float>::infinity();
    for (int c = 0; c < 3; ++c) px[4 * i + 1 + c] = hit ? img.normal[i][c] : 0.0f;
  }
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) ||
      !out->close())
    throw InputError("surface output " + path + ": " + out->geterror());
}

SurfaceImage readSurfaceImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError("surface image " + path + ": cannot open (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  int index[4];
  for (int k = 0; k < 4; ++k) {
    index[k] = spec.channelindex(kChannels[size_t(k)]);
    if (index[k] < 0)
      throw InputError("surface image " + path + ": no channel '" + kChannels[size_t(k)] +
                       "' (a surface image has channels t, nx, ny, nz; is this a colour image?)");
  }
  int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0) throw InputError("surface image " + path + ": empty image");
  std::vector<float> raw(size_t(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
    throw InputError("surface image " + path + ": " + in->geterror());
  SurfaceImage img(w, h);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    const float* p = &raw[i * nc];
    img.t[i] = std::isfinite(p[index[0]]) ? p[index[0]] : std::numeric_limits<float>::infinity();
    img.normal[i] = glm::vec3(p[index[1]], p[index[2]], p[index[3]]);
  }
  return img;
}

}  // namespace sortlast
