// The ray caster's part for several fields (render/volume/field_bricks.h): one transfer table per
// field, a brick's field textures and per-block ranges, the empty test of a block under every
// field, and the FIELDS program's uniforms (render/volume/raycast_fields.frag.glsl).
#include <algorithm>
#include <cfloat>
#include <stdexcept>
#include <string>

#include "render/volume/raycast_renderer.h"

namespace sortlast {

namespace {
// Texture units: the program's own take 0-7 (volume, table, surface, planes, skip, adaptive
// blocks, pre-integration, glow); field f's volume is on kFieldUnit + f, its table on
// kFieldUnit + kMaxUnits + f (16 units in all, what every GL 4.5 driver has).
constexpr int kFieldUnit = 8, kMaxUnits = 4;
}  // namespace

void RaycastRenderer::setFieldTransfers(const std::vector<TransferFunction>& tfs, const std::vector<int>& table_sizes) {
  if (tfs.size() > size_t(kMaxUnits))
    throw std::logic_error("ray caster: more than " + std::to_string(kMaxUnits) + " fields");
  while (field_tables_.size() < tfs.size()) field_tables_.push_back(std::make_unique<TransferTable>(gl_));
  field_tables_.resize(tfs.size());
  int version = 0;
  for (size_t f = 0; f < tfs.size(); ++f) {
    field_tables_[f]->set(tfs[f], table_sizes.at(f));
    version += field_tables_[f]->version();
  }
  field_tables_version_ = version;
  gl_.ActiveTexture(GL_TEXTURE0);
}

int RaycastRenderer::addFieldsBrick(const Brick& brick, const GridGeometry& grid,
                                    const std::vector<FieldBrickPart>& parts) {
  GpuBrick g;
  g.volume.brick = brick;
  g.volume.spacing = grid.spacing;
  volume_box_ = grid.worldBox();  // the layout grid's: where every ray's lattice span starts and ends
  // The blocks: the layout grid's ray blocks cut by the brick's faces (as cutBrickBlocks cuts
  // them), each block's range per field below.
  const RayBlockGrid rg = rayBlockGrid(grid, block_cells_);
  const int B = rg.cells;
  BrickBlocks& b = g.blocks;
  for (int a = 0; a < 3; ++a) {
    const int lo = brick.domain.lo[a], hi = brick.domain.hi[a];
    std::vector<int> cuts{lo};
    for (int c = (lo / B + 1) * B; c < hi; c += B) cuts.push_back(c);
    cuts.push_back(hi);
    b.first[a] = lo / B;
    b.count[a] = int(cuts.size()) - 1;
    for (int c : cuts) {
      glm::dvec3 idx(0.0);
      idx[a] = c;
      b.planes[a].push_back(grid.worldOfIndex(idx)[a]);
    }
  }
  const size_t n = size_t(b.count.x) * size_t(b.count.y) * size_t(b.count.z);
  // No step rule with several fields: the ranges adaptive steps reduce stay empty.
  b.vmin.assign(n, FLT_MAX);
  b.vmax.assign(n, -FLT_MAX);
  b.grown_min.assign(n, FLT_MAX);
  b.grown_max.assign(n, -FLT_MAX);
  for (const FieldBrickPart& part : parts) {
    if (part.samples->size() != size_t(part.stored.count()))
      throw std::logic_error("addFieldsBrick: sample count does not match the field's part");
    FieldGpu f;
    f.field = part.field;
    f.box = part.grid.worldBox();
    const Brick as_brick{brick.id, brick.cell, part.stored, part.stored, part.grid.worldBoxOf(part.stored)};
    f.volume = uploadVolumeBrick(gl_, as_brick, part.grid, FloatBrickSamples(*part.samples, part.stored), 0, pool_);
    fieldBlockRanges(part, b.planes, f.vmin, f.vmax);
    g.fields.push_back(std::move(f));
  }
  min_spacing_ = grid.minSpacing();
  global_count_ = rg.count;
  return addGpuBrick(std::move(g));
}

bool RaycastRenderer::fieldsVisible(const GpuBrick& g, size_t i) const {
  for (const FieldGpu& f : g.fields)
    if (size_t(f.field) < field_tables_.size() && field_tables_[size_t(f.field)]->visible(f.vmin[i], f.vmax[i]))
      return true;
  return false;
}

void RaycastRenderer::useFields(const GlProgram& program, const GpuBrick& g) const {
  for (size_t f = 0; f < field_tables_.size(); ++f) {
    const std::string i = "[" + std::to_string(f) + "]";
    const TransferFunction& tf = field_tables_[f]->function();
    const double range = tf.rangeHi() - tf.rangeLo();
    program.set("u_field_value_map" + i, glm::vec2(float(1.0 / range), float(-tf.rangeLo() / range)));
    const double size = double(field_tables_[f]->size());
    program.set("u_field_table_map" + i, glm::vec2(float((size - 1) / size), float(0.5 / size)));
    program.set("u_field_volume" + i, kFieldUnit + int(f));
    program.set("u_field_table" + i, kFieldUnit + kMaxUnits + int(f));
    // Not in this brick: an empty box, so no sample reads the (unbound) unit.
    program.set("u_field_lo" + i, glm::vec3(1e30f));
    program.set("u_field_hi" + i, glm::vec3(-1e30f));
    field_tables_[f]->bindTo(kFieldUnit + kMaxUnits + int(f));
  }
  for (const FieldGpu& f : g.fields) {
    const std::string i = "[" + std::to_string(f.field) + "]";
    program.set("u_field_tex_scale" + i, f.volume.tex_scale);
    program.set("u_field_tex_offset" + i, f.volume.tex_offset);
    program.set("u_field_lo" + i, glm::vec3(f.box.lo));
    program.set("u_field_hi" + i, glm::vec3(f.box.hi));
    gl_.ActiveTexture(GLenum(GL_TEXTURE0 + kFieldUnit + f.field));
    gl_.BindTexture(GL_TEXTURE_3D, f.volume.texture);
  }
  gl_.ActiveTexture(GL_TEXTURE0);
}

}  // namespace sortlast
