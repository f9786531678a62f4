// Frames out of Python the way `sortlast render` writes them (io/image.h): over the scene's
// background, PNG (8-bit) or EXR (float). The Image type's _repr_png_ and save() use these.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>

#include "bindings.h"
#include "common/error.h"
#include "io/image.h"
#include "io/image_files.h"

namespace sortlast_py {

namespace {

// A (H, W, 4) uint8 or float32 premultiplied RGBA array as the library's float image.
sortlast::ImageF imageOf(const py::array& a) {
  if (a.ndim() != 3 || a.shape(2) != 4) throw py::value_error("an image is an (H, W, 4) array");
  const int h = int(a.shape(0)), w = int(a.shape(1));
  if (a.dtype().equal(py::dtype::of<uint8_t>())) {
    auto c = py::array_t<uint8_t, py::array::c_style>::ensure(a);
    sortlast::ImageRGBA8 img(w, h);
    std::copy(c.data(), c.data() + img.px.size(), img.px.begin());
    return sortlast::toFloat(img);
  }
  if (a.dtype().equal(py::dtype::of<float>())) {
    auto c = py::array_t<float, py::array::c_style>::ensure(a);
    sortlast::ImageF img(w, h);
    std::copy(c.data(), c.data() + img.px.size(), img.px.begin());
    return img;
  }
  throw py::value_error("an image is uint8 or float32, not " + std::string(py::str(a.dtype())));
}

glm::dvec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

void bindImages(py::module_& m) {
  m.def("_encode_png", [](const py::array& a, std::array<double, 3> background) {
    const sortlast::ImageF img = imageOf(a);
    std::string png;
    {
      py::gil_scoped_release nogil;
      png = sortlast::files::encodePngDeflate(
          {img.width, img.height, 3, sortlast::toRGB8(sortlast::overBackground(img, vec(background)))});
    }
    return py::bytes(png);
  });
  m.def("_write_image", [](const std::string& path, const py::array& a, std::array<double, 3> background) {
    const sortlast::ImageF img = imageOf(a);
    try {
      py::gil_scoped_release nogil;
      sortlast::writeImage(path, img, vec(background));
    } catch (const sortlast::InputError& e) {
      raiseInputError(e.what());
    }
  });
}

}  // namespace sortlast_py
