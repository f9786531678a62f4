#pragma once
// Where the volume's samples come from, and reading any sub-box of them. Every reader returns just
// the samples of the box asked for (x fastest), so a rank never holds more than its own bricks.
#include <string>
#include <vector>

#include "common/box.h"
#include "common/grid.h"

namespace sortlast {

enum class SampleType { kUint8, kUint16, kInt16, kFloat32 };
int sampleTypeBytes(SampleType t);

struct VolumeDesc {
  std::string file;                     // empty: procedural
  std::string procedural = "blobs";     // blobs | marschner_lobb | sphere
  GridGeometry grid{{128, 128, 128}, {1.0, 1.0, 1.0}};
  SampleType type = SampleType::kUint8;
  bool big_endian = false;
  long long header_bytes = 0;

  bool isProcedural() const { return file.empty(); }
  bool isVtk() const;  // .vti or .vtk: read with VTK
};

// Checks what can be checked without reading samples (file exists, size matches dims and type)
// and, for VTK files, fills in dims and spacing from the file. Throws InputError.
void validateVolume(VolumeDesc& desc);

// Samples of `box` as float (x fastest). Raw files are read with one seek per row; NaN or
// infinite values are rejected with the voxel's index. VTK files: see readWholeVtk.
std::vector<float> readSamples(const VolumeDesc& desc, const IndexBox& box);

// Dims and spacing from a VTK image file's header (VTK reads only the metadata).
void readVtkGeometry(VolumeDesc& desc);

// The whole VTK image (x fastest) as float; the caller scatters it (one rank reads).
std::vector<float> readWholeVtk(const VolumeDesc& desc);

// Copy `box` out of a whole-volume array.
std::vector<float> extractBox(const std::vector<float>& whole, const glm::ivec3& dims,
                              const IndexBox& box);

// Procedural fields, defined on normalised coordinates u in [-1, 1]^3; values in [0, 1].
double proceduralValue(const std::string& name, const glm::dvec3& u);

}  // namespace sortlast
