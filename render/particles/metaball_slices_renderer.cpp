#include "render/particles/metaball_slices_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/particles/glsl_files.h"

namespace sortlast {

MetaballSlicesRenderer::MetaballSlicesRenderer(const GlContext& ctx, int width, int height,
                                               const MetaballSettings& settings)
    : MetaballBase(ctx, width, height, settings, "metaball slices") {
  // Both shaders with the slot side filled in.
  const std::string side = std::to_string(kSliceSlotSide);
  program_ = GlProgram(gl_, linkProgram(gl_, ShaderSource().add(glsl::fullscreen_vert),
                                        ShaderSource()
                                            .define("SIDE", side)
                                            .add(glsl::metaball_common)
                                            .add(glsl::metaball_slices_ray_frag)));
  splat_ = GlProgram(
      gl_, linkComputeProgram(
               gl_, ShaderSource().define("SIDE", side).add(glsl::metaball_slices_splat_comp)));
  gl_.check("metaball slices renderer setup");
}

void MetaballSlicesRenderer::setSettings(const MetaballSettings& settings) {
  if (settings.h != s_.h || settings.slice_spacing != s_.slice_spacing || settings.step > s_.step)
    throw std::logic_error(
        "MetaballSlicesRenderer::setSettings: h or the slice spacing changed, or the step grew");
  s_ = settings;
}

int MetaballSlicesRenderer::addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) {
  GpuBrick g;
  g.clip = clip;
  const double spacing = s_.slice_spacing * s_.h;
  // What one storage block holds bounds the voxels and samples (4 bytes each) and the list
  // entries (16).
  const size_t max_entries = size_t(max_block_bytes_ / 4);
  SliceLattice L;
  try {
    L = buildSliceLattice(particles, clip, s_.h, spacing, s_.step, max_entries);
  } catch (const std::length_error& e) {
    std::ostringstream msg;
    msg << "scene key 'particles.slice_spacing': " << s_.slice_spacing
        << " h needs more lattice samples in one brick than the GPU holds in one buffer ("
        << e.what() << "); use a larger spacing or more bricks (bricks.per_axis)";
    throw InputError(msg.str());
  }
  if (L.slots() > 0) splat(g, L, particles);
  bricks_.push_back(g);
  return int(bricks_.size()) - 1;
}

void MetaballSlicesRenderer::splat(GpuBrick& g, const SliceLattice& L,
                                   const std::vector<glm::vec3>& particles) {
  const float edge = L.spacing * float(kSliceVoxelCells);
  g.voxel_lo = L.voxel_lo;
  g.dims = L.dims;
  g.slots = L.slots();
  g.bound = intersect(g.clip, Box3{glm::dvec3(glm::vec3(L.voxel_lo) * edge),
                                   glm::dvec3(glm::vec3(L.voxel_lo + L.dims) * edge)});
  // The lists hold the centres and, in w, the particle's number (for a per-particle kernel).
  std::vector<glm::vec4> items(L.items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    const uint32_t k = L.items[i];
    float w;
    static_assert(sizeof w == sizeof k);
    std::memcpy(&w, &k, sizeof w);
    items[i] = glm::vec4(particles[k], w);
  }
  unsigned offsets = uploadStorage(L.offsets.data(), L.offsets.size() * 4);
  unsigned list = uploadStorage(items.data(), items.size() * sizeof(glm::vec4));
  unsigned voxels = uploadStorage(L.slot_voxel.data(), L.slot_voxel.size() * sizeof(glm::ivec4));
  g.slot_of = keepStorage(L.slot_of.data(), L.slot_of.size() * 4);
  g.samples = keepStorage(nullptr, 0);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, g.samples);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(g.slots * kSliceSlotPoints * sizeof(float)),
                 nullptr, GL_STATIC_DRAW);

  gl_.UseProgram(splat_);
  splat_.set("u_h", float(s_.h));
  splat_.set("u_spacing", L.spacing);
  splat_.set("u_slots", unsigned(g.slots));
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, offsets);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, list);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, voxels);
  gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, g.samples);
  // At most 65,535 work groups per dispatch (the minimum GL guarantees).
  for (size_t first = 0; first < g.slots; first += 65535) {
    splat_.set("u_first", unsigned(first));
    gl_.DispatchCompute(unsigned(std::min<size_t>(65535, g.slots - first)), 1, 1);
  }
  gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  for (unsigned b : {offsets, list, voxels}) gl_.DeleteBuffers(1, &b);
  gl_.check("metaball slices splat");
}

SurfaceBrick MetaballSlicesRenderer::render(int handle, const Camera& cam, double, double,
                                            bool want_surface) {
  const GpuBrick& b = bricks_.at(size_t(handle));
  if (b.slots == 0) return {};
  return drawOnePass(program_, b, cam, want_surface, [&] {
    program_.set("u_spacing", float(s_.slice_spacing * s_.h));
    program_.set("u_voxel_lo", glm::ivec4(b.voxel_lo, 0));
    program_.set("u_dims", glm::ivec4(b.dims, 0));
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b.slot_of);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, b.samples);
  });
}

}  // namespace sortlast
