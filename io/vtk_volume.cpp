// Reading .vti (XML) and legacy .vtk image files with VTK. Kept in its own file so only this one
// translation unit sees VTK's headers.
#include <algorithm>
#include <cmath>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkInformation.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStructuredPoints.h>
#include <vtkStructuredPointsReader.h>
#include <vtkXMLImageDataReader.h>

#include "common/error.h"
#include "io/volume_source.h"

namespace sortlast {

namespace {

vtkSmartPointer<vtkImageData> loadImage(const std::string& file, bool metadata_only) {
  bool xml = !(file.size() > 4 && file.substr(file.size() - 4) == ".vtk");
  if (xml) {
    vtkNew<vtkXMLImageDataReader> r;
    if (!r->CanReadFile(file.c_str()))
      throw InputError("volume.file " + file + ": not a readable VTK XML image (.vti) file");
    r->SetFileName(file.c_str());
    if (metadata_only) {
      r->UpdateInformation();
      int ext[6];
      double sp[3];
      r->GetOutputInformation(0)->Get(vtkDataObject::SPACING(), sp);
      r->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), ext);
      auto img = vtkSmartPointer<vtkImageData>::New();
      img->SetExtent(ext);
      img->SetSpacing(sp);
      return img;
    }
    r->Update();
    return r->GetOutput();
  }
  vtkNew<vtkStructuredPointsReader> r;
  r->SetFileName(file.c_str());
  if (!r->IsFileStructuredPoints())
    throw InputError("volume.file " + file +
                     ": not a legacy VTK STRUCTURED_POINTS file (only image data is supported)");
  r->Update();
  return r->GetOutput();
}

// The image's scalars (or its first point array).
vtkDataArray* scalarsOf(vtkImageData* img, const std::string& file) {
  vtkDataArray* a = img->GetPointData() ? img->GetPointData()->GetScalars() : nullptr;
  if (!a && img->GetPointData() && img->GetPointData()->GetNumberOfArrays() > 0)
    a = img->GetPointData()->GetArray(0);
  if (!a) throw InputError("volume.file " + file + ": no point scalars in the image");
  return a;
}

}  // namespace

// The brick is read in slabs of z rows, each through UpdateExtent: VTK's array then holds one slab
// beside ours, not a second copy of the whole brick (results/io: read whole, the brick's VTK copy
// put the peak 3 MiB over the bound of one brick beyond the bricks).
constexpr long long kVtiSlabBytes = 8ll << 20;

std::vector<float> readVtiBox(const VolumeDesc& d, const IndexBox& box) {
  vtkNew<vtkXMLImageDataReader> r;
  if (!r->CanReadFile(d.file.c_str()))
    throw InputError("volume.file " + d.file + ": not a readable VTK XML image (.vti) file");
  r->SetFileName(d.file.c_str());
  r->UpdateInformation();
  int whole[6];
  r->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  const glm::ivec3 n = box.size();
  const long long row_bytes = (long long)n.x * n.y * (long long)sizeof(double);  // the widest type
  const int slab = int(std::clamp<long long>(kVtiSlabBytes / row_bytes, 1, n.z));
  std::vector<float> out(size_t(box.count()));
  size_t o = 0;
  for (int z0 = box.lo.z; z0 <= box.hi.z; z0 += slab) {
    const int z1 = std::min(box.hi.z, z0 + slab - 1);
    // The slab in the file's extent (which need not start at 0); VTK reads the pieces that meet
    // it and fills an image of this extent alone.
    int ext[6] = {whole[0] + box.lo.x, whole[0] + box.hi.x, whole[2] + box.lo.y,
                  whole[2] + box.hi.y, whole[4] + z0,       whole[4] + z1};
    static_cast<vtkAlgorithm*>(r.GetPointer())->UpdateExtent(ext);  // (the reader hides the name)
    vtkImageData* img = r->GetOutput();
    vtkDataArray* a = scalarsOf(img, d.file);
    int got[6];
    img->GetExtent(got);
    for (int k = 0; k < 3; ++k)
      if (got[2 * k] > ext[2 * k] || got[2 * k + 1] < ext[2 * k + 1])
        throw InputError("volume.file " + d.file + ": VTK returned extent [" + std::to_string(got[2 * k]) + ", " +
                         std::to_string(got[2 * k + 1]) + "] on axis " + std::to_string(k) +
                         ", which does not hold the brick's [" + std::to_string(ext[2 * k]) + ", " +
                         std::to_string(ext[2 * k + 1]) + "] (a truncated file?)");
    const long long gx = got[1] - got[0] + 1, gy = got[3] - got[2] + 1;
    if (a->GetNumberOfTuples() != gx * gy * (got[5] - got[4] + 1))
      throw InputError("volume.file " + d.file + ": the scalar array has " + std::to_string(a->GetNumberOfTuples()) +
                       " values for the extent read (a truncated file?)");
    for (int z = ext[4]; z <= ext[5]; ++z)
      for (int y = ext[2]; y <= ext[3]; ++y)
        for (int x = ext[0]; x <= ext[1]; ++x) {
          const double v = a->GetComponent((x - got[0]) + gx * ((y - got[2]) + gy * (long long)(z - got[4])), 0);
          if (!std::isfinite(v))
            throw InputError("volume.file " + d.file + ": NaN or infinite value at voxel [" +
                             std::to_string(x - whole[0]) + ", " + std::to_string(y - whole[2]) + ", " +
                             std::to_string(z - whole[4]) + "]");
          out[o++] = float(v);
        }
  }
  return out;
}

void readVtkGeometry(VolumeDesc& d) {
  auto img = loadImage(d.file, true);
  int dims[3];
  img->GetDimensions(dims);
  double sp[3];
  img->GetSpacing(sp);
  d.grid.dims = {dims[0], dims[1], dims[2]};
  d.grid.spacing = {std::abs(sp[0]), std::abs(sp[1]), std::abs(sp[2])};
}

std::vector<float> readWholeVtk(const VolumeDesc& d) {
  auto img = loadImage(d.file, false);
  vtkDataArray* a = scalarsOf(img, d.file);
  long long n = d.grid.sampleCount();
  if (a->GetNumberOfTuples() != n)
    throw InputError("volume.file " + d.file + ": scalar array has " +
                     std::to_string(a->GetNumberOfTuples()) + " values, dims need " +
                     std::to_string(n));
  std::vector<float> out(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i) {
    double v = a->GetComponent(i, 0);
    if (!std::isfinite(v))
      throw InputError("volume.file " + d.file + ": NaN or infinite value at sample " +
                       std::to_string(i));
    out[size_t(i)] = float(v);
  }
  return out;
}

}  // namespace sortlast
