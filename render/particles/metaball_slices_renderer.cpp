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
  // Anisotropic smoothing: the splat with the per-particle kernel (the round one stays as it
  // was, so its images do not change). The ray pass is the same: it reads only the lattice.
  splat_ = GlProgram(gl_, linkComputeProgram(gl_, ShaderSource()
                                                      .define("SIDE", side)
                                                      .defineIf(s_.anisotropic, "ANISOTROPIC")
                                                      .add(glsl::metaball_slices_splat_comp)));
  gl_.check("metaball slices renderer setup");
}

void MetaballSlicesRenderer::setSettings(const MetaballSettings& settings) {
  if (settings.h != s_.h || settings.slice_spacing != s_.slice_spacing || settings.step > s_.step ||
      settings.anisotropic != s_.anisotropic || settings.anisotropic_params != s_.anisotropic_params)
    throw std::logic_error(
        "MetaballSlicesRenderer::setSettings: h, the slice spacing or the smoothing changed, or the "
        "step grew");
  s_ = settings;
}

int MetaballSlicesRenderer::addBrick(const Box3& clip, const std::vector<glm::vec3>& all) {
  GpuBrick g;
  g.clip = clip;
  const double spacing = s_.slice_spacing * s_.h;
  // Anisotropic: every particle's kernel from the brick's particles and ghosts, then only those
  // whose ellipsoid reaches the box the lattice serves (the clip box grown by a ray step and 2.5
  // spacings, ParticleDesc::ghostMargin) are kept, in order, at their kernels' centres. Their
  // neighbourhoods lie wholly in the ghost margin, so their kernels are what any rank computes.
  std::vector<glm::vec3> kept;
  std::vector<ParticleKernel> kernels;
  std::vector<float> reach;
  double h_bound = s_.h;
  if (s_.anisotropic && !all.empty()) {
    std::vector<ParticleKernel> k = computeAnisotropicKernels(all, s_.h, s_.anisotropic_params);
    const double serve = s_.step + 2.5 * spacing;
    for (size_t i = 0; i < all.size(); ++i) {
      glm::dvec3 q(k[i].centre);
      glm::dvec3 d = glm::max(glm::max(clip.lo - q, q - clip.hi), glm::dvec3(0.0));
      if (glm::length(d) <= double(k[i].reach) + serve)
        kept.push_back(k[i].centre), kernels.push_back(k[i]), reach.push_back(k[i].reach);
    }
    h_bound = std::max(s_.h, maxReach(kernels));
  }
  const std::vector<glm::vec3>& particles = s_.anisotropic ? kept : all;
  // What one storage block holds bounds the voxels and samples (4 bytes each) and the list
  // entries (16).
  const size_t max_entries = size_t(max_block_bytes_ / 4);
  SliceLattice L;
  try {
    L = buildSliceLattice(particles, clip, h_bound, spacing, s_.step, max_entries,
                          s_.anisotropic ? &reach : nullptr);
  } catch (const std::length_error& e) {
    std::ostringstream msg;
    msg << "scene key 'particles.slice_spacing': " << s_.slice_spacing
        << " h needs more lattice samples in one brick than the GPU holds in one buffer ("
        << e.what() << "); use a larger spacing or more bricks (bricks.per_axis)";
    throw InputError(msg.str());
  }
  if (L.slots() > 0) splat(g, L, particles, s_.anisotropic ? &kernels : nullptr);
  bricks_.push_back(g);
  return int(bricks_.size()) - 1;
}

void MetaballSlicesRenderer::splat(GpuBrick& g, const SliceLattice& L,
                                   const std::vector<glm::vec3>& particles,
                                   const std::vector<ParticleKernel>* kernels) {
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
  // Anisotropic: per particle 3 vec4, (A row 0, C), (A row 1, reach), (A row 2, unused), as the
  // grid method's (A is symmetric).
  unsigned frames = 0;
  if (kernels) {
    std::vector<glm::vec4> k(kernels->size() * 3);
    for (size_t i = 0; i < kernels->size(); ++i) {
      const ParticleKernel& pk = (*kernels)[i];
      k[3 * i] = glm::vec4(pk.a[0], pk.c);
      k[3 * i + 1] = glm::vec4(pk.a[1], pk.reach);
      k[3 * i + 2] = glm::vec4(pk.a[2], 0.0f);
    }
    if (double(k.size()) * 16.0 > double(max_block_bytes_))
      throw std::runtime_error("metaball slices: a brick's anisotropic kernels (" +
                               std::to_string(k.size() * 16) +
                               " bytes) exceed one shader storage block; use more bricks");
    frames = uploadStorage(k.data(), k.size() * sizeof(glm::vec4));
  }
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
  if (kernels) gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, frames);
  // At most 65,535 work groups per dispatch (the minimum GL guarantees).
  for (size_t first = 0; first < g.slots; first += 65535) {
    splat_.set("u_first", unsigned(first));
    gl_.DispatchCompute(unsigned(std::min<size_t>(65535, g.slots - first)), 1, 1);
  }
  gl_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  for (unsigned b : {offsets, list, voxels}) gl_.DeleteBuffers(1, &b);
  if (frames) gl_.DeleteBuffers(1, &frames);
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
