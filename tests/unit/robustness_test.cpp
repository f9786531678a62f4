// Numbers that would overflow float math on the GPU are refused naming the key and the
// value, and the memory estimate refuses scenes that cannot fit, naming the need, its largest
// parts and the budget.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "io/anisotropic_kernels.h"
#include "scene/scene.h"
#include "session/memory_budget.h"
#include "session/session_layout.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(RangeChecks, NameTheKeyAndTheValue) {
  struct Case {
    std::vector<std::string> set;
    std::string key, value;
  };
  const Case cases[] = {
      {{"camera.position=[1e300,0,0]"}, "camera.position", "1e+300"},
      {{"camera.position=[0,-2e18,5]"}, "camera.position", "-2e+18"},
      {{"camera.look_at=[0,0,1e19]"}, "camera.look_at", "1e+19"},
      {{"camera.up=[0,1e30,0]"}, "camera.up", "1e+30"},
      {{"volume.spacing=[1e-20,1,1]"}, "volume.spacing", "1e-20"},
      {{"volume.spacing=[1,1e17,1]"}, "volume.spacing", "1.27e+19"},  // extent: 127 x 1e17
      {{"transfer.range=[0,1e39]"}, "transfer.range", "1e+39"},
      {{"transfer.range=[1e10,1.000001e10]"}, "transfer.range", "1e+10"},
      {{"transfer.unit_length=1e-30"}, "transfer.unit_length", "1e-30"},
      {{"particles.procedural=layers", "particles.radius=1e19"}, "particles.radius", "1e+19"},
      {{"particles.procedural=layers", "particles.spacing=1e-13"}, "particles.spacing", "1e-13"},
      {{"camera.orbit.radius=1e20"}, "camera.orbit.radius", "1e+20"},
  };
  for (const Case& c : cases) {
    std::string msg = inputErrorOf([&] { loadScene("", c.set); });
    EXPECT_TRUE(has(msg, c.key) && has(msg, c.value)) << c.set[0] << ": " << msg;
  }
  // NaN and infinities are named too (YAML .nan / .inf).
  for (const char* s : {"camera.position=[.nan,0,0]", "camera.up=[0,.inf,0]",
                        "volume.spacing=[1,-.inf,1]", "transfer.range=[0,.nan]"}) {
    std::string msg = inputErrorOf([&] { loadScene("", {s}); });
    std::string key = std::string(s).substr(0, std::string(s).find('='));
    EXPECT_TRUE(has(msg, key) && has(msg, "finite")) << s << ": " << msg;
  }
  std::string msg = inputErrorOf([] {
    loadScene("", {"particles.procedural=layers", "particles.radius=.nan"});
  });
  EXPECT_TRUE(has(msg, "particles.radius")) << msg;
  // Just inside the limits is fine.
  EXPECT_NO_THROW(loadScene("", {"camera.position=[1e17,0,0]", "transfer.range=[-1e30,1e30]"}));
}

TEST(RangeChecks, CameraTooFarFromTheSceneIsNamed) {
  Box3 box{glm::dvec3(-1), glm::dvec3(1)};  // size 2 sqrt(3)
  Camera c;
  c.position = {4e6, 0, 0};  // 1.15e6 sizes away
  std::string msg = inputErrorOf([&] { checkCameraOutside(c, box); });
  EXPECT_TRUE(has(msg, "camera.position") && has(msg, "4e+06") && has(msg, "1e6")) << msg;
  c.position = {3e6, 0, 0};  // 0.87e6 sizes: allowed
  EXPECT_NO_THROW(checkCameraOutside(c, box));
}

