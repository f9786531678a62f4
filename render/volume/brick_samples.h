#pragma once
// Where a brick's stored samples come from when it is uploaded: a float array read from a file
// (the batch and service paths), or the simulation's own arrays plus the ghost samples fetched
// from its neighbours (in situ, which must not copy the step). The upload needs two things of
// them: the range of any box of samples (for empty-space skipping) and the samples themselves,
// written into the brick's 3D texture.
#include <utility>
#include <vector>

#include "common/box.h"
#include "render/gl/gl_api.h"

namespace sortlast {

class BrickSamples {
 public:
  virtual ~BrickSamples() = default;
  // Smallest and largest sample in `box` (global sample indices, inside the stored box).
  virtual std::pair<float, float> range(const IndexBox& box) const = 0;
  // Writes every sample of `stored` into the bound GL_TEXTURE_3D (already allocated as R32F of
  // stored.size()), e.g. with TexSubImage3D; texel (0, 0, 0) is sample stored.lo.
  virtual void upload(const GlApi& gl, const IndexBox& stored) const = 0;
};

// A dense float array of the stored box, x fastest.
class FloatBrickSamples : public BrickSamples {
 public:
  FloatBrickSamples(const std::vector<float>& samples, const IndexBox& stored)
      : samples_(samples), stored_(stored) {}
  std::pair<float, float> range(const IndexBox& box) const override;
  void upload(const GlApi& gl, const IndexBox& stored) const override;

 private:
  const std::vector<float>& samples_;
  IndexBox stored_;
};

}  // namespace sortlast
