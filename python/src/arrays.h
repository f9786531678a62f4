#pragma once
// numpy arrays described for the in-situ library where they lie (include/sortlast/insitu.h):
// the pointer, the element type and the strides numpy has, nothing copied. Throws
// sortlast::InputError naming what the C++ side cannot take.
#include <pybind11/numpy.h>

#include <array>
#include <string>

#include <sortlast/insitu.h>

namespace sortlast_py {

namespace py = pybind11;

// A 3-D array indexed grid[x, y, z] (axis 0 is x), any layout numpy has: C or Fortran order,
// slices and other strided views. ghost_lo/hi count layers along each axis.
sortlast::GridBlock gridBlock(const py::handle& array, const std::array<int, 3>& ghost_lo,
                              const std::array<int, 3>& ghost_hi, const std::array<double, 3>& origin,
                              const std::array<double, 3>& spacing, const std::string& name);

// An (N, 3) array of positions, float64 or float32; rows may be strided (a slice of a wider array).
sortlast::ParticleBlock particleBlock(const py::handle& array);

}  // namespace sortlast_py
