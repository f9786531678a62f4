#pragma once
// What every GL user of the glow emitters shares (the brick pass, the ray caster's GLOW variant,
// tests/unit/glow_glsl_test.cpp, bench/glow/main.cpp): float data textures, the emitters'
// texel layout and binding, and the pixel rays' uniforms. Their GLSL is in render/glow/*.glsl:
// glow_segment (one emitter's exact segment integral), glow_emitters (the emitters' uniforms and
// glowSpan), glow_along (every emitter's integral along a ray), glow_pixel_ray, and the pass itself
// (glow_pass.frag).
#include <vector>

#include "common/camera.h"
#include "glow/glow_field.h"
#include "render/gl/brick_output.h"
#include "render/gl/gl_api.h"
#include "render/gl/gl_program.h"

namespace sortlast {

// A w x h RGBA32F texture with nearest filtering, bound to GL_TEXTURE_2D of texture unit 0;
// `texels` (4 floats each, row 0 first) may be null.
unsigned makeFloatTexture(const GlApi& gl, int w, int h, const float* texels);
// A framebuffer drawing into `texture`; throws std::runtime_error if it is not complete.
unsigned makeFramebuffer(const GlApi& gl, unsigned texture);

// Row i of a 3-texel-wide texture is emitter i: (centre, a), (direction, b), (colour, 0).
std::vector<float> glowEmitterTexels(const std::vector<GlowEmitter>& emitters);

// The uniforms of glow_emitters.glsl for `program` (in use): the emitters' texture on texture
// unit `unit`, their count and core radius. Every program that includes it binds them here.
void bindGlowEmitters(const GlApi& gl, const GlProgram& program, const GlowPass& pass, int unit);

// The pixel-ray uniforms (u_eye, u_forward, u_right, u_up, u_orthographic, u_pixel_scale) for
// `program` (in use), shared by glow_pixel_ray.glsl and the ray caster's main(): Camera::pixelRay,
// pixel centre (x, y) at forward + sx right + sy up (perspective: the image plane at distance 1)
// or, orthographic, the ray along forward from eye + sx right + sy up.
void setPixelRayUniforms(const GlProgram& program, const Camera& cam);

}  // namespace sortlast
