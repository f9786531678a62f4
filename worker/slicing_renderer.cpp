#include "worker/slicing_renderer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "compositing/visibility.h"
#include "worker/gl_program.h"
#include "worker/slice_geometry.h"
#include "worker/slicing_shaders.h"

namespace sortlast {

SlicingRenderer::SlicingRenderer(const GlContext& ctx, int width, int height, int block_cells)
    : gl_(ctx.gl()), width_(width), height_(height), block_cells_(std::max(1, block_cells)) {
  gl_.GenTextures(1, &colour_);
  gl_.BindTexture(GL_TEXTURE_2D, colour_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.GenFramebuffers(1, &fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("OpenGL: float framebuffer of " + std::to_string(width) + " x " +
                             std::to_string(height) + " is not complete");
  program_ = linkProgram(gl_, shaders::kSliceVertex, shaders::kSliceFragment);
  gl_.GenVertexArrays(1, &vao_);
  gl_.BindVertexArray(vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  gl_.EnableVertexAttribArray(0);
  gl_.GenTextures(1, &tf_texture_);
  gl_.check("renderer setup");
}

SlicingRenderer::~SlicingRenderer() {
  for (auto& b : bricks_) gl_.DeleteTextures(1, &b.texture);
  gl_.DeleteTextures(1, &tf_texture_);
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteProgram(program_);
  gl_.DeleteFramebuffers(1, &fbo_);
  gl_.DeleteTextures(1, &colour_);
}

void SlicingRenderer::setTransferFunction(const TransferFunction& tf, int table_size) {
  tf_ = tf;
  tf_table_size_ = table_size;
  std::vector<float> table = tf.bakeTable(table_size);
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_1D, tf_texture_);
  gl_.TexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, table_size, 0, GL_RGBA, GL_FLOAT, table.data());
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.check("transfer function upload");
}

int SlicingRenderer::addBrick(const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples) {
  GpuBrick g;
  g.brick = brick;
  glm::ivec3 n = brick.stored.size();
  if (samples.size() != size_t(brick.stored.count()))
    throw std::logic_error("addBrick: sample count does not match the brick");
  // Block grid over the brick's cells; each block keeps the range of the samples it spans.
  glm::ivec3 cells = brick.domain.size() - 1, nb = (cells + block_cells_ - 1) / block_cells_;
  std::array<std::vector<int>, 3> cuts;
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i <= nb[a]; ++i) cuts[a].push_back(brick.domain.lo[a] + int((long long)cells[a] * i / nb[a]));
    for (int c : cuts[a]) {
      glm::dvec3 idx(0.0);
      idx[a] = c;
      g.block_planes[a].push_back(grid.worldOfIndex(idx)[a]);
    }
  }
  for (int bz = 0; bz < nb.z; ++bz)
    for (int by = 0; by < nb.y; ++by)
      for (int bx = 0; bx < nb.x; ++bx) {
        IndexBox box{{cuts[0][bx], cuts[1][by], cuts[2][bz]}, {cuts[0][bx + 1], cuts[1][by + 1], cuts[2][bz + 1]}};
        Block blk{grid.worldBoxOf(box), 1e30f, -1e30f};
        for (int z = box.lo.z; z <= box.hi.z; ++z)
          for (int y = box.lo.y; y <= box.hi.y; ++y) {
            const float* row = &samples[size_t(box.lo.x - brick.stored.lo.x) +
                                        size_t(n.x) * (size_t(y - brick.stored.lo.y) + size_t(n.y) * (z - brick.stored.lo.z))];
            auto [lo, hi] = std::minmax_element(row, row + (box.hi.x - box.lo.x + 1));
            blk.vmin = std::min(blk.vmin, *lo);
            blk.vmax = std::max(blk.vmax, *hi);
          }
        g.blocks.push_back(blk);
      }
  // Texel centres: stored sample s sits at texture coordinate (s - stored.lo + 0.5) / n, and the
  // sample index of world point p is p / spacing + (dims - 1) / 2.
  glm::dvec3 inv_n = 1.0 / glm::dvec3(n);
  g.tex_scale = glm::vec3(inv_n / grid.spacing);
  g.tex_offset = glm::vec3((0.5 * glm::dvec3(grid.dims - 1) - glm::dvec3(brick.stored.lo) + 0.5) * inv_n);
  gl_.GenTextures(1, &g.texture);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_3D, g.texture);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, n.x, n.y, n.z, 0, GL_RED, GL_FLOAT, samples.data());
  gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl_.TexParameteri(GL_TEXTURE_3D, w, GL_CLAMP_TO_EDGE);
  gl_.check("brick texture upload");
  bricks_.push_back(g);
  return int(bricks_.size()) - 1;
}

bool SlicingRenderer::visible(const Block& b) const {
  // The table is linearly filtered, so a value can pick up its neighbour entry: widen by one entry.
  double pad = (tf_.rangeHi() - tf_.rangeLo()) / (tf_table_size_ - 1);
  return tf_.maxOpacity(b.vmin - pad, b.vmax + pad) > 0.0;
}

