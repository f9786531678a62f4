// Particle snapshots in HDF5, the layout SPH and cosmology codes write (Gadget, SWIFT, AREPO):
// an N x 3 dataset of positions, /PartType0/Coordinates unless particles.dataset names another.
// A session reads it in shares, each rank a contiguous run of rows (session/particle_loading.cpp).
#include <vector>

#include "common/error.h"
#include "io/hdf5_detail.h"
#include "io/particles.h"

namespace sortlast {

using hdf5::Id;

std::vector<glm::vec3> readHdf5Particles(const std::string& file, const std::string& dataset, int part, int parts,
                                         long long* total) {
  hdf5::quiet();
  const std::string f = "particles.file " + file, w = f + ": dataset " + dataset;
  if (H5Fis_hdf5(file.c_str()) <= 0) throw InputError(f + ": not an HDF5 file (no HDF5 signature)");
  Id h5(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!h5.ok()) throw InputError(f + ": cannot open as HDF5 (a truncated or damaged file?)" + hdf5::because());
  if (H5Lexists(h5.get(), dataset.c_str(), H5P_DEFAULT) <= 0)
    throw InputError(w + ": no such dataset in the file (particles.dataset names it)");
  Id ds(H5Dopen2(h5.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(w + ": not a dataset (a group?)" + hdf5::because());
  Id space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t dims[2] = {0, 0};
  if (rank != 2 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) != 2 || dims[1] != 3)
    throw InputError(w + ": positions must be an N x 3 dataset, but it has " +
                     (rank == 2 ? "shape " + std::to_string(dims[0]) + " x " + std::to_string(dims[1])
                                : std::to_string(rank) + " dimension(s)"));
  if (dims[0] > hsize_t(1) << 31)
    throw InputError(w + ": " + std::to_string(dims[0]) + " particles, beyond 2^31");
  Id type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t c = H5Tget_class(type.get());
  const size_t bytes = H5Tget_size(type.get());
  if (c != H5T_FLOAT || (bytes != 4 && bytes != 8))
    throw InputError(w + ": positions of type " +
                     (c == H5T_INTEGER ? (H5Tget_sign(type.get()) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bytes * 8)
                      : c == H5T_FLOAT ? "float" + std::to_string(bytes * 8) : std::string("other than numbers")) +
                     " are not supported (float32, float64)");
  if (total) *total = (long long)dims[0];
  // Rows [n * part / parts, n * (part + 1) / parts): the shares are contiguous and in part order.
  const hsize_t first = hsize_t((unsigned long long)dims[0] * unsigned(part) / unsigned(parts));
  const hsize_t end = hsize_t((unsigned long long)dims[0] * unsigned(part + 1) / unsigned(parts));
  std::vector<glm::vec3> out(static_cast<size_t>(end - first));
  if (!out.empty()) {
    const hsize_t start[2] = {first, 0}, count[2] = {end - first, 3};
    H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
    Id memory(H5Screate_simple(2, count, nullptr), H5Sclose);
    // float64 positions are rounded to float32 here (every format's positions are held as float).
    if (bytes == 4) {
      if (H5Dread(ds.get(), H5T_NATIVE_FLOAT, memory.get(), space.get(), H5P_DEFAULT, out.data()) < 0)
        throw InputError(w + ": reading the positions failed (a truncated or damaged file?)" + hdf5::because());
    } else {
      std::vector<double> v(out.size() * 3);
      if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(), H5P_DEFAULT, v.data()) < 0)
        throw InputError(w + ": reading the positions failed (a truncated or damaged file?)" + hdf5::because());
      for (size_t i = 0; i < out.size(); ++i)
        out[i] = {float(v[3 * i]), float(v[3 * i + 1]), float(v[3 * i + 2])};
    }
  }
  return out;
}

}  // namespace sortlast
