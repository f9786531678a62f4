// Reading particle centres from VTK files: the points of a legacy .vtk polydata or unstructured
// grid (ASCII or binary; VTK handles big-endian binary) or of an XML .vtp / .vtu file. Only the
// points matter; cells and point data (ids, velocities) are ignored. Kept in its own file so only
// this translation unit sees VTK's headers.
#include <fstream>
#include <string>

#include <vtkDataObject.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtkXMLReader.h>

#include "common/error.h"
#include "io/particles.h"

namespace sortlast {

namespace {

// VTK's readers do not fail: a legacy file cut short gives the declared number of points, the
// missing ones uninitialised, and the only sign is a warning on VTK's output window ("Error
// reading ascii data", "Error reading binary data!"). So while a file is read, VTK's output window
// is replaced by one that keeps the first error (or warning about an error) for an InputError.
// The output window is global: files are read one at a time.
class CapturingWindow : public vtkOutputWindow {
 public:
  static CapturingWindow* New();
  vtkTypeMacro(CapturingWindow, vtkOutputWindow);

  std::string first_error;

  void DisplayText(const char* text) override {
    MessageTypes type = GetCurrentMessageType();
    std::string m = text ? text : "";
    bool is_error = type == MESSAGE_TYPE_ERROR ||
                    ((type == MESSAGE_TYPE_WARNING || type == MESSAGE_TYPE_GENERIC_WARNING) &&
                     m.find("rror") != std::string::npos);
    if (is_error && first_error.empty()) first_error = gist(m);
  }

 private:
  // VTK's messages read "ERROR: In FILE, line N\nvtkClass (0x...): what went wrong\n\n" or
  // "Generic Warning: In FILE, line N\nwhat went wrong\n\n": keep what went wrong.
  static std::string gist(std::string m) {
    while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
    m = m.substr(m.rfind('\n') + 1);  // npos + 1 == 0: a one-line message stays whole
    size_t at = m.find("): ");
    if (at != std::string::npos) m = m.substr(at + 3);
    return m.empty() ? "unknown error" : m;
  }
};
vtkStandardNewMacro(CapturingWindow);

class CaptureVtkErrors {
 public:
  explicit CaptureVtkErrors(std::string file) : file_(std::move(file)) {
    previous_ = vtkOutputWindow::GetInstance();
    vtkOutputWindow::SetInstance(window_);
  }
  ~CaptureVtkErrors() { vtkOutputWindow::SetInstance(previous_); }
  CaptureVtkErrors(const CaptureVtkErrors&) = delete;
  CaptureVtkErrors& operator=(const CaptureVtkErrors&) = delete;

  void throwIfAny() const {
    if (!window_->first_error.empty())
      throw InputError("particles.file " + file_ +
                       ": VTK could not read it: " + window_->first_error);
  }

 private:
  std::string file_;
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkNew<CapturingWindow> window_;
};

bool isLegacy(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(14, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  return in && head == "# vtk DataFile";
}

std::vector<glm::vec3> pointsOf(vtkDataObject* data, const std::string& file) {
  auto* set = vtkPointSet::SafeDownCast(data);
  if (!set)
    throw InputError("particles.file " + file + ": not a VTK point set (polydata or unstructured " +
                     "grid); got " + (data ? data->GetClassName() : std::string("nothing")));
  vtkPoints* pts = set->GetPoints();
  std::vector<glm::vec3> out(pts ? size_t(pts->GetNumberOfPoints()) : 0);
  for (size_t i = 0; i < out.size(); ++i) {
    double p[3];
    pts->GetPoint(vtkIdType(i), p);
    out[i] = glm::vec3(float(p[0]), float(p[1]), float(p[2]));
  }
  return out;
}

template <class Reader>
std::vector<glm::vec3> readLegacy(const std::string& file) {
  CaptureVtkErrors errors(file);
  vtkNew<Reader> r;
  r->SetFileName(file.c_str());
  r->Update();
  errors.throwIfAny();
  return pointsOf(r->GetOutput(), file);
}

}  // namespace

std::vector<glm::vec3> readVtkParticles(const std::string& file) {
  if (isLegacy(file)) {
    vtkNew<vtkPolyDataReader> probe;
    probe->SetFileName(file.c_str());
    if (probe->IsFilePolyData()) return readLegacy<vtkPolyDataReader>(file);
    if (probe->IsFileUnstructuredGrid()) return readLegacy<vtkUnstructuredGridReader>(file);
    throw InputError("particles.file " + file +
                     ": legacy VTK file is not POLYDATA or UNSTRUCTURED_GRID (only those hold "
                     "particles)");
  }
  CaptureVtkErrors errors(file);
  // An XML file names its own data type; pick the reader for it.
  vtkNew<vtkXMLGenericDataObjectReader> probe;
  bool parallel = false;
  int type = probe->ReadOutputType(file.c_str(), parallel);
  vtkSmartPointer<vtkXMLReader> r;
  if (type == VTK_POLY_DATA || type == VTK_UNSTRUCTURED_GRID)
    r = vtkXMLGenericDataObjectReader::CreateReader(type, parallel);
  if (!r)
    throw InputError("particles.file " + file +
                     ": neither a legacy VTK file nor a VTK XML polydata (.vtp) or unstructured "
                     "grid (.vtu) file");
  r->SetFileName(file.c_str());
  r->Update();
  errors.throwIfAny();
  return pointsOf(r->GetOutputDataObject(0), file);
}

}  // namespace sortlast
