#include "render/volume/bounded_pixels.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "compositing/projection_pixels.h"

namespace sortlast {

void toBoundedPixels(VolumeBlend blend, std::vector<float>& px, const std::vector<float>* layer) {
  if (layer && layer->size() != px.size())
    throw std::logic_error("bounded pixels: the layer is not the image's size");
  for (size_t i = 0; i < px.size(); i += 4) {
    float* p = &px[i];
    uint32_t rgb = 0;
    const bool hit = layer && (*layer)[i + 3] > 0.5f;
    if (hit)  // the ray caster's rounding of the layer's colour to 8 bits (projectionPixel)
      for (int c = 0; c < 3; ++c) {
        const float x = std::fmin(std::fmax((*layer)[i + size_t(c)], 0.0f), 1.0f);
        rgb |= uint32_t(x * 255.0f + 0.5f) << (8 * c);
      }
    const float layer_flag = hit ? kBoundedLayer : 0.0f;
    switch (blend) {
      case VolumeBlend::kMip:
      case VolumeBlend::kMinip:  // (v, rgb, 0, flags)
        p[1] = float(rgb), p[2] = 0.0f, p[3] = (p[3] > 0.0f ? kBoundedValue : 0.0f) + layer_flag;
        if (!(p[3] > 0.0f)) p[0] = 0.0f;
        break;
      case VolumeBlend::kAverage: {  // (sum, rgb, count, flags)
        const float count = p[3];
        p[2] = count > 0.0f ? count : 0.0f;
        if (!(count > 0.0f)) p[0] = 0.0f;
        p[1] = float(rgb), p[3] = (count > 0.0f ? kBoundedValue : 0.0f) + layer_flag;
        break;
      }
      case VolumeBlend::kAdditive: {  // the packed halves
        const float sum[4] = {p[0], p[1], p[2], p[3]};
        const bool value = sum[0] > 0.0f || sum[1] > 0.0f || sum[2] > 0.0f || sum[3] > 0.0f;
        const float zero[4] = {0, 0, 0, 0};
        packAdditiveBounded(value ? sum : zero, rgb, (value ? 1 : 0) | (hit ? 2 : 0), p);
        break;
      }
      default: throw std::logic_error("bounded pixels: not a projection");
    }
  }
}

}  // namespace sortlast
