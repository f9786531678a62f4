#include "worker/raycast_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "worker/adaptive_gpu_brick.h"
#include "worker/gl_program.h"
#include "worker/raycast_shaders.h"
#include "worker/volume_shading.h"

namespace sortlast {

RaycastRenderer::RaycastRenderer(const GlContext& ctx, int width, int height, int block_cells,
                                 const RaycastSettings& settings)
    : gl_(ctx.gl()),
      block_cells_(std::max(1, block_cells)),
      settings_(settings),
      target_(gl_, width, height),
      table_(gl_) {
  program_ = linkProgram(gl_, shaders::kRaycastVertex, shaders::kRaycastFragment);
  // A core-profile draw needs a vertex array, though the triangle has no attributes.
  gl_.GenVertexArrays(1, &vao_);
  gl_.check("ray caster setup");
}

RaycastRenderer::~RaycastRenderer() {
  for (auto& b : bricks_) {
    gl_.DeleteTextures(1, &b.volume.texture);
    gl_.DeleteTextures(1, &b.planes);
    gl_.DeleteTextures(1, &b.visible);
    if (b.adaptive) gl_.DeleteTextures(1, &b.lookup.table);
  }
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteProgram(program_);
  if (adaptive_program_) gl_.DeleteProgram(adaptive_program_);
  for (unsigned p : variant_programs_)
    if (p) gl_.DeleteProgram(p);
}

void RaycastRenderer::setTransferFunction(const TransferFunction& tf, int table_size,
                                          bool preintegrated) {
  table_.set(tf, table_size, preintegrated);
}

namespace {
// The fragment shader with `define` set (the #define must follow the #version line).
std::string variant(const char* define) {
  std::string src = shaders::kRaycastFragment;
  const std::string version = "#version 450 core\n";
  if (src.rfind(version, 0) != 0) throw std::logic_error("ray caster shader: no #version line");
  src.insert(version.size(), std::string("#define ") + define + " 1\n");
  return src;
}
}  // namespace

namespace {
// Integer and single-row textures are read with texelFetch only: no filtering, no mipmaps (a
// texture without them must not ask for mipmap filtering, or it is incomplete and reads zero).
void nearest(const GlApi& gl, GLenum target) {
  gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}
}  // namespace

int RaycastRenderer::addBrick(const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples) {
  GpuBrick g;
  g.volume = uploadVolumeBrick(gl_, brick, grid, samples, block_cells_);
  return addGpuBrick(std::move(g));
}

int RaycastRenderer::addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) {
  GpuBrick g;
  g.volume = uploadVolumeBrick(gl_, brick, grid, samples, block_cells_);
  return addGpuBrick(std::move(g));
}

int RaycastRenderer::addAdaptiveBrick(const Brick& brick, const GridGeometry& grid,
                                      const AdaptiveBrickBlocks& blocks) {
  if (!adaptive_program_)
    adaptive_program_ = linkProgram(gl_, shaders::kRaycastVertex, variant("ADAPTIVE").c_str());
  AdaptiveGpuBrick a = uploadAdaptiveBrick(gl_, brick, grid, blocks);
  GpuBrick g;
  g.volume = std::move(a.volume);
  g.adaptive = true;
  g.lookup = {a.table, a.index_scale, a.index_offset, a.block_cells, a.atlas_inv};
  return addGpuBrick(std::move(g));
}

int RaycastRenderer::addGpuBrick(GpuBrick g) {
  const glm::ivec3 nb = g.volume.block_count;
  const int width = std::max({nb.x, nb.y, nb.z}) + 1;
  // The planes as floats: a face shared with a neighbouring brick is the same double there, so
  // the same float, and both bricks compute the same ray distance for it.
  std::vector<float> planes(size_t(width) * 3, 0.0f);
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= nb[a]; ++i)
      planes[size_t(a) * width + i] = float(g.volume.block_planes[a][size_t(i)]);
  gl_.GenTextures(1, &g.planes);
  gl_.ActiveTexture(GL_TEXTURE3);
  gl_.BindTexture(GL_TEXTURE_2D, g.planes);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, 3, 0, GL_RED, GL_FLOAT, planes.data());
  nearest(gl_, GL_TEXTURE_2D);
  gl_.GenTextures(1, &g.visible);
  gl_.ActiveTexture(GL_TEXTURE4);
  gl_.BindTexture(GL_TEXTURE_3D, g.visible);
  gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, nb.x, nb.y, nb.z, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 nullptr);
  nearest(gl_, GL_TEXTURE_3D);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.check("ray caster brick upload");
  bricks_.push_back(std::move(g));
  return int(bricks_.size()) - 1;
}

