#include "common/missing_feature.h"

namespace sortlast {

namespace {

struct FeatureNames {
  const char* name;    // what the user wanted, as they know it
  const char* option;  // the CMake cache variable (cmake/features.cmake)
};

FeatureNames namesOf(Feature f) {
  switch (f) {
    case Feature::kVtk: return {"VTK", "SORTLAST_WITH_VTK"};
    case Feature::kHdf5: return {"HDF5", "SORTLAST_WITH_HDF5"};
    case Feature::kNetcdf: return {"NetCDF", "SORTLAST_WITH_NETCDF"};
    case Feature::kExr: return {"OpenEXR", "SORTLAST_WITH_EXR"};
    case Feature::kService: return {"service (Boost.Beast)", "SORTLAST_WITH_SERVICE"};
    case Feature::kOsmesa: return {"OSMesa backend", "SORTLAST_WITH_OSMESA"};
    case Feature::kEgl: return {"EGL backend", "SORTLAST_WITH_EGL"};
  }
  return {"?", "?"};
}

}  // namespace

std::string missingFeatureMessage(Feature feature, const std::string& what) {
  const FeatureNames n = namesOf(feature);
  return what + ": this build has no " + n.name + " (configure with -D" + n.option + "=ON)";
}

void refuseMissingFeature(Feature feature, const std::string& what) {
  throw InputError(missingFeatureMessage(feature, what));
}

}  // namespace sortlast