TEST(MemoryBudget, RefusesWhatCannotFitNamingTheParts) {
  // the motivating case: a 2000^3 procedural volume on 2 ranks: 4e9 samples with ghosts per rank,
  // 4 bytes on the host and 4 in the texture: > 30 GiB.
  Scene s = loadScene("", {"volume.procedural=sphere", "volume.dims=[2000,2000,2000]"});
  SessionLayout layout = makeLayout(s, noBox(), 0, 2);
  MemoryNeed need = sessionNeed(s, layout, 0, 0, false);
  const double samples = 0.5 * 2001.0 * 2001.0 * 2001.0;  // half the bricks, ghosts included
  EXPECT_GT(need.total(), 8.0 * samples * 0.99);
  EXPECT_LT(need.total(), 8.0 * samples * 1.05);  // the image's share is small
  MemoryBudget budget{16.0 * 1024 * 1024 * 1024, "16384 MiB (test)"};
  std::string msg = inputErrorOf([&] { checkMemory(need, budget, 0, "the scene"); });
  EXPECT_TRUE(has(msg, "needs about 306") && has(msg, "rank 0") && has(msg, "bricks' samples") &&
              has(msg, "16384 MiB (test)"))
      << msg;
  // Sizes beyond 2^32 samples per brick do not wrap around (size_t and double arithmetic).
  Scene huge = loadScene("", {"volume.dims=[1048576,1048576,1048576]"});
  SessionLayout hl = makeLayout(huge, noBox(), 0, 1);
  EXPECT_GT(sessionNeed(huge, hl, 0, 0, false).total(), 8.0 * 1.1e18);
  // Images: a 32768^2 frame alone needs > 40 GiB on rank 0.
  Scene big = loadScene("", {"image.width=32768", "image.height=32768"});
  EXPECT_GT(imageNeed(big, 32768, 32768, 0, 4, 8).total(), 40.0 * 1024 * 1024 * 1024);
  // Glow scenes hold their brick images in half floats (8 bytes a pixel, not 4) and a float
  // glow target with its read-back (32): rank 0 holding 2 of 8 bricks (d = 2) and receiving at
  // most 2 d = 4 adds (4 x (2 + 4) + 32) bytes a pixel.
  Scene glow = loadScene("", {"glow.emitters=[{center: [0, 0, 0], direction: [0, 0, 1], a: 1, b: 1, "
                              "color: [1, 1, 1]}]"});
  const double plain = imageNeed(loadScene("", {}), 1024, 1024, 0, 2, 8).total();
  EXPECT_DOUBLE_EQ(imageNeed(glow, 1024, 1024, 0, 2, 8).total() - plain, 1024.0 * 1024 * (4 * (2 + 4) + 32));
  // The default scene fits in 1 GiB.
  Scene small = loadScene("", {});
  SessionLayout sl = makeLayout(small, noBox(), 0, 1);
  EXPECT_NO_THROW(checkMemory(sessionNeed(small, sl, 0, 0, false),
                              MemoryBudget{1024.0 * 1024 * 1024, "1 GiB"}, 0, "x"));
}

// A GPU's memory: the textures and render targets, against 90% of what the driver
// reports free, shared by the node's ranks on that GPU; the refusal names the GPU. Without a
// report (llvmpipe), no GPU bound.
TEST(MemoryBudget, CountsTexturesAndTargetsAgainstTheGpuNamingIt) {
  Scene s = loadScene("", {"volume.procedural=sphere", "volume.dims=[2000,2000,2000]"});
  SessionLayout layout = makeLayout(s, noBox(), 0, 2);
  MemoryNeed gpu = sessionNeed(s, layout, 0, 0, false).onGpu();
  const double samples = 0.5 * 2001.0 * 2001.0 * 2001.0;
  // The R32F textures (4 bytes a sample) and the float target; not the host's samples.
  EXPECT_GT(gpu.total(), 4.0 * samples * 0.99);
  EXPECT_LT(gpu.total(), 4.0 * samples * 1.01);
  GlDeviceInfo info;
  info.renderer = "NVIDIA H200/PCIe/SSE2";
  info.device = 1;
  info.host = "node7";
  info.gpu_free_mib = 20000;
  info.gpu_memory_source = "GL_NVX_gpu_memory_info";
  MemoryBudget two = gpuMemoryBudget(info, 2);
  EXPECT_DOUBLE_EQ(two.bytes, 0.9 * 20000 * 1024.0 * 1024.0 / 2);
  std::string msg = inputErrorOf([&] { checkMemory(gpu, two, 0, "the scene's GPU textures and render targets"); });
  EXPECT_TRUE(has(msg, "GPU textures") && has(msg, "NVIDIA H200") && has(msg, "EGL device 1 of host node7") &&
              has(msg, "shared by 2 rank(s)") && has(msg, "3D textures"))
      << msg;
  // A small scene fits; an unknown GPU memory bounds nothing.
  Scene small = loadScene("", {});
  SessionLayout sl = makeLayout(small, noBox(), 0, 1);
  EXPECT_NO_THROW(checkMemory(sessionNeed(small, sl, 0, 0, false).onGpu(), two, 0, "x"));
  EXPECT_TRUE(std::isinf(gpuMemoryBudget(GlDeviceInfo{}, 1).bytes));
}

