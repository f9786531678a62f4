#include "render/glow/glow_gl.h"

#include <cmath>
#include <stdexcept>

namespace sortlast {

unsigned makeFloatTexture(const GlApi& gl, int w, int h, const float* texels) {
  unsigned tex = 0;
  gl.GenTextures(1, &tex);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, tex);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, texels);
  return tex;
}

unsigned makeFramebuffer(const GlApi& gl, unsigned texture) {
  unsigned fbo = 0;
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("OpenGL: float framebuffer is not complete");
  return fbo;
}

std::vector<float> glowEmitterTexels(const std::vector<GlowEmitter>& emitters) {
  std::vector<float> t;
  t.reserve(emitters.size() * 12);
  for (const GlowEmitter& e : emitters)
    for (double v : {e.centre.x, e.centre.y, e.centre.z, e.a, e.direction.x, e.direction.y,
                     e.direction.z, e.b, e.colour.r, e.colour.g, e.colour.b, 0.0})
      t.push_back(float(v));
  return t;
}

void bindGlowEmitters(const GlApi& gl, const GlProgram& program, const GlowPass& pass, int unit) {
  program.set("u_glow_eps", pass.eps);
  program.set("u_glow_count", pass.count);
  program.set("u_glow_emitters", unit);
  gl.ActiveTexture(GL_TEXTURE0 + unsigned(unit));
  gl.BindTexture(GL_TEXTURE_2D, pass.emitters);
}

void setPixelRayUniforms(const GlProgram& program, const Camera& cam) {
  const glm::dvec2 s = cam.screenScale();  // tan(fov / 2) (x aspect), or parallel_scale (x aspect)
  program.set("u_eye", glm::vec3(cam.position));
  program.set("u_forward", glm::vec3(cam.forward()));
  program.set("u_right", glm::vec3(cam.right() * s.x));
  program.set("u_up", glm::vec3(cam.trueUp() * s.y));
  program.set("u_orthographic", cam.orthographic() ? 1 : 0);  // programs without it ignore it
  program.set("u_pixel_scale", glm::vec2(float(2.0 / cam.width), float(2.0 / cam.height)));
}

}  // namespace sortlast
