// HDF5 volumes: the dataset found and described (validateVolume) and any box of it read with the
// default (sec2) driver, independently: the CPU reference, adaptive preprocessing and tests. The
// session's ranks read their bricks collectively through MPI-IO (session/hdf5_loading.cpp).
// Only the HDF5 readers include hdf5.h (io/hdf5_detail.h).
#include <climits>
#include <cmath>
#include <vector>

#include "common/error.h"
#include "io/hdf5_detail.h"
#include "io/volume_source.h"

namespace sortlast {
namespace hdf5 {

void quiet() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {

herr_t firstError(unsigned n, const H5E_error2_t* e, void* data) {
  if (n == 0 && e && e->desc) *static_cast<std::string*>(data) = e->desc;
  return 0;
}

std::string dimsText(const glm::ivec3& d) {
  return "[" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " + std::to_string(d.z) + "]";
}

// The name of an HDF5 type for messages: int32, uint64, float16, compound, string, ...
std::string typeName(hid_t type) {
  const size_t bits = H5Tget_size(type) * 8;
  switch (H5Tget_class(type)) {
    case H5T_INTEGER: return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
    case H5T_FLOAT: return "float" + std::to_string(bits);
    case H5T_STRING: return "string";
    case H5T_COMPOUND: return "compound";
    case H5T_ENUM: return "enum";
    case H5T_ARRAY: return "array";
    case H5T_VLEN: return "variable-length";
    case H5T_OPAQUE: return "opaque";
    case H5T_BITFIELD: return "bitfield";
    case H5T_REFERENCE: return "reference";
    case H5T_TIME: return "time";
    default: return "unknown";
  }
}

// Every 3-D dataset of the file (paths from the root), and how many datasets it holds in all.
struct Inventory {
  std::vector<std::string> three_d;
  int datasets = 0;
};

herr_t visitLink(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  if (info->type != H5L_TYPE_HARD) return 0;
  Id obj(H5Oopen(group, name, H5P_DEFAULT), H5Oclose);
  if (!obj.ok() || H5Iget_type(obj.get()) != H5I_DATASET) return 0;
  auto& inv = *static_cast<Inventory*>(data);
  ++inv.datasets;
  Id space(H5Dget_space(obj.get()), H5Sclose);
  if (space.ok() && H5Sget_simple_extent_ndims(space.get()) == 3) inv.three_d.push_back("/" + std::string(name));
  return 0;
}

std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < 8; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > 8) out += ", ...";
  return out;
}

// Three numbers from an attribute of the dataset (or, failing that, of the root group), in the
// dataset's dimension order, returned as x y z.
glm::dvec3 readTriple(hid_t file, hid_t dataset, const VolumeDesc& d, const std::string& key,
                      const std::string& name) {
  const std::string what = where(d) + ": " + key + " '" + name + "'";
  hid_t owner = dataset;
  if (H5Aexists(dataset, name.c_str()) <= 0) {
    if (H5Aexists_by_name(file, "/", name.c_str(), H5P_DEFAULT) <= 0)
      throw InputError(what + ": no such attribute on the dataset or on the file's root group");
    owner = -1;
  }
  Id attr(owner >= 0 ? H5Aopen(owner, name.c_str(), H5P_DEFAULT)
                     : H5Aopen_by_name(file, "/", name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose);
  if (!attr.ok()) throw InputError(what + ": cannot open the attribute" + because());
  Id type(H5Aget_type(attr.get()), H5Tclose);
  const H5T_class_t c = H5Tget_class(type.get());
  if (c != H5T_INTEGER && c != H5T_FLOAT)
    throw InputError(what + ": the attribute is of type " + typeName(type.get()) + ", not numbers");
  Id space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n != 3) throw InputError(what + ": the attribute holds " + std::to_string(n) + " values, not 3");
  double v[3];
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, v) < 0)
    throw InputError(what + ": cannot read the attribute" + because());
  for (double x : v)
    if (!std::isfinite(x)) throw InputError(what + ": the attribute holds a NaN or infinite value");
  return d.xyz() ? glm::dvec3(v[0], v[1], v[2]) : glm::dvec3(v[2], v[1], v[0]);
}

}  // namespace

std::string reason() {
  std::string out;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, firstError, &out);
  return out;
}

std::string because() {
  const std::string r = reason();
  return r.empty() ? std::string() : " (HDF5: " + r + ")";
}

std::string where(const VolumeDesc& d) { return "volume.file " + d.file + ": dataset " + d.dataset; }