// render.device auto: the node's ranks in turn over its hardware devices; none: surfaceless.
TEST(RenderDevice, AutoSpreadsANodesRanksOverItsDevices) {
  EXPECT_EQ(autoDevice(0, 4), 0);
  EXPECT_EQ(autoDevice(3, 4), 3);
  EXPECT_EQ(autoDevice(5, 4), 1);
  EXPECT_EQ(autoDevice(2, 1), 0);
  EXPECT_EQ(autoDevice(0, 0), -1);
  EXPECT_EQ(loadScene("", {}).render.device, -1);
  EXPECT_EQ(loadScene("", {"render.backend=egl", "render.device=3"}).render.device, 3);
  std::string msg = inputErrorOf([] { loadScene("", {"render.device=1"}); });
  EXPECT_TRUE(has(msg, "render.device") && has(msg, "render.backend is osmesa")) << msg;
  msg = inputErrorOf([] { loadScene("", {"render.backend=egl", "render.device=-1"}); });
  EXPECT_TRUE(has(msg, "render.device")) << msg;
}

double partBytes(const MemoryNeed& need, const std::string& prefix) {
  for (const MemoryPart& p : need.parts)
    if (p.what.rfind(prefix, 0) == 0) return p.bytes;
  return 0.0;
}

// Anisotropic smoothing (grid method): each held particle's kernels and their GPU buffer, and
// list entries in every cell of edge h/2 its ball of the reach bound touches (about 10 times the
// round metaballs' 84). The entries expected are counted here directly: the cells within the
// reach of many random centres, averaged.
TEST(MemoryBudget, CountsAnisotropicKernelsAndTheirLongerCellLists) {
  const long long count = 10000;
  auto scene = [&](const std::string& smoothing) {
    return loadScene("", {"volume.procedural=none", "particles.procedural=layers",
                          "particles.count=" + std::to_string(count), "particles.method=grid",
                          "particles.smoothing=" + smoothing, "bricks.per_axis=1"});
  };
  const Box3 centres{glm::dvec3(0.0), glm::dvec3(2.0)};
  Scene round = scene("none"), aniso = scene("anisotropic");
  SessionLayout rl = makeLayout(round, centres, 0, 1), al = makeLayout(aniso, centres, 0, 1);
  MemoryNeed rn = sessionNeed(round, rl, count, 0, false);
  MemoryNeed an = sessionNeed(aniso, al, count, 0, false);

  // One brick on one rank holds every particle. Per particle: two copies of its kernel (all,
  // then the kept ones), its reach and centre, its three vec4 rows on the host and on the GPU,
  // and the neighbour search's index and cell number.
  const double kernel_bytes = 2.0 * sizeof(ParticleKernel) + sizeof(float) + sizeof(glm::vec3) +
                              2.0 * 3.0 * sizeof(glm::vec4) + 2.0 * sizeof(uint32_t);
  EXPECT_DOUBLE_EQ(partBytes(an, "anisotropic kernels"), double(count) * kernel_bytes);
  EXPECT_EQ(partBytes(rn, "anisotropic kernels"), 0.0);

  // Cells of edge h/2 within the reach of a centre uniform in one cell, averaged over 4000.
  const double h = aniso.particles.influenceRadius(), cell = 0.5 * h;
  auto meanCells = [&](double reach) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, cell);
    const int n = int(std::ceil(reach / cell)) + 1;
    double sum = 0;
    for (int trial = 0; trial < 4000; ++trial) {
      const glm::dvec3 c(u(rng), u(rng), u(rng));
      for (int z = -n; z <= n; ++z)
        for (int y = -n; y <= n; ++y)
          for (int x = -n; x <= n; ++x) {
            const glm::dvec3 lo = glm::dvec3(x, y, z) * cell;
            const glm::dvec3 q = glm::clamp(c, lo, lo + cell);  // nearest point of the cell
            sum += glm::length(q - c) <= reach ? 1.0 : 0.0;
          }
    }
    return sum / 4000.0;
  };
  // An entry: its index while building, its centre staged and in the storage buffer (vec4 each).
  const double entry_bytes = sizeof(uint32_t) + 2.0 * sizeof(glm::vec4);
  const double round_lists = double(count) * meanCells(h) * entry_bytes;
  const double aniso_lists = double(count) * meanCells(aniso.particles.reach()) * entry_bytes;
  // The part also holds the cells' offsets (8 bytes a cell, here under 1 %), and the Monte
  // Carlo mean is within 0.5 %.
  EXPECT_NEAR(partBytes(rn, "metaball grids"), round_lists, 0.015 * round_lists);
  EXPECT_NEAR(partBytes(an, "metaball grids"), aniso_lists, 0.015 * aniso_lists);
  EXPECT_GT(aniso_lists, 8.0 * round_lists);  // the reach bound is 2.6 h
}

}  // namespace
}  // namespace sortlast
