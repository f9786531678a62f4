#pragma once
// Where the volume's samples come from, and reading any sub-box of them. Every reader returns just
// the samples of the box asked for (x fastest), so a rank never holds more than its own bricks.
#include <string>
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
enum class VolumeFormat { kRaw, kVti, kLegacyVtk, kNrrd };

struct VolumeDesc {
  std::string file;                     // empty: procedural
  std::string format = "auto";          // volume.format: auto | raw | vtk | nrrd
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

  bool isProcedural() const { return file.empty(); }
  VolumeFormat formatOf() const;
  // Legacy .vtk is read whole by one rank and scattered (VTK's legacy reader cannot read a part);
  // every other format is read per brick by the brick's owner.
  bool readsWhole() const { return !isProcedural() && formatOf() == VolumeFormat::kLegacyVtk; }
  bool isVtk() const;  // .vti or legacy .vtk (format vtk): dims and spacing from the file
};

// Checks what can be checked without reading samples (file exists, size matches dims and type)
// and, for VTK files, fills in dims and spacing from the file. Throws InputError.
void validateVolume(VolumeDesc& desc);

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
// Any format: the whole volume (the CPU reference and adaptive sampling's preprocessing).
std::vector<float> readWholeVolume(const VolumeDesc& desc);

// Copy `box` out of a whole-volume array.
std::vector<float> extractBox(const std::vector<float>& whole, const glm::ivec3& dims,
                              const IndexBox& box);

// Procedural fields, defined on normalised coordinates u in [-1, 1]^3; values in [0, 1].
double proceduralValue(const std::string& name, const glm::dvec3& u);

}  // namespace sortlast
