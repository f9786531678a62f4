#pragma once
// The reference section (reference.*): the CPU reference integrator. Rows: reference.cpp.
#include <utility>

#include "scene/scene_keys.h"

namespace sortlast {

// reference.field: what the reference integrates.
enum class ReferenceField { kOriginal, kAdaptive };
template <>
struct EnumNames<ReferenceField> {
  static constexpr std::pair<const char*, ReferenceField> list[] = {{"original", ReferenceField::kOriginal},
                                                                     {"adaptive", ReferenceField::kAdaptive}};
};

struct ReferenceSection {
  double step = 0.0625;  // in units of the smallest voxel spacing
  ReferenceField field = ReferenceField::kOriginal;
};

}  // namespace sortlast
