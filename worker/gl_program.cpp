#include "worker/gl_program.h"

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

}  // namespace

unsigned linkProgram(const GlApi& gl, const char* vs, const char* fs) {
  unsigned p = gl.CreateProgram();
  unsigned v = compile(gl, GL_VERTEX_SHADER, vs), f = compile(gl, GL_FRAGMENT_SHADER, fs);
  gl.AttachShader(p, v);
  gl.AttachShader(p, f);
  gl.LinkProgram(p);
  gl.DeleteShader(v);
  gl.DeleteShader(f);
  int ok = 0;
  gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("GLSL link error: ") + log);
  }
  return p;
}

}  // namespace sortlast
