#include "render/volume/slicing_renderer.h"

#include <algorithm>
#include <cfloat>
#include <stdexcept>
#include <string>

#include "common/visibility.h"
#include "render/volume/bounded_pixels.h"
#include "render/volume/glsl_files.h"  // generated from render/volume/*.glsl
#include "render/volume/slice_geometry.h"
#include "render/volume/volume_clip.h"
#include "render/volume/volume_shading.h"

namespace sortlast {

namespace {
// (A struct, not an enum, so that the names stay apart from the ray caster's variant bits when
// both files are compiled as one unity source: CMAKE_UNITY_BUILD.)
struct SlicingVariant {
  static constexpr unsigned kPreintegrated = 1;  // PREINTEGRATED: transfer.preintegrated
  static constexpr unsigned kShading = 2;        // SHADING: render.shading
  static constexpr unsigned kFloatFilter = 4;    // FLOAT_FILTER: the volume filtered in float (volume_shading.h floatFilter)
  // PROJECTION = 1 mip, 2 minip, 3 average, 4 additive (bits 3-5; render/volume/slicing.frag.glsl)
  static constexpr unsigned kProjectionShift = 3;
  static constexpr unsigned kProjectionMask = 7u << kProjectionShift;
};

// The PROJECTION define of a blend mode (0: emission-absorption), the ray caster's numbering.
unsigned projectionOf(VolumeBlend b) {
  switch (b) {
    case VolumeBlend::kComposite: return 0;
    case VolumeBlend::kMip: return 1;
    case VolumeBlend::kMinip: return 2;
    case VolumeBlend::kAverage: return 3;
    case VolumeBlend::kAdditive: return 4;
    default: throw std::logic_error("slicing: render.blend isosurface is the ray caster's only");
  }
}

// mip / minip pixels read back from the GL_MAX target into compositing/projection_pixels.h's
// format: a pixel no fragment reached (weight 0, value -FLT_MAX) becomes (0, 0, 0, 0), and
// minip's negated values (`negated`) are turned back.
void finishExtremum(std::vector<float>& px, bool negated) {
  for (size_t i = 0; i < px.size(); i += 4) {
    float* p = &px[i];
    if (!(p[3] > 0.0f))
      p[0] = p[1] = p[2] = p[3] = 0.0f;
    else if (negated)
      p[0] = -p[0];  // exact: a sign flip
  }
}

// A variant's sources: render/volume/slicing.frag.glsl describes the chunks.
ProgramSources slicingSources(unsigned v) {
  const bool preint = v & SlicingVariant::kPreintegrated, shading = v & SlicingVariant::kShading;
  const unsigned projection = (v & SlicingVariant::kProjectionMask) >> SlicingVariant::kProjectionShift;
  ShaderSource fragment;
  if (projection) fragment.define("PROJECTION", std::to_string(projection));
  fragment.defineIf(preint, "PREINTEGRATED")
      .defineIf(shading, "SHADING")
      .defineIf(v & SlicingVariant::kFloatFilter, "FLOAT_FILTER")
      .add(glsl::volume_filter)
      .add(glsl::value_scale)
      .addIf(shading, glsl::volume_shading)
      .add(glsl::slicing_inputs_frag)
      .add(glsl::volume_clip)
      .addIf(preint, glsl::preintegrated_segment)
      .add(glsl::slicing_frag);
  return {ShaderSource().add(glsl::slicing_vert), fragment};
}
}  // namespace

SlicingRenderer::SlicingRenderer(const GlContext& ctx, int width, int height, int block_cells,
                                 const SlicingSettings& settings)
    : gl_(ctx.gl()),
      float_filter_(floatFilter(ctx.info())),
      block_cells_(std::max(1, block_cells)),
      target_(gl_, width, height),
      table_(gl_),
      settings_(settings),
      programs_(gl_, slicingSources) {
  programs_.get(float_filter_ ? SlicingVariant::kFloatFilter : 0);  // the plain program now: a driver that cannot build it fails here
  gl_.GenVertexArrays(1, &vao_);
  gl_.BindVertexArray(vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  gl_.EnableVertexAttribArray(0);
  gl_.check("renderer setup");
}

SlicingRenderer::~SlicingRenderer() {
  for (auto& b : bricks_) gl_.DeleteTextures(1, &b.texture);
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
}

void SlicingRenderer::setTransferFunction(const TransferFunction& tf, int table_size,
                                          bool preintegrated) {
  table_.set(tf, table_size, preintegrated);
}

int SlicingRenderer::addBrick(const Brick& brick, const GridGeometry& grid,
                              const std::vector<float>& samples) {
  bricks_.push_back(uploadVolumeBrick(gl_, brick, grid, samples, block_cells_));
  return int(bricks_.size()) - 1;
}

int SlicingRenderer::addBrick(const Brick& brick, const GridGeometry& grid, const BrickSamples& samples) {
  bricks_.push_back(uploadVolumeBrick(gl_, brick, grid, samples, block_cells_));
  return int(bricks_.size()) - 1;
}

RenderedBrick SlicingRenderer::render(int handle, const Camera& cam, double spacing,
                                      double near_plane, double far_plane,
                                      const SurfaceLayer* surface) {
  const VolumeBrick& b = bricks_.at(size_t(handle));
  RenderedBrick out;
  const unsigned projection = projectionOf(settings_.blend);
  const bool has_surface = surface && !surface->rect.empty();
  if (projection && ((has_surface && !settings_.bounded) || shading_.enabled))  // the scene refuses these
    throw std::logic_error("slicing: a projection with shading, or a surface in a frame not drawn in "
                           "the bounded formats");
  const bool preint = table_.preintegrated() && !projection;  // segments mean nothing to a projection
  // mip, minip and average count every sample whatever its opacity: every block holding samples
  // is drawn. Additive adds c a, exactly zero where the table's opacity is: its empty blocks are
  // skipped as emission-absorption's (the ray caster's rule, raycast_renderer.cpp classify).
  const bool counts_all = projection >= 1 && projection <= 3;
  glm::dvec3 eye = cam.position, fwd = cam.forward();
  // Visible blocks, back to front (orthographic: by the view direction, common/visibility.h
  // orderEye), and the box around them (which sets the output rectangle).
  std::vector<float> tris;
  Box3 bound{glm::dvec3(1e300), glm::dvec3(-1e300)};
  const auto& bp = b.block_planes;
  const Box3 brick_box{{bp[0].front(), bp[1].front(), bp[2].front()}, {bp[0].back(), bp[1].back(), bp[2].back()}};
  for (int id : backToFrontOrder(b.block_planes, orderEye(cam, brick_box))) {
    const VolumeBlock& blk = b.blocks[size_t(id)];
    // Pre-integrated segments reach ds/2 beyond the block: its range grown by one voxel.
    if (counts_all ? !(blk.vmin <= blk.vmax)
        : preint   ? !table_.visible(blk.gmin, blk.gmax)
                   : !table_.visible(blk.vmin, blk.vmax))
      continue;
    if (clip_.culls(blk.world)) continue;  // wholly outside clip.planes / clip.box
    bound.lo = glm::min(bound.lo, blk.world.lo);
    bound.hi = glm::max(bound.hi, blk.world.hi);
    // Slices start just beyond the near plane so no polygon is clipped by it.
    std::vector<float> t = sliceTriangles(blk.world, eye, fwd, spacing, near_plane * 1.001);
    tris.insert(tris.end(), t.begin(), t.end());
  }
  Rect r = tris.empty() ? Rect{} : clippedRectOf(cam, bound, clip_);
  if (has_surface) r = r.empty() ? surface->rect : unite(r, surface->rect);
  if (r.empty()) return out;

  // A projection's target starts empty: the layer's colour is added after (toBoundedPixels).
  target_.begin(r, has_surface && !projection ? surface : nullptr);
  // mip and minip blend with GL_MAX (minip of the negated values, slicing.frag.glsl): the
  // target starts at the operator's identity in the value channel, -FLT_MAX, below any sample
  // (cleared again over begin()'s zeros, within the same scissor); the weight channel stays 0
  // where no fragment lands, and finishExtremum() makes those pixels all zero, as the ray
  // caster leaves them.
  const bool max_blend = projection == 1 || projection == 2;
  if (max_blend) {
    gl_.ClearColor(-FLT_MAX, 0.0f, 0.0f, 0.0f);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
    gl_.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  }
  if (!tris.empty()) {
    gl_.Enable(GL_BLEND);
    if (max_blend) {
      gl_.BlendEquation(GL_MAX);  // (the blend factors do not apply to GL_MAX)
    } else if (projection) {
      gl_.BlendFunc(GL_ONE, GL_ONE);  // sums: average's (value, count), additive's (c a, a)
    } else {
      gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over", back to front
    }
    const GlProgram& program =
        programs_.get((preint ? SlicingVariant::kPreintegrated : 0) | (shading_.enabled ? SlicingVariant::kShading : 0) |
                      (float_filter_ ? SlicingVariant::kFloatFilter : 0) | (projection << SlicingVariant::kProjectionShift));
    gl_.UseProgram(program);
    glm::mat4 vp = cam.viewProjection(near_plane, far_plane);
    program.set("u_view_proj", vp);
    program.set("u_volume", 0);
    program.set("u_tex_scale", b.tex_scale);
    program.set("u_tex_offset", b.tex_offset);
    program.set("u_eye", glm::vec3(eye));
    program.set("u_forward", glm::vec3(fwd));
    program.set("u_spacing", float(spacing));
    program.set("u_orthographic", cam.orthographic() ? 1 : 0);
    setClipUniforms(program, clip_);
    table_.use(program);
    if (preint) table_.usePreintegrated(program, spacing);  // L0: the slice spacing
    if (shading_.enabled) setShadingUniforms(program, shading_, b, table_.function());
    program.set("u_surface", 2);
    program.set("u_has_surface", has_surface ? 1 : 0);
    if (has_surface) {
      const Rect& sr = surface->rect;
      program.set("u_surface_rect", glm::ivec4(sr.x, sr.y, sr.w, sr.h));
      gl_.ActiveTexture(GL_TEXTURE2);
      gl_.BindTexture(GL_TEXTURE_2D, surface->surface_texture);
    }
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_3D, b.texture);
    gl_.BindVertexArray(vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(tris.size() * sizeof(float)), tris.data(), GL_STREAM_DRAW);
    gl_.DrawArrays(GL_TRIANGLES, 0, GLsizei(tris.size() / 3));
    gl_.BlendEquation(GL_FUNC_ADD);  // the default the other renderers of the context assume
    gl_.Disable(GL_BLEND);
  }
  out.rect = r;
  if (projection) {  // a projection's pixels are values and sums: float
    out.pixels_f = target_.finishFloat(r);
    if (max_blend) finishExtremum(out.pixels_f, projection == 2);
    if (settings_.bounded) {
      // The layer's colour read back the way composite mode gets it into its target.
      std::vector<float> layer;
      if (has_surface) {
        target_.begin(r, surface);
        layer = target_.finishFloat(r);
      }
      toBoundedPixels(settings_.blend, out.pixels_f, has_surface ? &layer : nullptr);
    }
  } else {
    target_.finish(r, out);
  }
  return out;
}

}  // namespace sortlast
