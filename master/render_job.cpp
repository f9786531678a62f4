// The frame loop, read top-down: scene -> bricks -> load -> GL -> for each frame: order, render,
// encode, composite, write.
#include "master/render_job.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/brick.h"
#include "common/decomposition.h"
#include "common/scene.h"
#include "compositing/compositor.h"
#include "compositing/rle.h"
#include "compositing/visibility.h"
#include "master/collective.h"
#include "master/frame_stats.h"
#include "master/progress.h"
#include "master/volume_loading.h"
#include "worker/gl_context.h"
#include "worker/slicing_renderer.h"

namespace sortlast {

std::string frameFileName(const std::string& out, int frame, int frames) {
  if (frames <= 1) return out;
  std::filesystem::path p(out);
  char num[16];
  std::snprintf(num, sizeof num, "_%04d", frame);
  return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

namespace {

// The camera must be outside the volume: slicing draws planes in front of the eye only, and the
// paper's method has no notion of a viewer inside the data.
void checkCameras(const std::vector<Camera>& cams, const GridGeometry& grid) {
  Box3 box = grid.worldBox();
  for (size_t i = 0; i < cams.size(); ++i) {
    const glm::dvec3& p = cams[i].position;
    if (box.contains(p)) {
      char msg[512];
      std::snprintf(msg, sizeof msg,
                    "camera.position (%g, %g, %g)%s is inside the volume, whose box is "
                    "[%g, %g] x [%g, %g] x [%g, %g]; move the camera outside it",
                    p.x, p.y, p.z, cams.size() > 1 ? (" of orbit frame " + std::to_string(i)).c_str() : "",
                    box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
      throw InputError(msg);
    }
  }
}

// Near and far planes enclosing the whole volume, shared by every brick of a frame so that all
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

std::array<std::vector<double>, 3> brickPlanes(const std::vector<Brick>& bricks, int d) {
  std::array<std::vector<double>, 3> planes;
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < d; ++i) {
      glm::ivec3 cell(0);
      cell[a] = i;
      planes[a].push_back(bricks[cell.x + d * (cell.y + d * cell.z)].world.lo[a]);
    }
    planes[a].push_back(bricks.back().world.hi[a]);
  }
  return planes;
}

// Fault injection for the tests: a rank that throws (the others must stop cleanly) or dies (mpirun
// must end the job). Inert unless the variables are set.
void injectTestFault(int rank) {
  auto is_me = [&](const char* var) { const char* v = std::getenv(var); return v && std::atoi(v) == rank; };
  if (is_me("SORTLAST_TEST_FAIL_RANK")) throw std::runtime_error("injected failure (SORTLAST_TEST_FAIL_RANK)");
  if (is_me("SORTLAST_TEST_CRASH_RANK")) std::abort();
}

}  // namespace

int runRenderJob(const RenderOptions& opts, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  try {
    // Scene, decomposition and cameras: every rank parses the same input, so they agree.
    Scene scene;
    std::vector<Brick> bricks;
    Assignment assignment;
    std::vector<Camera> cameras;
    collectively(comm, [&] {
      scene = loadScene(opts.scene, opts.overrides);
      validateVolume(scene.volume);
      bricks = makeBricks(scene.volume.grid, scene.bricks_per_axis);
      assignment = assignBricks(scene.bricks_per_axis, size);
      cameras = scene.frameCameras();
      checkCameras(cameras, scene.volume.grid);
    });
    const std::vector<int> mine = assignment.bricksOf(rank);

    // Each rank reads its own bricks only.
    auto samples = loadOwnBricks(scene.volume, bricks, mine, assignment, comm);
    auto [data_min, data_max] = globalRange(samples, comm);
    TransferFunction tf;
    collectively(comm, [&] {
      tf = scene.transfer.build(data_min, data_max, scene.volume.grid.minSpacing());
    });

    std::unique_ptr<GlContext> ctx;
    std::unique_ptr<SlicingRenderer> renderer;
    std::vector<int> handles;
    collectively(comm, [&] {
      ctx = createGlContext(scene.backend);
      renderer = std::make_unique<SlicingRenderer>(*ctx, scene.camera.width, scene.camera.height,
                                                   scene.block_cells);
      renderer->setTransferFunction(tf, scene.transfer.table_size);
      for (size_t i = 0; i < mine.size(); ++i) {
        handles.push_back(renderer->addBrick(bricks[mine[i]], scene.volume.grid, samples[i]));
        std::vector<float>().swap(samples[i]);  // the texture holds the data now
      }
    });
    if (rank == 0 && !opts.quiet)
      std::fprintf(stderr, "sortlast: %d rank(s), %d^3 bricks, %dx%d, %zu frame(s), %s\n", size,
                   scene.bricks_per_axis, scene.camera.width, scene.camera.height, cameras.size(),
                   ctx->description().c_str());

    auto compositor = makeCompositor(scene.strategy);
    auto planes = brickPlanes(bricks, scene.bricks_per_axis);
    nlohmann::json stats_json = nlohmann::json::array();
    Progress progress(int(cameras.size()), opts.quiet);
    for (int f = 0; f < int(cameras.size()); ++f) {
      const Camera& cam = cameras[f];
      double t_frame = MPI_Wtime();
      auto [near_plane, far_plane] = depthRange(cam, scene.volume.grid.worldBox());
      RankFrameStats st;
      std::vector<BrickImage> images;
      collectively(comm, [&] {
        injectTestFault(rank);
        for (size_t i = 0; i < mine.size(); ++i) {
          double t0 = MPI_Wtime();
          RenderedBrick rb = renderer->render(handles[i], cam, scene.sampleSpacingWorld(),
                                              near_plane, far_plane);
          double t1 = MPI_Wtime();
          BrickImage img{mine[i], rb.rect, {}};
          if (!rb.rect.empty()) rleEncode(rb.pixels.px, img.rle);
          st.render_s += t1 - t0;
          st.encode_s += MPI_Wtime() - t1;
          st.bytes_raw += double(rb.rect.area()) * 4;
          st.bytes_rle += double(img.rle.size());
          (rb.rect.empty() ? st.bricks_skipped : st.bricks_rendered) += 1;
          images.push_back(std::move(img));
        }
      });
      CompositeStats cs;
      ImageRGBA8 frame;
      collectively(comm, [&] {
        frame = compositor->composite(std::move(images), backToFrontOrder(planes, cam.position),
                                      cam.width, cam.height, comm, cs);
        if (rank == 0) writeImage(frameFileName(opts.output, f, int(cameras.size())), frame, scene.background);
      });
      st.transfer_s = cs.transfer_s;
      st.peak_rss_mb = peakRssMiB();
      auto all = gatherStats(st, comm);
      if (rank == 0) {
        stats_json.push_back(frameJson(f, all, cs.composite_s, MPI_Wtime() - t_frame));
        progress.frameDone(f);
      }
    }
    if (rank == 0 && !opts.stats.empty()) {
      std::ofstream out(opts.stats);
      out << nlohmann::json{{"ranks", size},
                            {"bricks_per_axis", scene.bricks_per_axis},
                            {"width", scene.camera.width},
                            {"height", scene.camera.height},
                            {"renderer", ctx->description()},
                            {"frames", stats_json}}
                 .dump(1)
          << "\n";
      if (!out) std::fprintf(stderr, "sortlast: warning: could not write stats to %s\n", opts.stats.c_str());
    }
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
