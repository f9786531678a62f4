#include "io/surface_image.h"

#include <algorithm>
#include <array>
#include <limits>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"
#include "io/image_files.h"

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
  if (files::formatOf(path) != files::Format::exr)
    throw InputError("surface output " + path + ": must be an OpenEXR file (.exr)");
  if constexpr (!build::kExr) refuseMissingFeature(Feature::kExr, "surface output " + path);
  std::vector<float> px(4 * n);
  for (size_t i = 0; i < n; ++i) {
    bool hit = img.hit(i);
    px[4 * i] = hit ? img.t[i] : std::numeric_limits<float>::infinity();
    for (int c = 0; c < 3; ++c) px[4 * i + 1 + c] = hit ? img.normal[i][c] : 0.0f;
  }
  try {
    if constexpr (build::kExr) files::writeExr(path, img.width, img.height, {kChannels.begin(), kChannels.end()}, px);
  } catch (const InputError& e) {
    throw InputError("surface output " + path + ": " + e.what());
  }
}

SurfaceImage readSurfaceImage(const std::string& path) {
  ImageChannels f;
  try {
    files::readFile(path, "surface image");  // a missing file: "cannot open" with the reason
    if constexpr (!build::kExr) refuseMissingFeature(Feature::kExr, "surface image " + path);
    else f = files::readExr(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind("surface image ", 0) == 0) throw;
    throw InputError("surface image " + path + ": " + what);
  }
  int index[4];
  for (int k = 0; k < 4; ++k) {
    auto it = std::find(f.names.begin(), f.names.end(), kChannels[size_t(k)]);
    if (it == f.names.end())
      throw InputError("surface image " + path + ": no channel '" + kChannels[size_t(k)] +
                       "' (a surface image has channels t, nx, ny, nz; is this a colour image?)");
    index[k] = int(it - f.names.begin());
  }
  const int w = f.width, h = f.height, nc = f.channels;
  SurfaceImage img(w, h);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    const float* p = &f.px[i * nc];
    img.t[i] = std::isfinite(p[index[0]]) ? p[index[0]] : std::numeric_limits<float>::infinity();
    img.normal[i] = glm::vec3(p[index[1]], p[index[2]], p[index[3]]);
  }
  return img;
}

}  // namespace sortlast
