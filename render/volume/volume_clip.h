#pragma once
// The clip region (common/clip.h) in the GL volume renderers: the uniforms of
// render/volume/volume_clip.glsl (clipRay for the ray caster, clipKeeps for slicing) and the brick
// culling both share.
#include "common/camera.h"
#include "common/clip.h"
#include "render/gl/gl_program.h"

namespace sortlast {

// u_clip[i] = (n, w) of every half-space, u_clip_count; the program in use. Throws
// std::logic_error beyond kMaxClipHalfSpaces (the scene refuses that many).
void setClipUniforms(const GlProgram& program, const ClipRegion& clip);

// The screen rectangle of the part of `bound` (a brick's non-empty blocks) the clip region can
// keep: empty where it keeps none of it (the brick is not drawn: no draw, no read-back, no pixels
// to composite), else the rectangle of `bound` cut by the clip box.
Rect clippedRectOf(const Camera& cam, const Box3& bound, const ClipRegion& clip);

}  // namespace sortlast