RenderedBrick RaycastRenderer::render(int handle, const Camera& cam, double spacing,
                                      double /*near_plane*/, double /*far_plane*/,
                                      const SurfaceLayer* surface) {
  GpuBrick& g = bricks_.at(size_t(handle));
  const VolumeBrick& b = g.volume;
  RenderedBrick out;
  const bool preint = table_.preintegrated();
  if (preint && g.adaptive)  // the scene refuses this (transfer.preintegrated with adaptive.tolerance)
    throw std::logic_error("ray caster: pre-integration of adaptive bricks is not supported");
  // Which blocks the current transfer function shows, and the box around them (the rectangle).
  std::vector<unsigned char> shown(b.blocks.size());
  Box3 bound{glm::dvec3(1e300), glm::dvec3(-1e300)};
  bool any = false;
  for (size_t i = 0; i < b.blocks.size(); ++i) {
    const VolumeBlock& blk = b.blocks[i];
    // Pre-integrated segments reach up to one voxel beyond the block (worker/raycast_shaders.h).
    shown[i] = (preint ? table_.visible(blk.gmin, blk.gmax) : table_.visible(blk.vmin, blk.vmax)) ? 1 : 0;
    if (!shown[i]) continue;
    any = true;
    bound.lo = glm::min(bound.lo, blk.world.lo);
    bound.hi = glm::max(bound.hi, blk.world.hi);
  }
  Rect r = any ? screenRectOf(cam, bound) : Rect{};
  const bool has_surface = surface && !surface->rect.empty();
  if (has_surface) r = r.empty() ? surface->rect : unite(r, surface->rect);
  if (r.empty()) return out;

  target_.begin(r, has_surface ? surface : nullptr);
  if (any) {
    if (shown != g.shown) {
      gl_.ActiveTexture(GL_TEXTURE4);
      gl_.BindTexture(GL_TEXTURE_3D, g.visible);
      gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
      gl_.TexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, b.block_count.x, b.block_count.y, b.block_count.z,
                     0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, shown.data());
      g.shown = shown;
    }
    gl_.Enable(GL_BLEND);
    gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // the ray's colour over the surface's
    // Adaptive blocks cannot be shaded (raycast_shaders.h shadedSample); the scene refuses it.
    if (g.adaptive && shading_.enabled)
      throw std::logic_error("ray caster: gradient shading of an adaptive brick");
    const int v = (preint ? 1 : 0) + (shading_.enabled ? 2 : 0);
    if (!g.adaptive && v != 0 && !variant_programs_[v]) {
      const std::string src = preint ? variant("PREINTEGRATED") : std::string(shaders::kRaycastFragment);
      variant_programs_[v] = linkProgram(gl_, shaders::kRaycastVertex,
                                         shading_.enabled ? withShading(src.c_str()).c_str() : src.c_str());
    }
    const unsigned program = g.adaptive ? adaptive_program_ : v != 0 ? variant_programs_[v] : program_;
    gl_.UseProgram(program);
    auto u3 = [&](const char* name, const glm::dvec3& v) {
      gl_.Uniform3f(gl_.GetUniformLocation(program, name), float(v.x), float(v.y), float(v.z));
    };
    // The image plane at distance 1: pixel centre (x, y) is forward + sx right + sy up, as in
    // Camera::rayDirection.
    const double th = std::tan(0.5 * cam.fov_deg * 3.14159265358979323846 / 180.0);
    u3("u_eye", cam.position);
    u3("u_forward", cam.forward());
    u3("u_right", cam.right() * (th * double(cam.width) / cam.height));
    u3("u_up", cam.trueUp() * th);
    if (g.adaptive) {
      u3("u_index_scale", glm::dvec3(g.lookup.index_scale));
      u3("u_index_offset", glm::dvec3(g.lookup.index_offset));
      u3("u_block_cells", glm::dvec3(g.lookup.block_cells));
      u3("u_atlas_inv", glm::dvec3(g.lookup.atlas_inv));
      gl_.Uniform1i(gl_.GetUniformLocation(program, "u_blocks"), 5);
      gl_.Uniform1i(gl_.GetUniformLocation(program, "u_own_steps"),
                    settings_.own_resolution_steps ? 1 : 0);
      gl_.ActiveTexture(GL_TEXTURE5);
      gl_.BindTexture(GL_TEXTURE_3D, g.lookup.table);
    } else {
      u3("u_tex_scale", glm::dvec3(b.tex_scale));
      u3("u_tex_offset", glm::dvec3(b.tex_offset));
    }
    gl_.Uniform2f(gl_.GetUniformLocation(program, "u_pixel_scale"), float(2.0 / cam.width),
                  float(2.0 / cam.height));
    gl_.Uniform1f(gl_.GetUniformLocation(program, "u_delta"), float(spacing));
    gl_.Uniform1f(gl_.GetUniformLocation(program, "u_ert"),
                  settings_.ert_threshold < 1.0 ? float(settings_.ert_threshold) : 2.0f);
    gl_.Uniform1i(gl_.GetUniformLocation(program, "u_volume"), 0);
    gl_.Uniform1i(gl_.GetUniformLocation(program, "u_surface"), 2);
    gl_.Uniform1i(gl_.GetUniformLocation(program, "u_planes"), 3);
    gl_.Uniform1i(gl_.GetUniformLocation(program, "u_visible"), 4);
    gl_.Uniform1i(gl_.GetUniformLocation(program, "u_has_surface"), has_surface ? 1 : 0);
    table_.use(program);
    if (preint) table_.usePreintegrated(program, spacing);  // segments delta long
    if (shading_.enabled) setShadingUniforms(gl_, program, shading_, b, table_.function());
    if (has_surface) {
      const Rect& sr = surface->rect;
      gl_.Uniform4i(gl_.GetUniformLocation(program, "u_surface_rect"), sr.x, sr.y, sr.w, sr.h);
      gl_.ActiveTexture(GL_TEXTURE2);
      gl_.BindTexture(GL_TEXTURE_2D, surface->surface_texture);
    }
    gl_.ActiveTexture(GL_TEXTURE3);
    gl_.BindTexture(GL_TEXTURE_2D, g.planes);
    gl_.ActiveTexture(GL_TEXTURE4);
    gl_.BindTexture(GL_TEXTURE_3D, g.visible);
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, b.texture);
    gl_.BindVertexArray(vao_);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    gl_.Disable(GL_BLEND);
  }
  out.rect = r;
  out.pixels = target_.finish(r);
  return out;
}

}  // namespace sortlast