hid_t memoryType(SampleType t) {
  switch (t) {
    case SampleType::kUint8: return H5T_NATIVE_UINT8;
    case SampleType::kUint16: return H5T_NATIVE_UINT16;
    case SampleType::kInt16: return H5T_NATIVE_INT16;
    case SampleType::kFloat32: return H5T_NATIVE_FLOAT;
    case SampleType::kFloat64: return H5T_NATIVE_DOUBLE;
  }
  return H5T_NATIVE_FLOAT;
}

Id openVolumeDataset(hid_t file, const VolumeDesc& d) {
  Id ds(H5Dopen2(file, d.dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(where(d) + ": cannot open the dataset" + because());
  Id space(H5Dget_space(ds.get()), H5Sclose);
  hsize_t dims[3];
  if (H5Sget_simple_extent_ndims(space.get()) != 3 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) != 3)
    throw InputError(where(d) + ": the dataset is no longer 3-D");
  const glm::ivec3 grid = d.xyz() ? glm::ivec3(int(dims[0]), int(dims[1]), int(dims[2]))
                                  : glm::ivec3(int(dims[2]), int(dims[1]), int(dims[0]));
  if (grid != d.grid.dims)
    throw InputError(where(d) + ": the dataset's dims " + dimsText(grid) + " are not the " +
                     dimsText(d.grid.dims) + " read when the scene was loaded");
  return ds;
}

void selectBox(hid_t file_space, const VolumeDesc& d, const IndexBox& box) {
  const glm::ivec3 s = box.size();
  hsize_t start[3], count[3];
  if (d.xyz()) {
    start[0] = hsize_t(box.lo.x), start[1] = hsize_t(box.lo.y), start[2] = hsize_t(box.lo.z);
    count[0] = hsize_t(s.x), count[1] = hsize_t(s.y), count[2] = hsize_t(s.z);
  } else {
    start[0] = hsize_t(box.lo.z), start[1] = hsize_t(box.lo.y), start[2] = hsize_t(box.lo.x);
    count[0] = hsize_t(s.z), count[1] = hsize_t(s.y), count[2] = hsize_t(s.x);
  }
  if (H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr) < 0)
    throw InputError("volume.file " + d.file + ": dataset " + d.dataset + ": cannot select the box" + because());
}

}  // namespace hdf5

using hdf5::Id;

