// numpy arrays described for the in-situ library without copying (arrays.h).
#include "arrays.h"

#include <climits>

#include "common/error.h"

namespace sortlast_py {

namespace {

using sortlast::ElementType;
using sortlast::InputError;

py::array asArray(const py::handle& h, const std::string& what) {
  if (!py::isinstance<py::array>(h))
    throw InputError(what + " must be a numpy array, not " +
                     std::string(py::str(py::type::of(h).attr("__name__"))));
  return py::reinterpret_borrow<py::array>(h);
}

std::string dtypeName(const py::array& a) { return py::str(a.dtype()); }

ElementType elementType(const py::array& a, const std::string& what) {
  // equal() is numpy's equivalence, byte order included: big-endian data is refused.
  const py::dtype dt = a.dtype();
  if (dt.equal(py::dtype::of<uint8_t>())) return ElementType::kUint8;
  if (dt.equal(py::dtype::of<uint16_t>())) return ElementType::kUint16;
  if (dt.equal(py::dtype::of<int16_t>())) return ElementType::kInt16;
  if (dt.equal(py::dtype::of<float>())) return ElementType::kFloat32;
  if (dt.equal(py::dtype::of<double>())) return ElementType::kFloat64;
  throw InputError(what + ": element type " + dtypeName(a) +
                   " is not one sortlast takes (uint8, uint16, int16, float32, float64 in this "
                   "machine's byte order); convert it with .astype(numpy.float32)");
}

// A byte stride in elements; numpy allows any byte stride (a field of a structured array, a
// view of bytes), the library only whole elements.
long long elementStride(const py::array& a, int axis, const std::string& what) {
  const py::ssize_t bytes = a.strides(axis), item = a.itemsize();
  if (bytes % item != 0)
    throw InputError(what + ": stride " + std::to_string(bytes) + " bytes along axis " +
                     std::to_string(axis) + " is not a whole number of " + std::to_string(item) +
                     "-byte elements (a view sortlast cannot read in place); pass a copy "
                     "(numpy.ascontiguousarray)");
  return bytes / item;
}

}  // namespace

sortlast::GridBlock gridBlock(const py::handle& h, const std::array<int, 3>& ghost_lo,
                              const std::array<int, 3>& ghost_hi, const std::array<double, 3>& origin,
                              const std::array<double, 3>& spacing, const std::string& name) {
  const py::array a = asArray(h, "grid");
  if (a.ndim() != 3)
    throw InputError("grid must have 3 dimensions (indexed grid[x, y, z]), not " + std::to_string(a.ndim()));
  sortlast::GridBlock g;
  g.type = elementType(a, "grid");
  bool broadcast = true;
  for (int axis = 0; axis < 3; ++axis) {
    if (a.shape(axis) < 1 || a.shape(axis) > INT_MAX)
      throw InputError("grid: " + std::to_string(a.shape(axis)) + " samples along axis " +
                       std::to_string(axis) + " (need 1 ... 2^31 - 1)");
    g.dims[size_t(axis)] = int(a.shape(axis));
    g.strides[size_t(axis)] = a.shape(axis) == 1 ? 0 : elementStride(a, axis, "grid");
    broadcast = broadcast && g.strides[size_t(axis)] == 0;
  }
  // All strides 0 means "dense" to the library: a single sample, or a broadcast array.
  if (broadcast) {
    if (g.dims[0] * 1LL * g.dims[1] * g.dims[2] > 1)
      throw InputError("grid: a broadcast array (every stride 0) has no samples of its own; pass a copy");
    g.strides = {1, 1, 1};
  } else {
    // Axes of one sample: any stride will do (never multiplied by more than 0); keep them non-zero.
    for (int axis = 0; axis < 3; ++axis)
      if (g.strides[size_t(axis)] == 0) g.strides[size_t(axis)] = 1;
  }
  g.data = a.data();
  g.ghost_lo = ghost_lo;
  g.ghost_hi = ghost_hi;
  g.origin = origin;
  g.spacing = spacing;
  g.name = name;
  return g;
}

sortlast::ParticleBlock particleBlock(const py::handle& h) {
  const py::array a = asArray(h, "particles");
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError("particles must be an (N, 3) array of positions");
  const bool f64 = a.dtype().equal(py::dtype::of<double>()), f32 = a.dtype().equal(py::dtype::of<float>());
  if (!f64 && !f32)
    throw InputError("particles: element type " + dtypeName(a) + " (positions are float64 or float32)");
  sortlast::ParticleBlock p;
  p.count = a.shape(0);
  if (p.count == 0) return p;
  long long row = elementStride(a, 0, "particles");
  const long long column = elementStride(a, 1, "particles");
  if (p.count == 1) row = 1;
  if (row < 1)
    throw InputError("particles: rows must go forwards in memory (row stride " + std::to_string(row) +
                     " elements); pass a copy");
  p.stride = row;
  if (f64) {
    const auto* x = static_cast<const double*>(a.data());
    p.x = x, p.y = x + column, p.z = x + 2 * column;
  } else {
    const auto* x = static_cast<const float*>(a.data());
    p.x32 = x, p.y32 = x + column, p.z32 = x + 2 * column;
  }
  return p;
}

}  // namespace sortlast_py
