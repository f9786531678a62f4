#pragma once
// Where the volume's samples come from, and reading any sub-box of them. Every reader returns just
// the samples of the box asked for (x fastest), so a rank never holds more than its own bricks.
#include <string>
#include <utility>
#include <vector>

#include "common/box.h"
#include "common/grid.h"

namespace sortlast {

enum class SampleType { kUint8, kUint16, kInt16, kFloat32, kFloat64 };
constexpr int sampleTypeBytes(SampleType t) {
  switch (t) {
    case SampleType::kUint8: return 1;
    case SampleType::kUint16:
    case SampleType::kInt16: return 2;
    case SampleType::kFloat32: return 4;
    case SampleType::kFloat64: return 8;
  }
  return 1;
}

// How volume.file is read (volume.format; `auto`: by the file's extension, formatOf()).
enum class VolumeFormat { kRaw, kVti, kLegacyVtk, kNrrd, kHdf5, kNetcdf };

struct VolumeDesc {
  std::string file;                     // empty: procedural
  std::string format = "auto";          // volume.format: auto | raw | vtk | nrrd | hdf5 | netcdf
  std::string procedural = "blobs";     // blobs | marschner_lobb | sphere
  GridGeometry grid{{128, 128, 128}, {1.0, 1.0, 1.0}};
  SampleType type = SampleType::kUint8;
  bool big_endian = false;
  long long header_bytes = 0;
  // Filled in by validateVolume from a NRRD header: the file holding the samples (detached .nhdr
  // data; empty: `file` itself) and whether they are gzip-compressed.
  std::string data_file;
  bool gzip = false;        // header_bytes is then where the gzip stream starts in data_file
  long long gzip_skip = 0;  // bytes of the decompressed stream before the samples
  // HDF5 and NetCDF (io/hdf5_volume.cpp, io/netcdf_volume.cpp). Both store arrays in C
  // order (the last dimension fastest): `zyx` (the default) reads the first dimension as z, the
  // last as x; `xyz` the first as x (a Fortran-order writer's array, or one transposed).
  std::string dataset;            // HDF5 path (volume.dataset; found by validateVolume if empty)
  std::string variable;           // NetCDF variable (volume.variable; found if empty)
  std::string axis_order = "zyx";  // volume.axis_order: zyx | xyz
  std::string spacing_attribute;  // HDF5: the attribute holding the spacing (empty: scene keys)
  std::string origin_attribute;   // HDF5: the attribute holding the origin (checked, not used)
  std::string mpi_io = "auto";  // HDF5 in a session: auto | collective | independent transfers
  // time.step where the steps are inside the file (the records of a 4-D NetCDF variable).
  int step = 0;
  // Filled in by validateVolume from a NetCDF file: the records along a 4-D variable's time
  // dimension (1 for 3-D), the one read (`step`; -1: 3-D) and the values that mark missing
  // samples (_FillValue, missing_value), which become NaN: transparent.
  int records = 1;
  int record = -1;
  std::vector<std::pair<std::string, double>> fill_values;  // (attribute, value)

