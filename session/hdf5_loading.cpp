#include "session/hdf5_loading.h"

#include <algorithm>
#include <string>

#include "common/error.h"
#include "io/hdf5_detail.h"
#include "session/collective.h"

namespace sortlast {

using hdf5::Id;

namespace {

// volume.mpi_io: auto is collective when the ranks span more than one node, independent on one:
// there every rank reads the same page cache, and aggregation bought nothing but a copy and the
// aggregator's buffer (results/io: 1.57x raw's time and 16 MiB over the memory bound, against
// 1.29x and within it). Collective (MPI_Comm_split_type).
bool collectiveTransfers(const VolumeDesc& desc, MPI_Comm comm) {
  if (desc.mpi_io != "auto") return desc.mpi_io == "collective";
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int node_size = 1, size = 1;
  MPI_Comm_size(node, &node_size);
  MPI_Comm_size(comm, &size);
  MPI_Comm_free(&node);
  return node_size < size;  // the same answer on every rank: one node holds all or none
}

}  // namespace

bool hdf5ReadsCollectively(const VolumeDesc& desc, MPI_Comm comm) {
  return collectiveTransfers(desc, comm);
}

std::vector<std::vector<float>> readHdf5Collective(const VolumeDesc& desc,
                                                   const std::vector<IndexBox>& boxes, MPI_Comm comm) {
  int reads = int(boxes.size()), most = 0;
  MPI_Allreduce(&reads, &most, 1, MPI_INT, MPI_MAX, comm);
  const bool in_place = desc.type == SampleType::kFloat32 && !desc.xyz();
  const bool collective = collectiveTransfers(desc, comm);
  std::vector<std::vector<float>> out(boxes.size());
  std::vector<unsigned char> file_data;
  // Memory first: a rank that cannot allocate fails here, before any rank is inside a collective
  // HDF5 call.
  collectively(comm, [&] {
    size_t largest = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
      out[i].resize(size_t(boxes[i].count()));
      largest = std::max(largest, out[i].size());
    }
    if (!in_place) file_data.resize(largest * size_t(sampleTypeBytes(desc.type)));
  });
  // Then the file. validateVolume has already opened it and checked the dataset on every rank
  // (independently), so what fails here is the same on every rank (the open) or is held (a read,
  // an unpacked NaN) until this rank has made every collective call the others make.
  collectively(comm, [&] {
    hdf5::quiet();
    std::string failed;
    {
      Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
      Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
      if (H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL) < 0 ||
          H5Pset_dxpl_mpio(dxpl.get(), collective ? H5FD_MPIO_COLLECTIVE : H5FD_MPIO_INDEPENDENT) < 0)
        throw InputError("volume.file " + desc.file + ": cannot set up HDF5's MPI-IO driver" + hdf5::because());
      Id file(H5Fopen(desc.file.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);  // collective
      if (!file.ok())
        throw InputError("volume.file " + desc.file + ": cannot open as HDF5 with MPI-IO" + hdf5::because());
      Id ds, file_space, none_memory;
      try {
        ds = hdf5::openVolumeDataset(file.get(), desc);
        file_space = Id(H5Dget_space(ds.get()), H5Sclose);
        const hsize_t one = 1;
        none_memory = Id(H5Screate_simple(1, &one, nullptr), H5Sclose);
        if (!file_space.ok() || !none_memory.ok() || H5Sselect_none(none_memory.get()) < 0)
          throw InputError(hdf5::where(desc) + ": cannot make the dataspaces" + hdf5::because());
      } catch (const std::exception& e) {
        failed = e.what();
      }
      // Every rank learns whether every rank has the dataset open before any collective read.
      int ok = failed.empty() ? 1 : 0, all = 0;
      MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm);
      if (all) {
        float dummy = 0.0f;
        for (int i = 0; i < most; ++i) {
          const bool mine = failed.empty() && i < reads;
          void* buffer = &dummy;
          Id memory_space;
          try {
            if (mine) {
              const IndexBox& box = boxes[size_t(i)];
              hdf5::selectBox(file_space.get(), desc, box);
              const hsize_t n = hsize_t(box.count());
              memory_space = Id(H5Screate_simple(1, &n, nullptr), H5Sclose);
              buffer = in_place ? static_cast<void*>(out[size_t(i)].data()) : file_data.data();
            } else {
              H5Sselect_none(file_space.get());
            }
          } catch (const std::exception& e) {
            failed = e.what();
            H5Sselect_none(file_space.get());
            buffer = &dummy;
            memory_space = Id();
          }
          const bool reading = failed.empty() && mine;
          const hid_t memory = reading ? memory_space.get() : none_memory.get();
          if (H5Dread(ds.get(), hdf5::memoryType(desc.type), memory, file_space.get(), dxpl.get(), buffer) < 0 &&
              reading && failed.empty())
            failed = hdf5::where(desc) + ": collective read of a brick failed (a truncated or damaged file?)" +
                     hdf5::because();
          if (reading && failed.empty()) {
            try {
              unpackBox(buffer, desc.type, desc.xyz(), boxes[size_t(i)], out[size_t(i)].data(), hdf5::where(desc));
            } catch (const std::exception& e) {
              failed = e.what();
            }
          }
        }
      }
    }  // the dataset and the file closed (H5Fclose is collective) on every rank
    if (!failed.empty()) throw InputError(failed);
  });
  return out;
}

}  // namespace sortlast
