#include "session/memory_budget.h"

#include "render/volume/field_bricks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/anisotropic_kernels.h"
#include "common/error.h"
#include "session/cgroup_memory.h"
#include "session/device_report.h"  // nodePlace
#include "render/particles/metaball_slices.h"  // kSliceVoxelCells, kSliceSlotPoints

namespace sortlast {

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string mib(double bytes) {
  char b[48];
  std::snprintf(b, sizeof b, "%.0f MiB", std::ceil(bytes / kMiB));
  return b;
}

// MemAvailable from /proc/meminfo, bytes; 0 where it cannot be read.
double memAvailable() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return 0.0;
}

// Bytes of one particle's centre (glm::vec3).
constexpr double kParticle = 12.0;
// Bytes of one grid list entry: its index on the host while building (4), the centre with it as
// the shader reads it, on the host (16) and in the storage buffer (16)
// (render/particles/metaball_grid_renderer.cpp); and of one cell's offset, on the host and the GPU.
constexpr double kGridEntryBytes = 4.0 + 16.0 + 16.0, kGridCellBytes = 4.0 + 4.0;
// Bytes per particle of anisotropic smoothing (render/particles/metaball_grid_renderer.cpp): every kernel
// of the brick's particles and ghosts, then the kept ones again with their reach and centres,
// their three vec4 rows staged on the host and in a storage buffer (the GPU), and the neighbour
// search's cell lists (io/anisotropic_kernels.cpp: an index and a cell number a particle).
constexpr double kAnisotropicBytes =
    2.0 * sizeof(ParticleKernel) + 4.0 + kParticle + 2.0 * 3.0 * 16.0 + 8.0;

// How many cells of edge `cell` a ball of `radius` touches on average: the volume of the cube
// grown by the radius, in cells (a metaball grid's list entries per particle).
double ballCellsTouched(double radius, double cell) {
  const double pi = 3.14159265358979323846, x = radius / cell;
  return 1.0 + 6.0 * x + 3.0 * pi * x * x + 4.0 / 3.0 * pi * x * x * x;
}

}  // namespace

double MemoryNeed::total() const {
  double t = 0;
  for (const MemoryPart& p : parts) t += p.bytes;
  return t;
}

void MemoryNeed::add(std::string what, double bytes, double gpu_bytes) {
  if (bytes > 0) parts.push_back({std::move(what), bytes, gpu_bytes});
}

MemoryNeed MemoryNeed::onGpu() const {
  MemoryNeed n;
  for (const MemoryPart& p : parts)
    if (p.gpu_bytes > 0) n.parts.push_back({p.what, p.gpu_bytes, p.gpu_bytes});
  return n;
}

MemoryBudget gpuMemoryBudget(const GlDeviceInfo& gpu, int sharing) {
  MemoryBudget b;
  if (!(gpu.gpu_free_mib >= 0)) {
    b.bytes = INFINITY;
    b.source = "unknown (the driver reports no GPU memory)";
    b.bound = "unknown";
    return b;
  }
  sharing = std::max(sharing, 1);
  b.bytes = kMemorySafety * gpu.gpu_free_mib * kMiB / sharing;
  std::ostringstream s;
  s << mib(b.bytes) << " of GPU memory (90% of the " << mib(gpu.gpu_free_mib * kMiB) << " free on "
    << gpu.renderer << ", EGL device " << gpu.device << " of host " << gpu.host << ", by "
    << gpu.gpu_memory_source << ", shared by " << sharing << " rank(s) on that GPU)";
  b.source = s.str();
  b.bound = "gpu";
  return b;
}