  bool isProcedural() const { return file.empty(); }
  VolumeFormat formatOf() const;
  // Legacy .vtk is read whole by one rank and scattered (VTK's legacy reader cannot read a part);
  // every other format is read per brick by the brick's owner.
  bool readsWhole() const { return !isProcedural() && formatOf() == VolumeFormat::kLegacyVtk; }
  bool isVtk() const;  // .vti or legacy .vtk (format vtk): dims and spacing from the file
  bool xyz() const { return axis_order == "xyz"; }
};

// Checks what can be checked without reading samples (file exists, size matches dims and type)
// and, for VTK files, fills in dims and spacing from the file. Throws InputError.
void validateVolume(VolumeDesc& desc);
// Refuses a volume file whose format this build was configured without (VTK, HDF5, NetCDF), with
// the CMake option that builds it; validateVolume calls it first.
void requireVolumeFormatBuilt(const VolumeDesc& desc);

// Samples of `box` as float (x fastest), read from the file's format: raw and NRRD raw with one
// seek per row, NRRD gzip as one stream up to the box's last row, .vti through VTK for the box's
// extent alone. NaN or infinite values are rejected with the voxel's index. Legacy .vtk: see
// readWholeVtk (readsWhole()).
std::vector<float> readSamples(const VolumeDesc& desc, const IndexBox& box);

// Dims and spacing from a VTK image file's header (VTK reads only the metadata).
void readVtkGeometry(VolumeDesc& desc);

// The whole VTK image (x fastest) as float; the caller scatters it (one rank reads).
std::vector<float> readWholeVtk(const VolumeDesc& desc);
// A .vti file's samples of `box` only: VTK's XML reader asked for the box's extent.
std::vector<float> readVtiBox(const VolumeDesc& desc, const IndexBox& box);
// HDF5 (io/hdf5_volume.cpp): the dataset found and checked (rank 3, type), dims, type,
// spacing and origin from it; and one box read independently (the default file driver). The
// session's ranks read their bricks collectively instead (session/hdf5_loading.h).
void describeHdf5(VolumeDesc& desc);
std::vector<float> readHdf5Box(const VolumeDesc& desc, const IndexBox& box);
// An HDF5 time series inside one file: volume.dataset with `{step}` (`/step_{step}/density`).
// hdf5StepPath: the path of one step ({step} replaced by its number, no padding); countHdf5Steps:
// the steps 0, 1, 2, ... whose dataset exists (throws where step 0 has none).
std::string hdf5StepPath(const std::string& dataset, int step);
int countHdf5Steps(const VolumeDesc& desc);
// NetCDF (io/netcdf_volume.cpp): the variable found and checked, dims, type, spacing from
// uniform coordinate variables, fill values; one box by nc_get_vara.
void describeNetcdf(VolumeDesc& desc);
std::vector<float> readNetcdfBox(const VolumeDesc& desc, const IndexBox& box);

// The samples of `box` from an array read in C order over the box (slowest axis z, or x when
// `xyz`) in the file's type `type`, into `out` as float, x fastest. `in` may be `out` itself for
// float32 zyx (then element i is read before it is written). Refuses NaN, infinite values and any
// of `fills`, naming the voxel: `where` starts the message ("volume.file F: dataset /d").
void unpackBox(const void* in, SampleType type, bool xyz, const IndexBox& box, float* out,
               const std::string& where,
               const std::vector<std::pair<std::string, double>>& fills = {});

// Any format: the whole volume (the CPU reference and adaptive sampling's preprocessing).
std::vector<float> readWholeVolume(const VolumeDesc& desc);

// Widens [lo, hi] by the n values at v, missing ones (NaN) left out (every comparison with NaN
// is false). The one loop the data range, the reference's range and block ranges share.
inline void widenRange(const float* v, size_t n, float& lo, float& hi) {
  for (size_t i = 0; i < n; ++i) {
    lo = v[i] < lo ? v[i] : lo;
    hi = v[i] > hi ? v[i] : hi;
  }
}

// The smallest and largest of `samples`, missing ones (NaN) left out; throws InputError when every
// sample is missing (there is then no range to scale a transfer function to).
// `file` is named in the message.
std::pair<float, float> presentRange(const std::vector<float>& samples, const std::string& file);
// The message of that error, for the ranks that reduce their ranges first.
std::string allSamplesMissing(const std::string& file);

// Copy `box` out of a whole-volume array.
std::vector<float> extractBox(const std::vector<float>& whole, const glm::ivec3& dims,
                              const IndexBox& box);

// Procedural fields, defined on normalised coordinates u in [-1, 1]^3; values in [0, 1].
double proceduralValue(const std::string& name, const glm::dvec3& u);

}  // namespace sortlast