RenderedBrick SlicingRenderer::render(int handle, const Camera& cam, double spacing,
                                      double near_plane, double far_plane,
                                      const SurfaceLayer* surface) {
  const GpuBrick& b = bricks_.at(size_t(handle));
  RenderedBrick out;
  glm::dvec3 eye = cam.position, fwd = cam.forward();
  // Visible blocks, back to front, and the box around them (which sets the output rectangle).
  std::vector<float> tris;
  Box3 bound{glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (int id : backToFrontOrder(b.block_planes, eye)) {
    const Block& blk = b.blocks[size_t(id)];
    if (!visible(blk)) continue;
    bound.lo = glm::min(bound.lo, blk.world.lo);
    bound.hi = glm::max(bound.hi, blk.world.hi);
    // Slices start just beyond the near plane so no polygon is clipped by it.
    std::vector<float> t = sliceTriangles(blk.world, eye, fwd, spacing, near_plane * 1.001);
    tris.insert(tris.end(), t.begin(), t.end());
  }
  Rect r = tris.empty() ? Rect{} : screenRectOf(cam, bound);
  const bool has_surface = surface && !surface->rect.empty();
  if (has_surface) r = r.empty() ? surface->rect : unite(r, surface->rect);
  if (r.empty()) return out;

  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width_, height_);
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x, r.y, r.w, r.h);
  gl_.ClearColor(0, 0, 0, 0);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  if (has_surface) {
    const Rect& s = surface->rect;
    gl_.CopyImageSubData(surface->colour_texture, GL_TEXTURE_2D, 0, s.x, s.y, 0, colour_, GL_TEXTURE_2D, 0,
                         s.x, s.y, 0, s.w, s.h, 1);
  }
  if (!tris.empty()) {
    gl_.Enable(GL_BLEND);
    gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over", back to front
    gl_.UseProgram(program_);
    glm::mat4 vp = cam.viewProjection(near_plane, far_plane);
    gl_.UniformMatrix4fv(gl_.GetUniformLocation(program_, "u_view_proj"), 1, GL_FALSE, &vp[0][0]);
    gl_.Uniform1i(gl_.GetUniformLocation(program_, "u_volume"), 0);
    gl_.Uniform1i(gl_.GetUniformLocation(program_, "u_table"), 1);
    gl_.Uniform3f(gl_.GetUniformLocation(program_, "u_tex_scale"), b.tex_scale.x, b.tex_scale.y, b.tex_scale.z);
    gl_.Uniform3f(gl_.GetUniformLocation(program_, "u_tex_offset"), b.tex_offset.x, b.tex_offset.y, b.tex_offset.z);
    gl_.Uniform3f(gl_.GetUniformLocation(program_, "u_eye"), float(eye.x), float(eye.y), float(eye.z));
    gl_.Uniform3f(gl_.GetUniformLocation(program_, "u_forward"), float(fwd.x), float(fwd.y), float(fwd.z));
    gl_.Uniform1f(gl_.GetUniformLocation(program_, "u_spacing"), float(spacing));
    double range = tf_.rangeHi() - tf_.rangeLo();
    gl_.Uniform2f(gl_.GetUniformLocation(program_, "u_value_map"), float(1.0 / range),
                  float(-tf_.rangeLo() / range));
    double n = tf_table_size_;
    gl_.Uniform2f(gl_.GetUniformLocation(program_, "u_table_map"), float((n - 1) / n), float(0.5 / n));
    gl_.Uniform1i(gl_.GetUniformLocation(program_, "u_surface"), 2);
    gl_.Uniform1i(gl_.GetUniformLocation(program_, "u_has_surface"), has_surface ? 1 : 0);
    if (has_surface) {
      const Rect& sr = surface->rect;
      gl_.Uniform4i(gl_.GetUniformLocation(program_, "u_surface_rect"), sr.x, sr.y, sr.w, sr.h);
      gl_.ActiveTexture(GL_TEXTURE2);
      gl_.BindTexture(GL_TEXTURE_2D, surface->surface_texture);
    }
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, b.texture);
    gl_.ActiveTexture(GL_TEXTURE1);
    gl_.BindTexture(GL_TEXTURE_1D, tf_texture_);
    gl_.BindVertexArray(vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(tris.size() * sizeof(float)), tris.data(), GL_STREAM_DRAW);
    gl_.DrawArrays(GL_TRIANGLES, 0, GLsizei(tris.size() / 3));
    gl_.Disable(GL_BLEND);
  }
  // Window row y is image row y (the projection flips y), so rows come back top first.
  readback_.resize(size_t(r.area()) * 4);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, readback_.data());
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.check("brick render");
  out.rect = r;
  out.pixels = ImageRGBA8(r.w, r.h);
  for (size_t i = 0; i < size_t(r.area()); ++i) toRGBA8(&readback_[4 * i], &out.pixels.px[4 * i]);
  return out;
}

}  // namespace sortlast
