#pragma once
// What every GL user of the glow emitters shares (the brick pass, the ray caster's GLOW variant,
// tests/unit/glow_glsl_test.cpp, bench/bench_glow.cpp): float data textures, the emitters'
// texel layout and binding, the GLSL that sums every emitter's exact segment integral along a ray
// (after worker/glow/glow_glsl.h's glowSegment()), and the fullscreen pass's triangle and pixel rays.
#include <stdexcept>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/glow_field.h"
#include "worker/gl/brick_output.h"
#include "worker/gl/gl_api.h"
#include "worker/glow/glow_glsl.h"

namespace sortlast {

// A w x h RGBA32F texture with nearest filtering, bound to GL_TEXTURE_2D of texture unit 0;
// `texels` (4 floats each, row 0 first) may be null.
unsigned makeFloatTexture(const GlApi& gl, int w, int h, const float* texels);
// A framebuffer drawing into `texture`; throws std::runtime_error if it is not complete.
unsigned makeFramebuffer(const GlApi& gl, unsigned texture);

// Row i of a 3-texel-wide texture is emitter i: (centre, a), (direction, b), (colour, 0).
std::vector<float> glowEmitterTexels(const std::vector<GlowEmitter>& emitters);

// The uniforms of kGlowEmitters for `program` (in use): the emitters' texture on texture unit
// `unit`, their count and core radius. Every program that includes kGlowEmitters binds them here.
void bindGlowEmitters(const GlApi& gl, unsigned program, const GlowPass& pass, int unit);

// The pixel-ray uniforms (u_eye, u_forward, u_right, u_up, u_pixel_scale) for `program` (in use),
// shared by kGlowPixelRay and the ray caster's main(): the image plane at distance 1, pixel
// centre (x, y) at forward + sx right + sy up, as in Camera::rayDirection.
void setPixelRayUniforms(const GlApi& gl, unsigned program, const Camera& cam);

namespace shaders {
// The vertex shader of a fullscreen pass: one triangle (gl_VertexID 0..2, no attributes) covering
// the viewport; the scissor picks the pixels.
inline constexpr const char* kGlowFullscreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// glowPixelRay(): the unit direction of this fragment's ray from u_eye, as the ray caster makes it
// (raycast_shaders.h), so t along it is the surface layer's t. Row y of the target is image row y
// from the top: s.y = 1 - 2 (y + 0.5) / height.
inline constexpr const char* kGlowPixelRay = R"(
uniform vec3 u_eye, u_forward, u_right, u_up;
uniform vec2 u_pixel_scale;
vec3 glowPixelRay() {
  vec2 s = vec2(gl_FragCoord.x * u_pixel_scale.x - 1.0, 1.0 - gl_FragCoord.y * u_pixel_scale.y);
  return normalize(u_forward + s.x * u_right + s.y * u_up);
}
)";

// The emitters' uniforms (the texture above: u_glow_emitters, u_glow_count rows; core radius
// u_glow_eps) and glowSpan(), which every glow program needs (the brick pass and the ray caster's
// GLOW variant).
inline constexpr const char* kGlowEmitters = R"(
uniform sampler2D u_glow_emitters;
uniform int u_glow_count;
uniform float u_glow_eps;

// The ray's span inside [lo, hi], t >= 0; false: it misses. An axis the ray does not move along
// is tested by position (no 0 * inf): a ray lying in a face plane between two bricks belongs to
// the brick above it only (hi_open 1 on that axis: [lo, hi)), so it is neither lost nor counted
// twice; the glow box's own upper faces are closed, as the reference's box is. Straight-line
// (selects, no loop with early returns): llvmpipe runs a per-pixel loop's control flow masked.
bool glowSpan(vec3 o, vec3 u, vec3 lo, vec3 hi, vec3 hi_open, out float t0, out float t1) {
  bvec3 still = equal(u, vec3(0.0));
  vec3 a = (lo - o) / u, b = (hi - o) / u;  // not used on a still axis (inf or NaN there)
  vec3 near = mix(min(a, b), vec3(0.0), still), far = mix(max(a, b), vec3(3.0e38), still);
  t0 = max(max(0.0, near.x), max(near.y, near.z));
  t1 = min(min(3.0e38, far.x), min(far.y, far.z));
  bvec3 outside = bvec3(lessThan(o, lo).x || greaterThan(o, hi).x || (hi_open.x > 0.5 && o.x == hi.x),
                        lessThan(o, lo).y || greaterThan(o, hi).y || (hi_open.y > 0.5 && o.y == hi.y),
                        lessThan(o, lo).z || greaterThan(o, hi).z || (hi_open.z > 0.5 && o.z == hi.z));
  return !any(bvec3(still.x && outside.x, still.y && outside.y, still.z && outside.z)) && t1 > t0;
}
)";

// glowAlong(o, u, s0, s1): the colour-weighted sum of every emitter's integral over [s0, s1] of
// the ray o + s u (unit u). Include after kGlowSegment and kGlowEmitters. (The ray caster sums
// glowSegment itself, with the field's slope: glowFlushDue.)
inline constexpr const char* kGlowAlong = R"(
vec3 glowAlong(vec3 o, vec3 u, float s0, float s1) {
  vec3 sum = vec3(0.0);
  if (!(s1 > s0)) return sum;
  for (int i = 0; i < u_glow_count; ++i) {
    vec4 e0 = texelFetch(u_glow_emitters, ivec2(0, i), 0), e1 = texelFetch(u_glow_emitters, ivec2(1, i), 0);
    vec3 colour = texelFetch(u_glow_emitters, ivec2(2, i), 0).rgb;
    sum += colour * glowSegment(e0.xyz, e1.xyz, e0.w, e1.w, u_glow_eps, o, u, s0, s1);
  }
  return sum;
}
)";

// A fragment shader `src` (starting with its #version line) with GLOW defined and glowSegment(),
// the emitters' uniforms and glowSpan() put before its own text (the ray caster's GLOW variant).
inline std::string withGlow(const std::string& src) {
  const std::string version = "#version 450 core\n";
  if (src.rfind(version, 0) != 0) throw std::logic_error("glow shader: no #version line");
  return version + "#define GLOW 1\n" + kGlowSegment + kGlowEmitters + src.substr(version.size());
}
}  // namespace shaders

}  // namespace sortlast
