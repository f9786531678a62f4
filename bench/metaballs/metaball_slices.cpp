// Times the slices method's per-brick work (render/particles/metaball_slices_renderer.h), paid once
// per brick and time step: the coarse bit voxelization, the slots and lists (CPU,
// buildSliceLattice), and the whole addBrick (that, the upload and the splat in a compute shader).
// Also the bit voxelization done in GL instead (bench_voxelize.comp.glsl, one invocation per
// particle, atomicOr into the bit grid, read back), which the renderer does not use: it is measured
// here against the CPU pass it would replace. One brick over the whole set; prints one JSON line,
// the fastest of --repeats runs.
// Usage: bench_metaball_slices [procedural (splash | layers)] [count] [spacing (units of h)]
// [repeats]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench/metaballs/glsl_files.h"  // generated from bench/metaballs/*.glsl (cmake/embed_shaders.cmake)
#include "io/particles.h"
#include "render/gl/gl_program.h"
#include "render/particles/metaball_slices.h"
#include "render/particles/metaball_slices_renderer.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sortlast;
  const std::string name = argc > 1 ? argv[1] : "splash";
  const long long count = argc > 2 ? std::atoll(argv[2]) : 1000000;
  const double rel = argc > 3 ? std::atof(argv[3]) : 0.25;
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 3;
  const double spacing = 0.3, h = 0.61;  // configs/particles_layers.yaml
  ParticleSet set = proceduralParticles(name, count, spacing);
  Box3 b = set.bounds();
  Box3 clip{b.lo - h, b.hi + h};
  MetaballSettings s;
  s.h = h;
  s.step = h / 8;
  s.method = ParticleMethod::kSlices;
  s.slice_spacing = rel;
  auto ctx = createGlContext("osmesa");
  const GlApi& gl = ctx->gl();

  double cpu_bits = 1e30, cpu = 1e30, brick = 1e30, glvox = 1e30;
  SliceLattice L;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = Clock::now();
    L = markSliceVoxels(set.positions, clip, h, rel * h, s.step);
    cpu_bits = std::min(cpu_bits, since(t0));
    allocateSlices(L, set.positions, h);
    cpu = std::min(cpu, since(t0));
    MetaballSlicesRenderer r(*ctx, 16, 16, s);
    t0 = Clock::now();
    r.addBrick(clip, set.positions);
    gl.Finish();
    brick = std::min(brick, since(t0));
  }
  // GL voxelization of the same voxels: upload, dispatch, read back.
  unsigned prog = linkComputeProgram(gl, ShaderSource().add(glsl::bench_voxelize_comp));
  std::vector<glm::vec4> centres(set.positions.size());
  for (size_t i = 0; i < centres.size(); ++i) centres[i] = glm::vec4(set.positions[i], 0.0f);
  const size_t words = (L.voxelCount() + 31) / 32;
  std::vector<uint32_t> bits(words);
  for (int i = 0; i < repeats; ++i) {
    auto t0 = Clock::now();
    unsigned buf[2];
    gl.GenBuffers(2, buf);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[0]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(centres.size() * 16), centres.data(),
                  GL_STATIC_DRAW);
    std::vector<uint32_t> zero(words, 0);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[1]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(words * 4), zero.data(), GL_DYNAMIC_READ);
    gl.UseProgram(prog);
    gl.Uniform1ui(gl.GetUniformLocation(prog, "u_count"), unsigned(centres.size()));
    gl.Uniform1f(gl.GetUniformLocation(prog, "u_r"), float(h * 1.01));
    gl.Uniform1f(gl.GetUniformLocation(prog, "u_edge"), L.spacing * float(kSliceVoxelCells));
    gl.Uniform4i(gl.GetUniformLocation(prog, "u_lo"), L.voxel_lo.x, L.voxel_lo.y, L.voxel_lo.z, 0);
    gl.Uniform4i(gl.GetUniformLocation(prog, "u_dims"), L.dims.x, L.dims.y, L.dims.z, 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buf[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buf[1]);
    gl.DispatchCompute(unsigned((centres.size() + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(words * 4), bits.data());
    glvox = std::min(glvox, since(t0));
    gl.DeleteBuffers(2, buf);
  }
  // The GL bits must be the CPU's (the same test, in float; a voxel at exactly the padded
  // distance could round either way: counted, not hidden).
  size_t differ = 0;
  for (size_t v = 0; v < L.voxelCount(); ++v)
    differ += L.occupied(v) != bool((bits[v >> 5] >> (v & 31)) & 1u);
  std::printf(
      "{\"procedural\": \"%s\", \"particles\": %lld, \"slice_spacing\": %g, \"voxels\": %zu, "
      "\"slots\": %zu, \"list_entries\": %zu, \"samples_mib\": %.1f, \"cpu_bits_s\": %.4f, "
      "\"gl_bits_s\": %.4f, \"bits_differ\": %zu, \"cpu_lattice_s\": %.4f, \"add_brick_s\": "
      "%.4f}\n",
      name.c_str(), count, rel, L.voxelCount(), L.slots(), L.items.size(),
      double(L.slots()) * kSliceSlotPoints * 4 / 1048576.0, cpu_bits, glvox, differ, cpu, brick);
  return 0;
}
