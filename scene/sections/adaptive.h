#pragma once
// The adaptive section (adaptive.*): the paper's adaptive sampling. Rows: adaptive.cpp.
#include <utility>

#include "scene/scene_keys.h"

namespace sortlast {

// adaptive.steps: how a block's samples are taken along the rays.
enum class AdaptiveSteps { kOwn, kFine };
template <>
struct EnumNames<AdaptiveSteps> {
  static constexpr std::pair<const char*, AdaptiveSteps> list[] = {{"own", AdaptiveSteps::kOwn},
                                                                    {"fine", AdaptiveSteps::kFine}};
};

struct AdaptiveSection {
  double tolerance = 0.0;  // relative L2 error per block, a fraction (the key is in percent); 0: off
  int blocks = 8;          // b, blocks per axis of the whole volume
  AdaptiveSteps steps = AdaptiveSteps::kOwn;

  bool enabled() const { return tolerance > 0.0; }
};

}  // namespace sortlast
