#pragma once
// The reference: a CPU integrator in double precision of the same emission-absorption model the
// GL renderer approximates (same trilinear field, same transfer function, same opacity
// correction), in the continuous limit of the sample spacing: each ray is cut into steps of
// `step` world units (default 1/16 voxel) and each step is composited exactly with its midpoint
// value, T *= exp(-tau h). This is what accuracy is measured against.
#include <vector>

#include "common/camera.h"
#include "common/grid.h"
#include "common/image.h"
#include "common/transfer_function.h"

namespace sortlast {

struct WholeVolume {
  GridGeometry grid;
  std::vector<float> samples;  // x fastest
  double at(const glm::dvec3& index) const;  // trilinear, index clamped to the grid
};

ImageF renderReference(const WholeVolume& vol, const TransferFunction& tf, const Camera& cam,
                       double step, int threads);

}  // namespace sortlast
