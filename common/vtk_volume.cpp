// Reading .vti (XML) and legacy .vtk image files with VTK. Kept in its own file so only this one
// translation unit sees VTK's headers.
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
#include "common/volume_source.h"

namespace sortlast {

namespace {

vtkSmartPointer<vtkImageData> loadImage(const std::string& file, bool metadata_only) {
  bool xml = file.size() > 4 && file.substr(file.size() - 4) == ".vti";
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

}  // namespace

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
  vtkDataArray* a = img->GetPointData() ? img->GetPointData()->GetScalars() : nullptr;
  if (!a && img->GetPointData() && img->GetPointData()->GetNumberOfArrays() > 0)
    a = img->GetPointData()->GetArray(0);
  if (!a) throw InputError("volume.file " + d.file + ": no point scalars in the image");
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