void describeHdf5(VolumeDesc& d) {
  hdf5::quiet();
  const std::string f = "volume.file " + d.file;
  if (H5Fis_hdf5(d.file.c_str()) <= 0) throw InputError(f + ": not an HDF5 file (no HDF5 signature)");
  Id file(H5Fopen(d.file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw InputError(f + ": cannot open as HDF5 (a truncated or damaged file?)" + hdf5::because());
  if (d.dataset.empty()) {
    hdf5::Inventory inv;
    if (H5Lvisit(file.get(), H5_INDEX_NAME, H5_ITER_INC, hdf5::visitLink, &inv) < 0)
      throw InputError(f + ": cannot list the file's datasets" + hdf5::because());
    if (inv.three_d.empty())
      throw InputError(f + ": no 3-D dataset in the file (" + std::to_string(inv.datasets) +
                       " dataset(s) of other ranks); volume.dataset names the one to read");
    if (inv.three_d.size() > 1)
      throw InputError(f + ": the file holds " + std::to_string(inv.three_d.size()) + " 3-D datasets (" +
                       hdf5::listed(inv.three_d) + "): set volume.dataset to the one to read");
    d.dataset = inv.three_d.front();
  }
  const std::string w = hdf5::where(d);
  if (H5Lexists(file.get(), d.dataset.c_str(), H5P_DEFAULT) <= 0) {
    hdf5::Inventory inv;
    H5Lvisit(file.get(), H5_INDEX_NAME, H5_ITER_INC, hdf5::visitLink, &inv);
    throw InputError(w + ": no such dataset in the file" +
                     (inv.three_d.empty() ? std::string(" (it has no 3-D dataset)")
                                          : " (its 3-D datasets: " + hdf5::listed(inv.three_d) + ")"));
  }
  Id ds(H5Dopen2(file.get(), d.dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) throw InputError(w + ": not a dataset (a group?)" + hdf5::because());
  Id space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 3) throw InputError(w + ": the dataset has " + std::to_string(rank) + " dimension(s), not 3");
  hsize_t dims[3];
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  for (hsize_t n : dims)
    if (n > hsize_t(1) << 20)
      throw InputError(w + ": a dimension of " + std::to_string(n) + " samples is beyond 2^20");
  d.grid.dims = d.xyz() ? glm::ivec3(int(dims[0]), int(dims[1]), int(dims[2]))
                        : glm::ivec3(int(dims[2]), int(dims[1]), int(dims[0]));
  Id type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t c = H5Tget_class(type.get());
  const size_t bytes = H5Tget_size(type.get());
  const bool is_signed = c == H5T_INTEGER && H5Tget_sign(type.get()) != H5T_SGN_NONE;
  if (c == H5T_INTEGER && bytes == 1 && !is_signed) d.type = SampleType::kUint8;
  else if (c == H5T_INTEGER && bytes == 2) d.type = is_signed ? SampleType::kInt16 : SampleType::kUint16;
  else if (c == H5T_FLOAT && bytes == 4) d.type = SampleType::kFloat32;
  else if (c == H5T_FLOAT && bytes == 8) d.type = SampleType::kFloat64;
  else
    throw InputError(w + ": samples of type " + hdf5::typeName(type.get()) +
                     " are not supported (uint8, uint16, int16, float32, float64)");
  if (!d.spacing_attribute.empty()) {
    const glm::dvec3 s = hdf5::readTriple(file.get(), ds.get(), d, "volume.spacing_attribute", d.spacing_attribute);
    for (int a = 0; a < 3; ++a)
      if (!(s[a] > 0.0))
        throw InputError(w + ": volume.spacing_attribute '" + d.spacing_attribute +
                         "': every spacing must be > 0, got " + std::to_string(s[a]));
    d.grid.spacing = s;
  }
  // The origin is checked, not used: every volume is centred on the world origin (common/grid.h).
  if (!d.origin_attribute.empty())
    hdf5::readTriple(file.get(), ds.get(), d, "volume.origin_attribute", d.origin_attribute);
}

namespace {
// H5Lexists on each component of an absolute path in turn (it fails, rather than answering no,
// where a group on the way is missing).
bool pathExists(hid_t file, const std::string& path) {
  for (size_t slash = path.find('/', 1);; slash = path.find('/', slash + 1)) {
    const std::string part = path.substr(0, slash);
    if (!part.empty() && part != "/" && H5Lexists(file, part.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
  }
}
}  // namespace

std::string hdf5StepPath(const std::string& dataset, int step) {
  std::string out = dataset;
  for (size_t at = out.find("{step}"); at != std::string::npos; at = out.find("{step}", at))
    out.replace(at, 6, std::to_string(step));
  return out;
}

int countHdf5Steps(const VolumeDesc& d) {
  hdf5::quiet();
  const std::string f = "volume.file " + d.file;
  if (H5Fis_hdf5(d.file.c_str()) <= 0) throw InputError(f + ": not an HDF5 file (no HDF5 signature)");
  Id file(H5Fopen(d.file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw InputError(f + ": cannot open as HDF5 (a truncated or damaged file?)" + hdf5::because());
  const std::string dataset = d.dataset.front() == '/' ? d.dataset : "/" + d.dataset;
  int steps = 0;
  while (steps < (1 << 20) && pathExists(file.get(), hdf5StepPath(dataset, steps))) ++steps;
  if (steps == 0)
    throw InputError(f + ": volume.dataset " + d.dataset + ": no dataset " + hdf5StepPath(dataset, 0) +
                     " for step 0 (a series' steps are numbered 0, 1, 2, ... without padding)");
  return steps;
}

std::vector<float> readHdf5Box(const VolumeDesc& d, const IndexBox& box) {
  hdf5::quiet();
  Id file(H5Fopen(d.file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok())
    throw InputError("volume.file " + d.file + ": cannot open as HDF5 (a truncated or damaged file?)" + hdf5::because());
  Id ds = hdf5::openVolumeDataset(file.get(), d);
  Id file_space(H5Dget_space(ds.get()), H5Sclose);
  hdf5::selectBox(file_space.get(), d, box);
  const hsize_t n = hsize_t(box.count());
  Id memory_space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  std::vector<float> out(static_cast<size_t>(n));
  // float32 in z y x order is the output's layout already: read in place.
  const bool in_place = d.type == SampleType::kFloat32 && !d.xyz();
  std::vector<unsigned char> file_data(in_place ? 0 : size_t(n) * sampleTypeBytes(d.type));
  void* buffer = in_place ? static_cast<void*>(out.data()) : file_data.data();
  if (H5Dread(ds.get(), hdf5::memoryType(d.type), memory_space.get(), file_space.get(), H5P_DEFAULT, buffer) < 0)
    throw InputError(hdf5::where(d) + ": reading the box " + hdf5::dimsText(box.lo) + " - " +
                     hdf5::dimsText(box.hi) + " failed (a truncated or damaged file?)" + hdf5::because());
  unpackBox(buffer, d.type, d.xyz(), box, out.data(), hdf5::where(d));
  return out;
}

}  // namespace sortlast
