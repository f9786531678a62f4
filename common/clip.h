#pragma once
// The clip region (scene keys clip.planes and clip.box): the part of space a volume is shown in.
// A plane {normal n, offset w} keeps the side n . x <= w; the box keeps [lo, hi]; the region is the
// intersection of all of them (no plane and no box: everything). Volumes only: particles, surfaces
// and glow are not clipped (as ParaView's volume cropping; docs/volumes.md).
//
// Every renderer clips a ray o + t d (t >= 0) to one span [t0, t1] with spanOf()'s arithmetic
// (the box as its six planes), the reference in double, the ray caster in float
// (render/volume/volume_clip.glsl): the same float formula in every brick, so a sample is taken iff
// its t lies in the clipped span whichever brick owns it, and no seam appears at brick faces.
#include <vector>

#include <glm/glm.hpp>

#include "common/box.h"

namespace sortlast {

struct ClipPlane {
  glm::dvec3 normal{0.0, 0.0, 1.0};  // need not be unit; never zero (the scene refuses it)
  double offset = 0.0;
};

struct ClipRegion {
  std::vector<ClipPlane> planes;
  bool has_box = false;
  Box3 box;

  bool active() const { return !planes.empty() || has_box; }
  // Every half-space: the planes, then the box's six faces (-x <= -lo.x, x <= hi.x, ...).
  std::vector<ClipPlane> halfSpaces() const;
  // Whether no point of `b` is kept (b wholly outside one half-space, or outside the box).
  bool culls(const Box3& b) const;
  // The box around what of `b` may be kept: b cut by the clip box (the planes do not shrink it).
  Box3 bound(const Box3& b) const;
};

// The most half-spaces a GL renderer takes (the shaders' uniform array): the box's six included.
inline constexpr int kMaxClipHalfSpaces = 32;

// Cuts [t0, t1] of the ray o + t d to the region: for each half-space with n . d > 0,
// t1 = min(t1, (w - n . o) / (n . d)); with n . d < 0, t0 = max(t0, the same); with n . d = 0 the
// whole ray is kept (n . o <= w) or nothing (t1 = t0). Empty: t0 >= t1.
void clipSpan(const ClipRegion& clip, const glm::dvec3& o, const glm::dvec3& d, double& t0, double& t1);

}  // namespace sortlast
