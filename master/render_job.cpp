// The frame loop, read top-down: scene -> brick grid -> load (particles, volume) -> GL -> for each
// frame: render each brick, encode, composite in visibility order, write.
#include "master/render_job.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <tuple>

#include "common/brick.h"
#include "common/brick_planes.h"
#include "common/decomposition.h"
#include "common/scene.h"
#include "compositing/compositor.h"
#include "compositing/rle.h"
#include "compositing/visibility.h"
#include "master/adaptive_loading.h"
#include "master/brick_renderer.h"
#include "master/collective.h"
#include "master/compare.h"
#include "master/frame_reference.h"
#include "master/frame_stats.h"
#include "master/progress.h"
#include "master/particle_loading.h"
#include "master/surface_gather.h"
#include "master/volume_loading.h"

namespace sortlast {

std::string frameFileName(const std::string& out, int frame, int frames) {
  if (frames <= 1) return out;
  std::filesystem::path p(out);
  char num[16];
  std::snprintf(num, sizeof num, "_%04d", frame);
  return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

std::vector<Camera> firstFrames(std::vector<Camera> cameras, int max_frames) {
  if (max_frames > 0 && cameras.size() > size_t(max_frames)) cameras.resize(size_t(max_frames));
  return cameras;
}

namespace {

// The camera must be outside the scene's box: slicing draws planes in front of the eye only, the
// metaball billboards must lie in front of it, and neither method has a notion of a viewer inside
// the data.
void checkCameras(const std::vector<Camera>& cams, const Box3& box) {
  for (size_t i = 0; i < cams.size(); ++i) {
    const glm::dvec3& p = cams[i].position;
    if (box.contains(p)) {
      char msg[512];
      std::snprintf(msg, sizeof msg,
                    "camera.position (%g, %g, %g)%s is inside the scene, whose box (the volume, "
                    "and the particles grown by their influence radius) is "
                    "[%g, %g] x [%g, %g] x [%g, %g]; move the camera outside it",
                    p.x, p.y, p.z, cams.size() > 1 ? (" of orbit frame " + std::to_string(i)).c_str() : "",
                    box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
      throw InputError(msg);
    }
  }
}

// Near and far planes enclosing the whole scene, shared by every brick of a frame so that all
// bricks rasterise with the same transform.
std::pair<double, double> depthRange(const Camera& cam, const Box3& box) {
  double tmin = 1e300, tmax = -1e300;
  for (int c = 0; c < 8; ++c) {
    double t = glm::dot(cam.forward(), box.corner(c) - cam.position);
    tmin = std::min(tmin, t);
    tmax = std::max(tmax, t);
  }
  double extent = glm::length(box.extent());
  double near_plane = std::max(tmin * 0.5, 1e-4 * extent);
  return {near_plane, std::max(tmax * 1.01, near_plane * 2.0)};
}

Box3 grow(const Box3& b, double by) { return {b.lo - by, b.hi + by}; }
Box3 unite(const Box3& a, const Box3& b) { return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }
bool isEmpty(const Box3& b) { return b.lo.x > b.hi.x; }

// Fault injection for the tests: a rank that throws (the others must stop cleanly) or dies (mpirun
// must end the job), before its first brick, or after its first brick's image has gone to the
// compositor (direct send has then started sending it). Inert unless the variables are set.
bool isTestFaultRank(const char* var, int rank) {
  const char* v = std::getenv(var);
  return v && std::atoi(v) == rank;
}

void injectTestFault(int rank) {
  if (isTestFaultRank("SORTLAST_TEST_FAIL_RANK", rank))
    throw std::runtime_error("injected failure (SORTLAST_TEST_FAIL_RANK)");
  if (isTestFaultRank("SORTLAST_TEST_CRASH_RANK", rank)) std::abort();
}

void injectLateTestFault(int rank) {
  if (isTestFaultRank("SORTLAST_TEST_FAIL_RANK_AFTER_BRICK", rank))
    throw std::runtime_error("injected failure after a brick (SORTLAST_TEST_FAIL_RANK_AFTER_BRICK)");
}

// bench_compositing --layers input: the frame size and brick order (order.txt) and each brick's
// packed image (brick_ID.bin).
void dumpOrder(const std::string& dir, const Camera& cam, const VisibilityOrder& order) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir + "/order.txt");
  out << cam.width << " " << cam.height << "\n";
  for (int id : order.bricks) out << id << "\n";
  if (!out) throw InputError("cannot write " + dir + "/order.txt");
}

void dumpLayer(const std::string& dir, const BrickImage& img) {
  std::vector<uint8_t> bytes = packBrickImage(img);
  std::ofstream out(dir + "/brick_" + std::to_string(img.brick_id) + ".bin", std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw InputError("cannot write brick image into " + dir);
}

// The frame's distance from the CPU reference, as `sortlast compare` reports it on the two images
// written over the background: PSNR over RGB and the largest channel difference.
void addAccuracy(nlohmann::json& j, const ImageRGBA8& frame, const FrameReference& reference,
                 const Camera& cam, const glm::dvec3& background) {
  double t0 = MPI_Wtime();
  ImageDifference d = compareImages(opaqueOver(toFloat(frame), background),
                                    opaqueOver(reference.render(cam), background));
  // JSON has no infinity: an image identical to the reference reports null.
  j["psnr_db"] = std::isfinite(d.psnr_db) ? nlohmann::json(d.psnr_db) : nlohmann::json();
  j["max_diff"] = d.max_diff;
  j["reference_s"] = MPI_Wtime() - t0;
}

// What every rank knows about the scene's layout before any data is read.
struct Layout {
  Scene scene;
  std::vector<Brick> volume_bricks;  // empty without a volume
  BrickPlanes planes;                // the brick grid (volume and particles share it)
  Assignment assignment;
  Box3 bounds;                       // the scene's box: cameras frame it and stay outside it
  Box3 particle_domain;              // particle centres grown by h (empty: no particles)
  std::vector<Camera> cameras;
};

}  // namespace

int runRenderJob(const RenderOptions& opts, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  try {
    // Scene and volume geometry: every rank parses the same input, so they agree.
    Layout L;
    bool adaptive_blocks = false;
    collectively(comm, [&] {
      L.scene = loadScene(opts.scene, opts.overrides);
      adaptive_blocks = usesAdaptiveBlocks(L.scene);
      if (L.scene.hasVolume()) {
        validateVolume(L.scene.volume);
        L.volume_bricks = makeBricks(L.scene.volume.grid, L.scene.bricks_per_axis);
      }
    });
    const Scene& scene = L.scene;
    const int d = scene.bricks_per_axis;
    const bool has_particles = scene.particles.enabled();
    const double h = scene.particles.influenceRadius();

    // Particles: rank 0 loads them; their extent shapes the brick grid and the camera.
    RootParticles root;
    if (has_particles) root = loadParticlesOnRoot(scene.particles, comm);
    L.particle_domain = root.total > 0 ? grow(root.bounds, h) : Box3{glm::dvec3(1), glm::dvec3(-1)};
    collectively(comm, [&] {
      if (scene.hasVolume()) {
        L.planes = volumeBrickPlanes(L.volume_bricks, d);
        L.bounds = scene.volume.grid.worldBox();
        if (!isEmpty(L.particle_domain)) {
          L.planes = coverBox(L.planes, L.particle_domain);
          L.bounds = unite(L.bounds, L.particle_domain);
        }
      } else {
        // No volume and no particle at all: an empty (transparent) frame of a unit box.
        L.bounds = isEmpty(L.particle_domain) ? Box3{glm::dvec3(-0.5), glm::dvec3(0.5)} : L.particle_domain;
        L.planes = uniformBrickPlanes(L.bounds, d);
      }
      L.assignment = assignBricks(d, size);
      L.cameras = firstFrames(scene.frameCameras(L.bounds), opts.max_frames);
      checkCameras(L.cameras, L.bounds);
    });
    const std::vector<int> mine = L.assignment.bricksOf(rank);
    auto cellOf = [&](int id) { return glm::ivec3(id % d, (id / d) % d, id / (d * d)); };

    // Each rank gets its region's particles plus ghosts within h, and its own bricks' samples.
    std::vector<glm::vec3> my_particles;
    if (has_particles) {
      std::vector<Box3> regions;
      for (int r = 0; r < size; ++r) regions.push_back(cellRangeBox(L.planes, L.assignment.region[size_t(r)]));
      my_particles = scatterParticles(root, regions, h, comm);
      root.set = {};  // rank 0 keeps only the count
    }
    // Adaptive sampling: every rank reads the whole volume (master/adaptive_loading.h) and keeps
    // its bricks' adaptive blocks instead of their samples.
    std::vector<std::vector<float>> samples;
    AdaptiveRankData adaptive;
    TransferFunction tf;
    if (scene.hasVolume()) {
      double data_min = 0, data_max = 0;
      if (adaptive_blocks) {
        adaptive = loadAdaptiveBricks(scene, L.volume_bricks, mine, comm);
        data_min = adaptive.data_min, data_max = adaptive.data_max;
      } else {
        samples = loadOwnBricks(scene.volume, L.volume_bricks, mine, L.assignment, comm);
        std::tie(data_min, data_max) = globalRange(samples, comm);
      }
      collectively(comm, [&] {
        tf = scene.transfer.build(data_min, data_max, scene.volume.grid.minSpacing());
      });
    }

    std::unique_ptr<BrickRenderer> renderer;
    std::vector<int> handles;
    double particles_held = 0;
    collectively(comm, [&] {
      renderer = std::make_unique<BrickRenderer>(scene.backend, scene.camera.width, scene.camera.height);
      if (scene.hasVolume())
        renderer->enableVolume(tf, scene.transfer.table_size, scene.block_cells, volumeMethod(scene));
      if (has_particles) renderer->enableParticles(metaballSettings(scene.particles));
      for (size_t i = 0; i < mine.size(); ++i) {
        Box3 clip = brickBox(L.planes, cellOf(mine[i]));
        std::vector<glm::vec3> near = has_particles ? particlesNear(my_particles, clip, h) : std::vector<glm::vec3>();
        particles_held += double(near.size());
        const Brick* vb = scene.hasVolume() ? &L.volume_bricks[size_t(mine[i])] : nullptr;
        const bool sampled = vb && !adaptive_blocks;
        handles.push_back(renderer->addBrick(vb, &scene.volume.grid, sampled ? &samples[i] : nullptr, clip,
                                             has_particles ? &near : nullptr,
                                             vb && adaptive_blocks ? &adaptive.bricks[i] : nullptr));
        // The textures hold the data now.
        if (sampled) std::vector<float>().swap(samples[i]);
        if (vb && adaptive_blocks) adaptive.bricks[i] = {};
      }
    });
    if (rank == 0 && !opts.quiet)
      std::fprintf(stderr, "sortlast: %d rank(s), %d^3 bricks, %dx%d, %zu frame(s)%s, %s\n", size, d,
                   scene.camera.width, scene.camera.height, L.cameras.size(),
                   has_particles ? (", " + std::to_string(root.total) + " particles").c_str() : "",
                   renderer->description().c_str());

    // An EXR output holds the frame before rounding; PNG is 8-bit.
    const bool float_output = std::filesystem::path(opts.output).extension() == ".exr";
    CompositeOptions copts;
    copts.precision = scene.precision == "rgba8" ? Precision::RGBA8 : Precision::Float;
    copts.overlap = scene.overlap;
    copts.rle = scene.rle;
    copts.float_frame = float_output;
    auto compositor = makeCompositor(scene.strategy, scene.radix, copts);
    // --psnr: rank 0 holds the whole scene for the CPU reference of every frame.
    std::unique_ptr<FrameReference> reference;
    if (opts.psnr)
      collectively(comm, [&] { if (rank == 0) reference = std::make_unique<FrameReference>(scene, 0); });
    const bool want_surface = has_particles && !opts.surface_out.empty();
    nlohmann::json stats_json = nlohmann::json::array();
    Progress progress(int(L.cameras.size()), opts.quiet);
    for (int f = 0; f < int(L.cameras.size()); ++f) {
      const Camera& cam = L.cameras[f];
      double t_frame = MPI_Wtime();
      // Billboards reach sqrt(3) h beyond a particle: the depth range holds them too.
      auto [near_plane, far_plane] = depthRange(cam, has_particles ? grow(L.bounds, h) : L.bounds);
      RankFrameStats st;
      st.particles_held = particles_held;
      std::vector<SurfacePiece> surfaces;
      const VisibilityOrder order = visibilityOrder(L.assignment, L.planes, cam.position);
      // Each brick image goes to the compositor as soon as it is encoded: direct send starts
      // sending it while the next brick renders.
      compositor->begin(FrameSetup{&order, int(mine.size()), cam.width, cam.height, comm});
      if (f == 0 && !opts.dump_layers.empty())  // rank 0 makes the directory first
        collectively(comm, [&] { if (rank == 0) dumpOrder(opts.dump_layers, cam, order); });
      try {
        collectively(comm, [&] {
          injectTestFault(rank);
          for (size_t i = 0; i < mine.size(); ++i) {
            double t0 = MPI_Wtime();
            BrickFrame bf = renderer->render(handles[i], cam, scene.sampleSpacingWorld(), near_plane,
                                             far_plane, want_surface);
            double t1 = MPI_Wtime();
            BrickImage img{mine[i], bf.rect, {}};
            if (!bf.rect.empty()) rleEncode(bf.pixels.px, img.rle, 4, scene.rle ? kMaxRun : 1);
            st.render_s += t1 - t0;
            st.encode_s += MPI_Wtime() - t1;
            st.bytes_raw += double(bf.rect.area()) * 4;
            st.bytes_rle += double(img.rle.size());
            st.particle_rounds = std::max(st.particle_rounds, double(bf.particle_rounds));
            (bf.rect.empty() ? st.bricks_skipped : st.bricks_rendered) += 1;
            if (f == 0 && !opts.dump_layers.empty()) dumpLayer(opts.dump_layers, img);
            compositor->add(std::move(img));
            if (want_surface) surfaces.push_back({bf.rect, std::move(bf.surface)});
            injectLateTestFault(rank);
          }
        }, [&] { compositor->progress(); });
      } catch (const JobFailed&) {
        compositor->abandon();  // so no rank is left with a send nobody receives
        throw;
      }
      CompositeStats cs;
      ImageRGBA8 frame;
      ImageF frame_f;
      const int frames = int(L.cameras.size());
      collectively(comm, [&] {
        frame = compositor->finish(cs, float_output ? &frame_f : nullptr);
        if (rank == 0) {
          const std::string file = frameFileName(opts.output, f, frames);
          if (float_output)
            writeImage(file, frame_f, scene.background);
          else
            writeImage(file, frame, scene.background);
        }
      });
      if (want_surface) {
        SurfaceImage surface = gatherSurface(surfaces, cam.width, cam.height, comm);
        collectively(comm, [&] {
          if (rank == 0) writeSurfaceImage(frameFileName(opts.surface_out, f, frames), surface);
        });
      }
      st.transfer_s = cs.transfer_s;
      st.bytes_sent = cs.bytes_sent;
      st.peak_rss_mb = peakRssMiB();
      auto all = gatherStats(st, comm);
      if (rank == 0) {
        nlohmann::json j = frameJson(f, all, cs.composite_s, MPI_Wtime() - t_frame);
        // After the frame's time is taken: the reference is a measuring instrument.
        if (reference) addAccuracy(j, frame, *reference, cam, scene.background);
        stats_json.push_back(std::move(j));
        progress.frameDone(f);
      }
    }
    if (rank == 0 && !opts.stats.empty()) {
      std::ofstream out(opts.stats);
      nlohmann::json top{{"ranks", size},
                         {"bricks_per_axis", d},
                         {"width", scene.camera.width},
                         {"height", scene.camera.height},
                         {"renderer", renderer->description()},
                         {"volume_method", scene.hasVolume() ? scene.volume_method : ""},
                         {"compositing", scene.strategy},
                         {"particles", root.total},
                         {"frames", stats_json}};
      if (adaptive_blocks) {
        // Once per job, before the first frame (not in any frame's total_s); slowest rank.
        top["adaptive_tolerance_percent"] = 100.0 * scene.adaptive_tolerance;
        top["adaptive_blocks"] = scene.adaptive_blocks;
        top["adaptive_data_left_percent"] = 100.0 * adaptive.data_left;
        top["adaptive_read_s"] = adaptive.read_s;
        top["adaptive_preprocess_s"] = adaptive.preprocess_s;
        top["adaptive_bricks_s"] = adaptive.bricks_s;
      }
      out << top.dump(1) << "\n";
      if (!out) std::fprintf(stderr, "sortlast: warning: could not write stats to %s\n", opts.stats.c_str());
    }
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
