#pragma once
// The refusal of something this build was configured without: one wording everywhere, naming the
// CMake option that builds it, e.g.
//   volume.file x.h5: this build has no HDF5 (configure with -DSORTLAST_WITH_HDF5=ON)
// Whether a feature is built is common/build_features.h (generated at configure).
#include <string>

#include "common/error.h"

namespace sortlast {

enum class Feature { kVtk, kHdf5, kNetcdf, kExr, kService, kOsmesa, kEgl };

// "WHAT: this build has no NAME (configure with -DSORTLAST_WITH_X=ON)".
std::string missingFeatureMessage(Feature feature, const std::string& what);

// An InputError with that message: main() prints it and every rank exits non-zero (the callers
// refuse while parsing or inside `collectively`, before any rank waits on another).
[[noreturn]] void refuseMissingFeature(Feature feature, const std::string& what);

}  // namespace sortlast
