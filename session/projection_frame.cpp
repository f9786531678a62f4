#include "session/projection_frame.h"

#include <array>
#include <cstdint>
#include <stdexcept>

#include "common/pixel_threads.h"
#include "compositing/projection_pixels.h"
#include "transfer/projection_colour.h"

namespace sortlast {

WireFormat projectionFormat(VolumeBlend blend, bool bounded) {
  if (bounded) {
    if (blend == VolumeBlend::kMip) return WireFormat::ValueMaxBounded;
    if (blend == VolumeBlend::kMinip) return WireFormat::ValueMinBounded;
    if (blend == VolumeBlend::kAverage) return WireFormat::ValueSumBounded;
    if (blend == VolumeBlend::kAdditive) return WireFormat::AdditiveBounded;
    throw std::logic_error("projectionFormat: not a projection");
  }
  switch (blend) {
    case VolumeBlend::kMip: return WireFormat::ValueMax;
    case VolumeBlend::kMinip: return WireFormat::ValueMin;
    case VolumeBlend::kAverage: return WireFormat::ValueSum;
    case VolumeBlend::kAdditive: return WireFormat::Additive;
    default: return WireFormat::RGBA8;
  }
}

std::function<void(float*, size_t)> projectionColouring(VolumeBlend blend,
                                                        std::shared_ptr<const TransferFunction> tf,
                                                        bool bounded) {
  const WireFormat f = projectionFormat(blend, bounded);
  if (f == WireFormat::RGBA8) throw std::logic_error("projectionColouring: not a projection");
  return [blend, tf, bounded, f](float* px, size_t n) {
    parallelFor(n, size_t(1) << 14, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        float* p = px + 4 * i;
        if (bounded) {  // the value's colour over the layer's: compositing/projection_pixels.h
          std::array<double, 4> c{0.0, 0.0, 0.0, 0.0};
          if (boundedHasValue(f, p)) {
            if (f == WireFormat::AdditiveBounded) {
              float sum[4];
              additiveBoundedSums(p, sum);
              clampAdditive(sum);
              for (int k = 0; k < 4; ++k) c[size_t(k)] = double(sum[k]);
            } else {
              const double v = f == WireFormat::ValueSumBounded ? double(p[0]) / double(p[2]) : double(p[0]);
              c = projectedColour(*tf, v);
            }
          }
          if (boundedHasLayer(f, p)) {
            const uint32_t s = boundedLayer(f, p);
            c = overOpaque(c, {(s & 0xff) / 255.0, ((s >> 8) & 0xff) / 255.0, (s >> 16) / 255.0});
          }
          for (int k = 0; k < 4; ++k) p[k] = float(c[size_t(k)]);
          continue;
        }
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