MemoryBudget memoryBudget(const Scene& scene, MPI_Comm comm) {
  const int on_node = nodePlace(comm).size;
  MemoryBudget b;
  if (scene.limits.memory_mib) {
    b.bytes = *scene.limits.memory_mib * kMiB;
    b.source = mib(b.bytes) + " (limits.memory_mib)";
    b.bound = "limits.memory_mib";
    return b;
  }
  const double avail = memAvailable();
  const std::optional<CgroupLimit> cgroup = processCgroupMemoryLimit();
  std::ostringstream s;
  if (cgroup && !(cgroup->bytes >= avail)) {
    // The job's limit on this node: past it the kernel kills a rank, whatever the node has free.
    b.bytes = kMemorySafety * cgroup->bytes / on_node;
    b.bound = "cgroup";
    s << mib(b.bytes) << " (90% of the cgroup memory limit " << mib(cgroup->bytes) << ", "
      << cgroup->file << ", shared by " << on_node << " rank(s) on this node";
    if (avail > 0) s << "; MemAvailable is " << mib(avail);
    s << "; limits.memory_mib sets it)";
  } else if (avail > 0) {
    b.bytes = kMemorySafety * avail / on_node;
    b.bound = "MemAvailable";
    s << mib(b.bytes) << " (90% of MemAvailable " << mib(avail) << " shared by " << on_node
      << " rank(s) on this node";
    if (cgroup) s << "; the cgroup's limit " << mib(cgroup->bytes) << " is larger";
    s << "; limits.memory_mib sets it)";
  } else {  // no /proc/meminfo and no cgroup limit: no bound we could state
    b.bytes = INFINITY;
    b.bound = "unknown";
    s << "unknown (no MemAvailable in /proc/meminfo, no cgroup memory limit; set limits.memory_mib)";
  }
  b.source = s.str();
  return b;
}

MemoryNeed particleSetNeed(const Scene& scene, int ranks) {
  MemoryNeed n;
  const ParticleDesc& p = scene.particles;
  if (!p.enabled()) return n;
  double count = 0;
  if (p.file.empty()) {
    count = double(p.count < 0 ? 4096 : p.count);
  } else {
    std::error_code ec;
    double size = double(std::filesystem::file_size(p.file, ec));
    if (ec) return n;  // the loader names a missing file
    // Raw and VTK hold at least 12 bytes a particle; CSV text at least 6 ("0,0,0\n").
    bool csv = p.format == "csv" ||
               (p.format == "auto" && std::filesystem::path(p.file).extension() == ".csv");
    count = size / (csv ? 6.0 : 12.0);
  }
  // The set, and the copy scattering builds of it; where every rank reads a share, its share.
  if (ranks > 1 && readsInShares(p)) {
    const double share = std::ceil(count / ranks);
    n.add("this rank's share of the particle set (" + std::to_string((long long)share) + " of at most " +
              std::to_string((long long)count) + " particles, with its exchange copy)",
          2.0 * share * kParticle);
    return n;
  }
  n.add("the particle set on rank 0 (" + std::to_string((long long)count) +
            " particles, with its scatter copy)",
        2.0 * count * kParticle);
  return n;
}

MemoryNeed imageNeed(const Scene& scene, int width, int height, int rank, int bricks_here,
                     int bricks_all) {
  MemoryNeed n;
  const double px = double(width) * double(height);
  // Per brick frame: the float target (RGBA32F), its read-back, the RGBA8 pixels and their RLE
  // code (at most the pixels' size).
  n.add("image targets (" + std::to_string(width) + " x " + std::to_string(height) + ")",
        px * (16 + 16 + 4 + 4), px * 16);
  if (scene.particles.enabled())  // metaball state, hit, potential, colour and surface images
    n.add("metaball image targets", px * (scene.particles.method == ParticleMethod::kGrid ? 16 : 6 * 16 + 4),
          px * (scene.particles.method == ParticleMethod::kGrid ? 16 : 6 * 16 + 4));
  // Glow scenes: the glow pass's own RGBA32F target and its float read-back.
  if (scene.glow.enabled()) n.add("glow image targets", px * (16 + 16), px * 16);
  // Compositing: the brick images this rank holds, a float frame, and on rank 0 the brick images
  // received and the final frame in RGBA8 and float. A brick image covers only its brick's screen
  // rectangle, and a ray crosses at most about 2 d of the d^3 bricks, so the images held sum to
  // at most about 2 d frames (RLE no larger): 4 bytes a pixel in RGBA8, 8 in the half-float
  // Emission format of glow scenes (docs/glow.md).
  const int d = scene.bricks.per_axis;
  const double image_px = scene.glow.enabled() ? 8.0 : 4.0;
  double comp = px * (image_px * std::min(bricks_here, 2 * d) + 16.0);
  if (rank == 0) comp += px * (image_px * std::min(bricks_all, 2 * d) + 16 + 16 + 4);
  n.add("compositing buffers", comp);
  return n;
}

