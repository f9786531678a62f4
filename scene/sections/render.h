#pragma once
// The render section (render.*): how each rank draws its bricks. Its rows are in render.cpp.
#include <utility>

#include "scene/scene_keys.h"
#include "transfer/shading.h"

namespace sortlast {

// render.method: the volume renderer.
enum class RenderMethod { kSlicing, kRaycast };
template <>
struct EnumNames<RenderMethod> {
  static constexpr std::pair<const char*, RenderMethod> list[] = {{"slicing", RenderMethod::kSlicing},
                                                                   {"raycast", RenderMethod::kRaycast}};
};

// render.backend: where the GL context comes from.
enum class GlBackend { kOsmesa, kEgl };
template <>
struct EnumNames<GlBackend> {
  static constexpr std::pair<const char*, GlBackend> list[] = {{"osmesa", GlBackend::kOsmesa},
                                                                {"egl", GlBackend::kEgl}};
};

struct RenderSection {
  GlBackend backend = GlBackend::kOsmesa;
  int device = -1;              // a hardware EGL device index; -1: auto
  double sample_spacing = 0.5;  // in units of the smallest voxel spacing
  // render.sample_spacing: auto: the session picks the step per view and transfer function
  // (session/auto_spacing.h); sample_spacing then holds 0.5 until it does.
  bool sample_spacing_auto = true;
  int block_cells = 64;     // empty-space skipping granularity (slicing)
  int ray_block_cells = 8;  // the ray caster's skipping and step blocks
  RenderMethod method = RenderMethod::kRaycast;
  double ert_threshold = 0.99;            // ray casting: early ray termination opacity
  Shading shading;                        // gradient shading of the volume (render.shading*)
  bool adaptive_step = false;             // ray casting: a block takes every m-th lattice sample
  double adaptive_step_tolerance = 0.02;  // the step rule's bound (render/volume/step_rule.h)

  bool raycast() const { return method == RenderMethod::kRaycast; }
};

}  // namespace sortlast
