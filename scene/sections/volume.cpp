// The volume section's keys: the volume: its file or procedural field, grid, sample type and layout
// (io/volume_source.h holds VolumeDesc).
#include "scene/key_rows.h"
#include "scene/scene_reader.h"

std::vector<sortlast::SceneKey> sortlast::volumeKeys() {
  const Check kLength = lengthCheck();
  return {
    {"volume.file", "\"\"",
     "Data file. Empty: a procedural volume (`volume.procedural`). `.vti`: a VTK XML image, each "
     "rank reading its bricks' extent; `.vtk`: a legacy VTK image, read whole by rank 0 and "
     "scattered; `.nrrd`/`.nhdr`: NRRD (raw or gzip encoding, read per brick; docs/data.md); "
     "`.h5`/`.hdf5`: an HDF5 dataset (`volume.dataset`), each rank reading its bricks "
     "collectively through MPI-IO; `.nc`: a NetCDF variable (`volume.variable`), read per brick "
     "(docs/data_hdf5_netcdf.md). For these the file gives dims, spacing and type. Anything else: "
     "raw samples, x fastest, no header unless `volume.header_bytes`. Relative paths are relative "
     "to the scene file.",
     Text{member<&Scene::volume, &VolumeDesc::file>, true}},
    {"volume.format", "auto",
     "How `volume.file` is read: `raw`, `vtk` (.vti or legacy .vtk), `nrrd`, `hdf5`, `netcdf`, or "
     "`auto`: by its extension (`.vti`/`.vtk` vtk, `.nrrd`/`.nhdr` nrrd, `.h5`/`.hdf5` hdf5, `.nc` "
     "netcdf, anything else raw).",
     Choice{member<&Scene::volume, &VolumeDesc::format>,
           names({"auto", "raw", "vtk", "nrrd", "hdf5", "netcdf"})}},
    {"volume.dataset", "\"\"",
     "HDF5: the path of the 3-D dataset to read (`/fields/density`). Empty: the file's only 3-D "
     "dataset (a file with several needs this key). Its type gives the samples' (uint8, uint16, "
     "int16, float32, float64; others are refused). With `{step}` (`/step_{step}/density`) the "
     "file is a time series: steps 0, 1, 2, ... (no padding) while their datasets exist, "
     "`time.step` picks one.",
     Text{member<&Scene::volume, &VolumeDesc::dataset>}},
    {"volume.variable", "\"\"",
     "NetCDF: the variable to read, 3-D, or 4-D with an unlimited (or `time`) first dimension: "
     "a time series, one step per record (`time.step` picks it). Empty: the file's only such variable. Coordinate variables (1-D, "
     "named like a dimension) give the spacing when uniform (within 1e-6 relative; non-uniform "
     "ones are refused); samples equal to `_FillValue` or `missing_value` are missing: a point "
     "whose trilinear stencil touches one is transparent (not with `adaptive.tolerance`).",
     Text{member<&Scene::volume, &VolumeDesc::variable>}},
    {"volume.axis_order", "zyx",
     "HDF5 and NetCDF: which axis each dimension of the array is, slowest (first) to fastest "
     "(last). Both store arrays in C order, so `zyx` (what NumPy's `a[z, y, x]` writes) makes "
     "the last dimension x (a Fortran `a(nx, ny, nz)` written through the Fortran API is stored "
     "so too); `xyz` makes the first dimension x (NumPy's `a[x, y, z]`).",
     Choice{member<&Scene::volume, &VolumeDesc::axis_order>, names({"zyx", "xyz"})}},
    {"volume.spacing_attribute", "\"\"",
     "HDF5: the attribute (of the dataset, else of the root group) holding the spacing, three "
     "numbers in the dataset's dimension order (`zyx`: [dz, dy, dx]). Empty: `volume.spacing`.",
     Text{member<&Scene::volume, &VolumeDesc::spacing_attribute>}},
    {"volume.origin_attribute", "\"\"",
     "HDF5: the attribute holding the origin (three numbers, dimension order). It is read and "
     "checked (finite numbers) but does not move the volume: sortlast centres every volume on "
     "the world origin.",
     Text{member<&Scene::volume, &VolumeDesc::origin_attribute>}},
    {"volume.mpi_io", "auto",
     "HDF5: how the ranks read their bricks through MPI-IO: `collective` (one collective "
     "H5Dread per brick: MPI-IO may aggregate the ranks' requests, what a parallel file system "
     "wants at scale), `independent` (each rank reads alone: on one node or a local disk it "
     "was faster and held less memory, results/io) or `auto`: collective when the ranks span "
     "more than one node, independent on one.",
     Choice{member<&Scene::volume, &VolumeDesc::mpi_io>, names({"auto", "collective", "independent"})}},
    {"volume.procedural", "blobs",
     "Procedural field when there is no file: `blobs` (shells, blobs and a torus), "
     "`marschner_lobb` (the Marschner-Lobb test signal), `sphere` (1 - r), or `none`: no "
     "volume (the scene must then have particles).",
     Text{member<&Scene::volume, &VolumeDesc::procedural>}},
    {"volume.files", "\"\"",
     "A time series: one data file per step, as a list of names or one glob pattern "
     "(`step_*.raw`; matches sorted by name). Each file is read like `volume.file` (same dims, "
     "type and layout for every step); `time.step` picks the step. Excludes `volume.file`.",
     Structured{"list of file names, or a glob pattern"}},
    {"volume.dims", "[128, 128, 128]", "Samples per axis [x, y, z] (raw and procedural volumes).",
     Vector<glm::ivec3>{member<&Scene::volume, &VolumeDesc::grid, &GridGeometry::dims>,
                        {{"integers in [2, 2^20]", "entries must be {allowed}"}}}},
    {"volume.type", "uint8", "Raw sample type.",
     Choice{member<&Scene::volume, &VolumeDesc::type>,
                        {{"uint8", SampleType::kUint8},
                         {"uint16", SampleType::kUint16},
                         {"int16", SampleType::kInt16},
                         {"float32", SampleType::kFloat32},
                         {"float64", SampleType::kFloat64}},
                        "{key}: unknown type '{text}' (known: {list})"}},
    {"volume.spacing", "[1, 1, 1]", "Distance between samples along x, y, z (world units).",
     Vector<glm::dvec3>{member<&Scene::volume, &VolumeDesc::grid, &GridGeometry::spacing>,
                        {kLength}}},
    {"volume.byte_order", "little", "Byte order of raw samples.",
     Choice{member<&Scene::volume, &VolumeDesc::big_endian>,
                  {{"little", false}, {"big", true}}}},
    {"volume.header_bytes", "0", "Bytes to skip at the start of a raw file.",
     Long{member<&Scene::volume, &VolumeDesc::header_bytes>, {{">= 0"}}}},
  };
}

namespace sortlast {

// The volume's extent along each axis must be a length float math on the GPU can hold.
void checkVolumeKeys(const Scene& s) {
  const VolumeDesc& vol = s.volume;
  for (int a = 0; a < 3; ++a)
    requireTable("volume.spacing", vol.grid.spacing[a] * (vol.grid.dims[a] - 1),
                 "volume.spacing (times volume.dims - 1: the volume's extent)");
}

}  // namespace sortlast
