#include "render/particles/metaball_base.h"

#include <cmath>
#include <utility>

namespace sortlast {

void setRayUniforms(const GlApi& gl, const GlProgram& p, const Camera& cam, int width, int height,
                    const MetaballSettings& s, const Box3& clip) {
  gl.UseProgram(p);
  const glm::dvec2 scale = cam.screenScale();  // tan(fov / 2) (x aspect), or parallel_scale (x aspect)
  p.set("u_eye", glm::vec3(cam.position));
  p.set("u_fwd", glm::vec3(cam.forward()));
  p.set("u_right_s", glm::vec3(cam.right() * scale.x));
  p.set("u_up_s", glm::vec3(cam.trueUp() * scale.y));
  p.set("u_orthographic", cam.orthographic() ? 1 : 0);
  p.set("u_size", glm::vec2(float(width), float(height)));
  p.set("u_h", float(s.h));
  p.set("u_T", float(s.threshold));
  p.set("u_w", float(s.step));
  p.set("u_cap", float(s.max_samples));
  p.set("u_refine", s.refine_iterations);
  p.set("u_colour", glm::vec3(s.colour));
  p.set("u_box_lo", glm::vec3(clip.lo));
  p.set("u_box_hi", glm::vec3(clip.hi));
}

MetaballBase::MetaballBase(const GlContext& ctx, int width, int height,
                           const MetaballSettings& settings, std::string name)
    : gl_(ctx.gl()), s_(settings), name_(std::move(name)), target_(ctx.gl(), width, height) {
  gl_.GenVertexArrays(1, &empty_vao_);
  GLint max_block = 0;
  gl_.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  max_block_bytes_ = max_block > 0 ? max_block : (1LL << 27);
}

MetaballBase::~MetaballBase() {
  for (unsigned b : kept_) gl_.DeleteBuffers(1, &b);
  gl_.DeleteVertexArrays(1, &empty_vao_);
}

void MetaballBase::resize(int width, int height) {
  target_.resize(width, height);
  gl_.check((name_ + " renderer resize").c_str());
}

unsigned MetaballBase::uploadStorage(const void* data, size_t bytes) const {
  unsigned b = 0;
  gl_.GenBuffers(1, &b);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes > 0 ? bytes : 4),
                 bytes > 0 ? data : nullptr, GL_STATIC_DRAW);
  return b;
}

unsigned MetaballBase::keepStorage(const void* data, size_t bytes) {
  kept_.push_back(uploadStorage(data, bytes));
  return kept_.back();
}

SurfaceBrick MetaballBase::drawOnePass(const GlProgram& program, const BrickBox& box,
                                       const Camera& cam, bool want_surface,
                                       const std::function<void()>& bind) {
  SurfaceBrick out;
  Rect r = screenRectOf(cam, box.bound);
  if (r.empty()) return out;
  setRayUniforms(gl_, program, cam, target_.width(), target_.height(), s_, box.clip);
  bind();
  target_.bindForDrawing(r, name_.c_str());
  gl_.BindVertexArray(empty_vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  target_.readBack(r, want_surface, out);
  out.rounds = 1;
  gl_.check((name_ + " render").c_str());
  return out;
}

}  // namespace sortlast
