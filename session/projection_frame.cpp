#include "session/projection_frame.h"

#include <stdexcept>

#include "common/pixel_threads.h"
#include "transfer/projection_colour.h"

namespace sortlast {

WireFormat projectionFormat(VolumeBlend blend) {
  switch (blend) {
    case VolumeBlend::kMip: return WireFormat::ValueMax;
    case VolumeBlend::kMinip: return WireFormat::ValueMin;
    case VolumeBlend::kAverage: return WireFormat::ValueSum;
    case VolumeBlend::kAdditive: return WireFormat::Additive;
    default: return WireFormat::RGBA8;
  }
}

std::function<void(float*, size_t)> projectionColouring(VolumeBlend blend,
                                                        std::shared_ptr<const TransferFunction> tf) {
  if (projectionFormat(blend) == WireFormat::RGBA8)
    throw std::logic_error("projectionColouring: not a projection");
  return [blend, tf](float* px, size_t n) {
    parallelFor(n, size_t(1) << 14, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        float* p = px + 4 * i;
        if (blend == VolumeBlend::kAdditive) {
          clampAdditive(p);
          continue;
        }
        if (!(p[3] > 0.0f)) {  // no sample reached it: transparent
          p[0] = p[1] = p[2] = p[3] = 0.0f;
          continue;
        }
        const double v = blend == VolumeBlend::kAverage ? double(p[0]) / double(p[3]) : double(p[0]);
        const auto c = projectedColour(*tf, v);
        for (int k = 0; k < 4; ++k) p[k] = float(c[k]);
      }
    });
  };
}

}  // namespace sortlast
