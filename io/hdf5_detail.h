#pragma once
// Internal to the HDF5 readers (io/hdf5_volume.cpp, io/hdf5_particles.cpp,
// session/hdf5_loading.cpp): ids that close themselves, HDF5's own error text, and the
// volume dataset's hyperslabs. Include it only from those files: it brings in hdf5.h (Debian's
// parallel build, libhdf5-openmpi, whose headers include mpi.h).
#include <hdf5.h>

#include <string>
#include <utility>

#include "common/box.h"
#include "io/volume_source.h"

namespace sortlast::hdf5 {

// An HDF5 id closed by `close` (H5Fclose, H5Dclose, H5Sclose, H5Tclose, H5Pclose, H5Aclose).
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer close) : id_(id), close_(close) {}
  Id(Id&& o) noexcept : id_(std::exchange(o.id_, -1)), close_(o.close_) {}
  Id& operator=(Id&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, -1);
      close_ = o.close_;
    }
    return *this;
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { reset(); }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

// Turns off HDF5's printing of its error stack (our messages say what went wrong); every reader
// calls it before its first HDF5 call.
void quiet();
// The innermost message on HDF5's error stack (what failed first), or "" when it is empty.
std::string reason();
// " (HDF5: reason)" or "".
std::string because();

// "volume.file F: dataset /d"
std::string where(const VolumeDesc& d);
// The volume dataset of an open file (d.dataset, as validateVolume resolved it), checked against
// the description (rank 3, the dims validateVolume found).
Id openVolumeDataset(hid_t file, const VolumeDesc& d);
// The memory type of the file's samples (the dataset's type as read: native uint8, uint16, int16,
// float or double); the bytes are unpacked by unpackBox.
hid_t memoryType(SampleType t);
// Selects `box` (grid indices, x y z) as a hyperslab of the dataset's file space, in the
// dataset's dimension order (volume.axis_order).
void selectBox(hid_t file_space, const VolumeDesc& d, const IndexBox& box);

}  // namespace sortlast::hdf5
