#include "worker/gl/gl_program.h"

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace sortlast {

namespace {

unsigned compile(const GlApi& gl, GLenum type, const char* src) {
  unsigned s = gl.CreateShader(type);
  gl.ShaderSource(s, 1, &src, nullptr);
  gl.CompileShader(s);
  int ok = 0;
  gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
    gl.DeleteShader(s);
    throw std::runtime_error(std::string("GLSL compile error: ") + log);
  }
  return s;
}

// Links p (its shaders attached), deletes the shaders; throws with the log on failure.
unsigned link(const GlApi& gl, unsigned p, std::initializer_list<unsigned> shaders) {
  gl.LinkProgram(p);
  for (unsigned s : shaders) gl.DeleteShader(s);
  int ok = 0;
  gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("GLSL link error: ") + log);
  }
  return p;
}

}  // namespace

unsigned linkProgram(const GlApi& gl, const char* vs, const char* fs) {
  unsigned p = gl.CreateProgram();
  unsigned v = compile(gl, GL_VERTEX_SHADER, vs), f = compile(gl, GL_FRAGMENT_SHADER, fs);
  gl.AttachShader(p, v);
  gl.AttachShader(p, f);
  return link(gl, p, {v, f});
}

unsigned linkComputeProgram(const GlApi& gl, const char* cs) {
  unsigned p = gl.CreateProgram();
  unsigned c = compile(gl, GL_COMPUTE_SHADER, cs);
  gl.AttachShader(p, c);
  return link(gl, p, {c});
}

}  // namespace sortlast