MemoryNeed sessionNeed(const Scene& scene, const SessionLayout& layout, long long particles,
                       int rank, bool resident) {
  MemoryNeed n;
  const int d = scene.bricks.per_axis, bricks_all = d * d * d;
  double step_host = 0;
  if (scene.hasFields()) {
    // Several fields: each one's parts of this rank's bricks (session/fields_loading.h), on the
    // host and as textures.
    for (const FieldSpec& f : scene.fields) {
      double samples = 0, largest = 0;
      for (int id : layout.mine) {
        bool present = false;
        const IndexBox box = fieldBoxOf(f.volume.grid, layout.volume_bricks[size_t(id)].world, present);
        const double c = present ? double(box.count()) : 0.0;
        samples += c;
        largest = std::max(largest, c);
      }
      char what[200];
      std::snprintf(what, sizeof what, "%s: its parts of the bricks with ghosts (%d brick(s), %.3g samples, float)",
                    f.name.c_str(), int(layout.mine.size()), samples);
      n.add(what, 4.0 * samples);
      n.add(f.name + ": its 3D textures (R32F)", 4.0 * samples, 4.0 * samples);
      if (!f.volume.isProcedural()) n.add(f.name + ": one brick's file data while it is read", 8.0 * largest);
      step_host += 4.0 * samples;
    }
  } else if (scene.hasVolume()) {
    double samples = 0, largest = 0;
    for (int id : layout.mine) {
      double c = double(layout.volume_bricks[size_t(id)].stored.count());
      samples += c;
      largest = std::max(largest, c);
    }
    char what[160];
    std::snprintf(what, sizeof what,
                  "bricks' samples with ghosts (%d brick(s), %.3g samples, float)",
                  int(layout.mine.size()), samples);
    n.add(what, 4.0 * samples);
    n.add("the bricks' 3D textures (R32F)", 4.0 * samples, 4.0 * samples);
    if (scene.volume.readsWhole()) {
      // Legacy .vtk: rank 0 reads the whole image (VTK's array of the file's type, then a float
      // copy) and keeps each brick it sends until the sends complete.
      if (rank == 0)
        n.add("the whole legacy .vtk volume on rank 0 (read and scattered)",
              double(scene.volume.grid.sampleCount()) * (8.0 + 4.0 + 4.0));
    } else if (!scene.volume.isProcedural()) {
      n.add("one brick's file data while it is read", 8.0 * largest);
    }
    step_host += 4.0 * samples;
  }
  if (scene.particles.enabled() && particles > 0) {
    // A rank's share of the particles with ghosts: its bricks' fraction of the scene, grown by
    // the ghost margin h on every side (at most all of them).
    // (Anisotropic smoothing: h here is the longer reach, and the ghosts reach h_n further.)
    glm::dvec3 e = layout.bounds.extent();
    double side = std::max({e.x, e.y, e.z}) / d, h = layout.particle_h;
    const bool anisotropic = scene.particles.anisotropicOn();
    const double ghosts = anisotropic ? scene.particles.ghostMargin() : h;
    double grow = side > 0 ? std::pow((side + 2 * ghosts) / side, 3.0) : 1.0;
    double held = std::min(double(particles),
                           double(particles) * double(layout.mine.size()) / bricks_all * grow);
    n.add(
        "this rank's particles with ghosts (" + std::to_string((long long)held) + ", host and GPU)",
        2.0 * held * kParticle, held * kParticle);
    const int ranks = int(layout.assignment.region.size());
    if (readsInShares(scene.particles) && ranks > 1)
      n.add("this rank's share of the particle set", std::ceil(double(particles) / ranks) * kParticle);
    else if (rank == 0)
      n.add("the particle set on rank 0", double(particles) * kParticle);
    if (scene.particles.method == ParticleMethod::kGrid) {
      // Cells of edge h/2 (the influence radius) over a brick grown by the reach, at most 2^24;
      // each particle listed in every cell its ball of the reach touches (round: 84 cells;
      // anisotropic, by the reach bound: about 10 times as many, each with a 4-byte index on the
      // GPU for its kernel).
      const double cell = 0.5 * scene.particles.influenceRadius();
      double cells = 0;
      for (size_t i = 0; i < layout.mine.size(); ++i)
        cells += std::min(std::pow((side + 2 * h) / cell, 3.0), double(1 << 24));
      n.add("metaball grids (host and GPU)",
            held * ballCellsTouched(h, cell) * kGridEntryBytes + cells * kGridCellBytes,
            held * ballCellsTouched(h, cell) * (anisotropic ? 20.0 : 16.0) + cells * 4.0);
    }
    // The grid and the slices methods alike (the slices' GPU copy lives only during the splat).
    if (anisotropic)
      n.add("anisotropic kernels (host and GPU)", held * kAnisotropicBytes, held * 3.0 * 16.0);
    if (scene.particles.method == ParticleMethod::kSlices) {
      // A particle's ball (radius h) meets on average (e^3 + 6 e^2 h + 3 pi e h^2 + 4/3 pi h^3) / e^3
      // voxels of edge e (the volume of the cube grown by h; measured 20.6 list entries per
      // particle at e = h). Slots: at most one per voxel of a brick grown by the ghost margin,
      // and at most one per list entry. Lists: 4 + 16 bytes an entry on the host, 16 on the GPU.
      const double pi = 3.14159265358979, margin = scene.particles.ghostMargin();
      const double e = scene.particles.slice_spacing * h * kSliceVoxelCells;
      const double entries = held * (1 + 6 * h / e + 3 * pi * std::pow(h / e, 2) + 4.0 / 3.0 * pi * std::pow(h / e, 3));
      double voxels = 0;
      for (size_t i = 0; i < layout.mine.size(); ++i) voxels += std::pow((side + 2 * margin) / e + 1, 3.0);
      const double slots = std::min(voxels, entries);
      n.add("metaball slices: samples (GPU), voxel slots and lists (host and GPU)",
            4.0 * kSliceSlotPoints * slots + 8.0 * voxels + 36.0 * entries,
            4.0 * kSliceSlotPoints * slots + 4.0 * voxels + 16.0 * entries);
    }
    step_host += held * kParticle;
  }
  MemoryNeed img = imageNeed(scene, scene.camera.width, scene.camera.height, rank,
                             int(layout.mine.size()), bricks_all);
  n.parts.insert(n.parts.end(), img.parts.begin(), img.parts.end());
  // A resident session keeps other steps' host copies too, up to time.cache_mib.
  if (resident && scene.time.steps > 1)
    n.add("the step cache (time.cache_mib)",
          std::min(scene.time.cache_mib * kMiB, step_host * (scene.time.steps - 1)));
  return n;
}

void checkMemory(const MemoryNeed& need, const MemoryBudget& budget, int rank,
                 const std::string& what) {
  const double total = need.total();
  if (!(total > budget.bytes)) return;
  std::vector<MemoryPart> parts = need.parts;
  std::sort(parts.begin(), parts.end(),
            [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  std::string largest;
  for (size_t i = 0; i < parts.size() && i < 3; ++i)
    largest += (i ? ", " : "") + parts[i].what + " " + mib(parts[i].bytes);
  throw InputError(
      what + " needs about " + mib(total) + " on rank " + std::to_string(rank) +
      " (largest: " + largest + "), but " + budget.source +
      " is available: use fewer or smaller samples, particles or image, or more ranks");
}

}  // namespace sortlast
