#include "render/gl/gl_program.h"

#include <algorithm>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace sortlast {

namespace {

// The whole info log of shader or program `object`: get_iv is GetShaderiv or GetProgramiv,
// get_log GetShaderInfoLog or GetProgramInfoLog.
template <class GetIv, class GetLog>
std::string infoLog(unsigned object, GetIv get_iv, GetLog get_log) {
  int length = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  get_log(object, GLsizei(log.size()), nullptr, log.data());
  return log.substr(0, log.find('\0'));
}

unsigned compile(const GlApi& gl, GLenum type, const ShaderSource& source) {
  const std::string text = source.text();
  const char* src = text.c_str();
  unsigned s = gl.CreateShader(type);
  gl.ShaderSource(s, 1, &src, nullptr);
  gl.CompileShader(s);
  int ok = 0;
  gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(s, gl.GetShaderiv, gl.GetShaderInfoLog);
    gl.DeleteShader(s);
    throw std::runtime_error("GLSL compile error: " + source.locate(log));
  }
  return s;
}

// Links p (its shaders attached), deletes the shaders; throws with the log on failure.
unsigned link(const GlApi& gl, unsigned p, std::initializer_list<unsigned> shaders,
              const std::string& files) {
  gl.LinkProgram(p);
  for (unsigned s : shaders) gl.DeleteShader(s);
  int ok = 0;
  gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(p, gl.GetProgramiv, gl.GetProgramInfoLog);
    gl.DeleteProgram(p);
    throw std::runtime_error("GLSL link error (" + files + "): " + log);
  }
  return p;
}

}  // namespace

unsigned linkProgram(const GlApi& gl, const ShaderSource& vs, const ShaderSource& fs) {
  const unsigned v = compile(gl, GL_VERTEX_SHADER, vs);
  unsigned f = 0;
  try {
    f = compile(gl, GL_FRAGMENT_SHADER, fs);
  } catch (...) {
    gl.DeleteShader(v);
    throw;
  }
  const unsigned p = gl.CreateProgram();
  gl.AttachShader(p, v);
  gl.AttachShader(p, f);
  return link(gl, p, {v, f}, vs.paths() + "; " + fs.paths());
}

unsigned linkComputeProgram(const GlApi& gl, const ShaderSource& cs) {
  const unsigned c = compile(gl, GL_COMPUTE_SHADER, cs);
  const unsigned p = gl.CreateProgram();
  gl.AttachShader(p, c);
  return link(gl, p, {c}, cs.paths());
}

GlProgram::GlProgram(GlProgram&& o) noexcept
    : gl_(o.gl_), id_(std::exchange(o.id_, 0)), locations_(std::move(o.locations_)) {
  o.locations_.clear();
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  if (this != &o) {
    if (id_) gl_->DeleteProgram(id_);
    gl_ = o.gl_;
    id_ = std::exchange(o.id_, 0);
    locations_ = std::move(o.locations_);
    o.locations_.clear();
  }
  return *this;
}

GlProgram::~GlProgram() {
  if (id_) gl_->DeleteProgram(id_);
}

int GlProgram::uniformLocation(std::string_view name) const {
  auto at = locations_.find(name);
  if (at == locations_.end()) {
    std::string key(name);  // GetUniformLocation takes a null-terminated name
    const int loc = gl_->GetUniformLocation(id_, key.c_str());
    at = locations_.emplace(std::move(key), loc).first;
  }
  return at->second;
}

// A location of -1 is passed on: glUniform* ignores it without an error (GL 4.5 core, 7.6.1).
void GlProgram::set(std::string_view name, int v) const { gl_->Uniform1i(uniformLocation(name), v); }

void GlProgram::set(std::string_view name, unsigned v) const {
  gl_->Uniform1ui(uniformLocation(name), v);
}

void GlProgram::set(std::string_view name, float v) const { gl_->Uniform1f(uniformLocation(name), v); }

void GlProgram::set(std::string_view name, const glm::vec2& v) const {
  gl_->Uniform2f(uniformLocation(name), v.x, v.y);
}

void GlProgram::set(std::string_view name, const glm::vec3& v) const {
  gl_->Uniform3f(uniformLocation(name), v.x, v.y, v.z);
}

void GlProgram::set(std::string_view name, const glm::dvec2& v) const {
  gl_->Uniform2d(uniformLocation(name), v.x, v.y);
}

void GlProgram::set(std::string_view name, const glm::dvec3& v) const {
  gl_->Uniform3d(uniformLocation(name), v.x, v.y, v.z);
}

void GlProgram::set(std::string_view name, const glm::vec4& v) const {
  gl_->Uniform4f(uniformLocation(name), v.x, v.y, v.z, v.w);
}

void GlProgram::set(std::string_view name, const glm::ivec4& v) const {
  gl_->Uniform4i(uniformLocation(name), v.x, v.y, v.z, v.w);
}

void GlProgram::set(std::string_view name, const glm::mat4& v) const {
  gl_->UniformMatrix4fv(uniformLocation(name), 1, GL_FALSE, &v[0][0]);
}

}  // namespace sortlast
