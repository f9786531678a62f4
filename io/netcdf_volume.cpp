// NetCDF volumes (classic or NetCDF-4, through Debian's libnetcdf-mpi, which is built on the same
// parallel HDF5 as io/hdf5_volume.cpp): the variable found and described, spacing from uniform
// coordinate variables, and any box read by nc_get_vara (independent access, every reader).
#include <netcdf.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/error.h"
#include "io/volume_source.h"

namespace sortlast {

namespace {

std::string where(const VolumeDesc& d) { return "volume.file " + d.file + ": variable " + d.variable; }

struct File {
  int id = -1;
  File(const VolumeDesc& d) {
    const int status = nc_open(d.file.c_str(), NC_NOWRITE, &id);
    if (status != NC_NOERR)
      throw InputError("volume.file " + d.file + ": cannot open as NetCDF (" + nc_strerror(status) + ")");
  }
  ~File() { nc_close(id); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
};

std::string typeName(nc_type t) {
  switch (t) {
    case NC_BYTE: return "byte (int8)";
    case NC_CHAR: return "char";
    case NC_SHORT: return "short (int16)";
    case NC_INT: return "int (int32)";
    case NC_FLOAT: return "float";
    case NC_DOUBLE: return "double";
    case NC_UBYTE: return "ubyte (uint8)";
    case NC_USHORT: return "ushort (uint16)";
    case NC_UINT: return "uint (uint32)";
    case NC_INT64: return "int64";
    case NC_UINT64: return "uint64";
    case NC_STRING: return "string";
    default: return "user-defined type " + std::to_string(t);
  }
}

struct Var {
  int id = -1;
  std::string name;
  nc_type type = NC_NAT;
  int ndims = 0;
  int dims[NC_MAX_VAR_DIMS] = {};
};

Var inquire(int nc, int id) {
  Var v;
  v.id = id;
  char name[NC_MAX_NAME + 1] = {};
  nc_inq_var(nc, id, name, &v.type, &v.ndims, v.dims, nullptr);
  v.name = name;
  return v;
}

std::string dimName(int nc, int dim) {
  char name[NC_MAX_NAME + 1] = {};
  nc_inq_dimname(nc, dim, name);
  return name;
}

size_t dimLength(int nc, int dim) {
  size_t n = 0;
  nc_inq_dimlen(nc, dim, &n);
  return n;
}

bool isUnlimited(int nc, int dim) {
  int n = 0;
  int ids[NC_MAX_DIMS];
  if (nc_inq_unlimdims(nc, &n, ids) != NC_NOERR) return false;
  for (int i = 0; i < n; ++i)
    if (ids[i] == dim) return true;
  return false;
}

// A record dimension in front of three spatial ones: unlimited, or named time.
bool isTimeSeries(int nc, const Var& v) {
  return v.ndims == 4 && (isUnlimited(nc, v.dims[0]) || dimName(nc, v.dims[0]) == "time");
}

bool hasAttribute(int nc, int var, const char* name) {
  int att = 0;
  return nc_inq_attid(nc, var, name, &att) == NC_NOERR;
}

// Spacing (and origin, checked) of one axis from its coordinate variable, if there is one.
std::optional<double> coordinateSpacing(int nc, int dim, const VolumeDesc& d) {
  const std::string name = dimName(nc, dim);
  int id = -1;
  if (nc_inq_varid(nc, name.c_str(), &id) != NC_NOERR) return std::nullopt;
  const Var c = inquire(nc, id);
  if (c.ndims != 1 || c.dims[0] != dim) return std::nullopt;  // not a coordinate variable
  const std::string what = "volume.file " + d.file + ": coordinate variable " + name;
  if (c.type == NC_CHAR || c.type == NC_STRING) throw InputError(what + ": holds text, not numbers");
  const size_t n = dimLength(nc, dim);
  std::vector<double> v(n);
  const int status = nc_get_var_double(nc, id, v.data());
  if (status != NC_NOERR) throw InputError(what + ": cannot read (" + std::string(nc_strerror(status)) + ")");
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) throw InputError(what + ": NaN or infinite value at index " + std::to_string(i));
  if (n < 2) return std::nullopt;
  const double step = (v[n - 1] - v[0]) / double(n - 1);
  if (step == 0.0) throw InputError(what + ": all its values are equal (no spacing)");
  for (size_t i = 0; i + 1 < n; ++i) {
    const double s = v[i + 1] - v[i];
    if (std::abs(s - step) > 1e-6 * std::abs(step))
      throw InputError(what + ": not uniform (from index " + std::to_string(i) + " to " +
                       std::to_string(i + 1) + " the step is " + std::to_string(s) + ", the mean step " +
                       std::to_string(step) + "); sortlast does not resample non-uniform grids");
  }
  return std::abs(step);
}

void getBox(int nc, const VolumeDesc& d, int var, const size_t* start, const size_t* count, void* out) {
  int status = NC_NOERR;
  switch (d.type) {
    case SampleType::kUint8: status = nc_get_vara_uchar(nc, var, start, count, static_cast<unsigned char*>(out)); break;
    case SampleType::kUint16: status = nc_get_vara_ushort(nc, var, start, count, static_cast<unsigned short*>(out)); break;
    case SampleType::kInt16: status = nc_get_vara_short(nc, var, start, count, static_cast<short*>(out)); break;
    case SampleType::kFloat32: status = nc_get_vara_float(nc, var, start, count, static_cast<float*>(out)); break;
    case SampleType::kFloat64: status = nc_get_vara_double(nc, var, start, count, static_cast<double*>(out)); break;
  }
  if (status != NC_NOERR)
    throw InputError(where(d) + ": reading a brick failed (" + std::string(nc_strerror(status)) + "; a truncated file?)");
}

}  // namespace

void describeNetcdf(VolumeDesc& d) {
  File f(d);
  const std::string file = "volume.file " + d.file;
  int nvars = 0;
  nc_inq_nvars(f.id, &nvars);
  if (d.variable.empty()) {
    std::vector<std::string> volumes;
    for (int i = 0; i < nvars; ++i) {
      const Var v = inquire(f.id, i);
      if (v.ndims == 3 || isTimeSeries(f.id, v)) volumes.push_back(v.name);
    }
    if (volumes.empty()) throw InputError(file + ": no 3-D variable in the file; volume.variable names the one to read");
    if (volumes.size() > 1) {
      std::string list;
      for (size_t i = 0; i < volumes.size(); ++i) list += (i ? ", " : "") + volumes[i];
      throw InputError(file + ": the file holds " + std::to_string(volumes.size()) + " 3-D variables (" + list +
                       "): set volume.variable to the one to read");
    }
    d.variable = volumes.front();
  }
  const std::string w = where(d);
  int id = -1;
  if (nc_inq_varid(f.id, d.variable.c_str(), &id) != NC_NOERR) throw InputError(w + ": no such variable in the file");
  const Var v = inquire(f.id, id);
  int first = 0;  // the first spatial dimension
  d.record = -1;
  d.records = 1;
  if (v.ndims == 4) {
    if (!isTimeSeries(f.id, v))
      throw InputError(w + ": the variable has 4 dimensions, and the first (" + dimName(f.id, v.dims[0]) +
                       ") is neither unlimited nor named time");
    // A time series: time.step picks the record (scene.cpp counts them as the scene's steps).
    const size_t records = dimLength(f.id, v.dims[0]);
    if (records == 0) throw InputError(w + ": the variable has no records along " + dimName(f.id, v.dims[0]));
    if (records > size_t(1) << 20)
      throw InputError(w + ": " + std::to_string(records) + " records along " + dimName(f.id, v.dims[0]) + ", beyond 2^20");
    d.records = int(records);
    if (d.step < 0 || d.step >= d.records)
      throw InputError(w + ": time step " + std::to_string(d.step) + " is out of range: the variable holds " +
                       std::to_string(records) + " record(s) along " + dimName(f.id, v.dims[0]));
    d.record = d.step;
    first = 1;
  } else if (v.ndims != 3) {
    throw InputError(w + ": the variable has " + std::to_string(v.ndims) +
                     " dimension(s), not 3 (or 4 with a time dimension first)");
  }
  switch (v.type) {
    case NC_UBYTE: d.type = SampleType::kUint8; break;
    case NC_USHORT: d.type = SampleType::kUint16; break;
    case NC_SHORT: d.type = SampleType::kInt16; break;
    case NC_FLOAT: d.type = SampleType::kFloat32; break;
    case NC_DOUBLE: d.type = SampleType::kFloat64; break;
    default:
      throw InputError(w + ": samples of type " + typeName(v.type) +
                       " are not supported (ubyte, ushort, short, float, double)");
  }
  for (const char* packed : {"scale_factor", "add_offset"})
    if (hasAttribute(f.id, id, packed))
      throw InputError(w + ": has the attribute " + packed +
                       " (packed data); unpacking is not supported: store the values themselves");
  glm::ivec3 dims;
  glm::dvec3 spacing = d.grid.spacing;
  for (int k = 0; k < 3; ++k) {  // k: position among the spatial dimensions, slowest first
    const int dim = v.dims[first + k];
    const size_t n = dimLength(f.id, dim);
    if (n > size_t(1) << 20)
      throw InputError(w + ": dimension " + dimName(f.id, dim) + " has " + std::to_string(n) + " samples, beyond 2^20");
    const int axis = d.xyz() ? k : 2 - k;
    dims[axis] = int(n);
    if (const auto s = coordinateSpacing(f.id, dim, d)) spacing[axis] = *s;
  }
  d.grid.dims = dims;
  d.grid.spacing = spacing;
  d.fill_values.clear();
  for (const char* name : {"_FillValue", "missing_value"}) {
    nc_type t = NC_NAT;
    size_t len = 0;
    if (nc_inq_att(f.id, id, name, &t, &len) != NC_NOERR) continue;
    if (t == NC_CHAR || t == NC_STRING) throw InputError(w + ": attribute " + name + " holds text, not a number");
    std::vector<double> values(len);
    if (len > 0 && nc_get_att_double(f.id, id, name, values.data()) != NC_NOERR)
      throw InputError(w + ": cannot read its attribute " + name);
    for (double x : values) d.fill_values.emplace_back(name, x);
  }
}

std::vector<float> readNetcdfBox(const VolumeDesc& d, const IndexBox& box) {
  File f(d);
  int id = -1;
  if (nc_inq_varid(f.id, d.variable.c_str(), &id) != NC_NOERR) throw InputError(where(d) + ": no such variable in the file");
  const glm::ivec3 s = box.size();
  size_t start[4], count[4];
  int k = 0;
  if (d.record >= 0) start[k] = size_t(d.record), count[k++] = 1;
  const glm::ivec3 order = d.xyz() ? glm::ivec3(0, 1, 2) : glm::ivec3(2, 1, 0);
  for (int i = 0; i < 3; ++i, ++k) start[k] = size_t(box.lo[order[i]]), count[k] = size_t(s[order[i]]);
  std::vector<float> out(size_t(box.count()));
  const bool in_place = d.type == SampleType::kFloat32 && !d.xyz();
  std::vector<unsigned char> file_data(in_place ? 0 : out.size() * sampleTypeBytes(d.type));
  void* buffer = in_place ? static_cast<void*>(out.data()) : file_data.data();
  getBox(f.id, d, id, start, count, buffer);
  unpackBox(buffer, d.type, d.xyz(), box, out.data(), where(d), d.fill_values);
  return out;
}

}  // namespace sortlast
