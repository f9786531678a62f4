// `sortlast render`: the simplest client of the resident session. Every rank opens the session on
// the scene, then asks it for each camera of the orbit in turn; rank 0 writes the frames (on its
// writer thread, io/frame_writer.h, while the next frame renders), the stats and (--psnr) their
// distance from the CPU reference.
#include "app/render_job.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "app/frame_output.h"
#include "io/frame_writer.h"
#include "io/movie_writer.h"
#include "scene/scene.h"
#include "scene/surface_output.h"
#include "session/collective.h"
#include "app/compare.h"
#include "reference/frame_reference.h"
#include "app/progress.h"
#include "session/render_session.h"

namespace sortlast {

std::vector<Camera> firstFrames(std::vector<Camera> cameras, int max_frames) {
  if (max_frames > 0 && cameras.size() > size_t(max_frames)) cameras.resize(size_t(max_frames));
  return cameras;
}

namespace {

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

Camera cameraOf(const nlohmann::json& stats, const Camera& fallback) {
  Camera c = fallback;
  auto v = [](const nlohmann::json& a) { return glm::dvec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); };
  const auto& j = stats.at("camera");
  c.position = v(j.at("position"));
  c.look_at = v(j.at("look_at"));
  c.up = v(j.at("up"));
  c.fov_deg = j.at("fov").get<double>();
  if (j.contains("parallel_scale")) {
    c.projection = Projection::kOrthographic;
    c.parallel_scale = j.at("parallel_scale").get<double>();
  } else {
    c.projection = Projection::kPerspective;
  }
  c.width = j.at("width").get<int>();
  c.height = j.at("height").get<int>();
  return c;
}

}  // namespace

int runRenderJob(const RenderOptions& opts, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  try {
    SessionOptions so;
    so.overrides = opts.overrides;
    so.quiet = opts.quiet;
    collectively(comm, [&] {
      if (!isMoviePath(opts.output)) checkOutputFormat(opts.output);
      so.scene = readSceneText(opts.scene);
    });
    RenderSession session(std::move(so), comm);
    const Scene& scene = session.baseScene();
    const int frames = std::min(session.orbitFrames(), opts.max_frames > 0 ? opts.max_frames : 1 << 30);
    // An EXR output holds the frame before rounding; PNG is 8-bit.
    const bool float_output = std::filesystem::path(opts.output).extension() == ".exr";
    // --psnr: rank 0 holds the whole scene for the CPU reference of every frame.
    std::unique_ptr<FrameReference> reference;
    if (opts.psnr)
      collectively(comm, [&] { if (rank == 0) reference = std::make_unique<FrameReference>(scene, 0); });
    // --stats: each frame's object goes to the file as the frame ends, so rank 0 holds none of
    // them (a long orbit's stats would otherwise grow its memory by ~3 KiB a frame, which the soak
    // test would read as a leak). Written to FILE.partial, renamed when the job ends well.
    std::ofstream stats_out;
    const std::string stats_partial = opts.stats + ".partial";
    bool first_frame_stats = true;
    if (rank == 0 && !opts.stats.empty()) {
      stats_out.open(stats_partial);
      stats_out << "{\"frames\": [\n";
    }
    // Frame N is encoded and written while frame N+1 renders. Two frames may wait (the writer
    // holds a third): at 1024² that is 12 MiB of pixels at most, and one frame of slack for a
    // write that takes longer once (a slow disk) before the render waits for it.
    FrameWriter writer(opts.sync_output ? 0 : 2);
    // Image files or a movie (app/frame_output.h), with the legend drawn in on the writer thread.
    std::unique_ptr<FrameOutput> output;
    collectively(comm, [&] {
      if (rank == 0) output = std::make_unique<FrameOutput>(opts.output, scene, frames, writer);
    });
    Progress progress(frames, opts.quiet);
    for (int f = 0; f < frames; ++f) {
      FrameRequest request;
      request.orbit_frame = f;
      request.float_frame = float_output;
      request.surface = !opts.surface_out.empty();
      if (f == 0) request.dump_layers = opts.dump_layers;
      FrameResult result = session.render(request);
      // After the frame's time is taken: the reference is a measuring instrument. Before the
      // hand-off, which takes the frame's pixels.
      if (rank == 0 && reference)
        addAccuracy(result.stats, result.image, *reference, cameraOf(result.stats, scene.camera),
                    scene.image.background);
      // Rank 0 hands the frame to its writer; a write that failed before (this frame's
      // predecessors) is thrown here and so stops every rank.
      collectively(comm, [&] {
        if (rank != 0) return;
        if (float_output)
          output->push(f, std::move(result.image_f));
        else
          output->push(f, std::move(result.image), scene.hasVolume() ? session.transferFunction() : TransferFunction());
        if (request.surface && hasSurfaceImage(scene)) {
          const std::string surface_file = frameFileName(opts.surface_out, f, frames);
          writer.push(surface_file, [surface_file, surface = std::move(result.surface)] {
            writeSurfaceImage(surface_file, surface);
          });
        }
      });
      if (rank == 0) {
        if (stats_out.is_open()) {
          stats_out << (first_frame_stats ? "" : ",\n") << result.stats.dump(1);
          first_frame_stats = false;
        }
        progress.frameDone(f);
      }
    }
    // The last frames are written before the job ends well, and before the stats, which say so.
    collectively(comm, [&] {
      if (rank == 0) {
        output->close();
        writer.finish();
      }
    });
    if (stats_out.is_open()) {
      nlohmann::json top{{"ranks", size},
                         {"bricks_per_axis", scene.bricks.per_axis},
                         {"width", scene.camera.width},
                         {"height", scene.camera.height},
                         {"renderer", session.rendererDescription()},
                         {"volume_method", scene.hasVolume() ? std::string(nameOf(scene.render.method)) : ""},
                         {"compositing", std::string(nameOf(scene.compositing.strategy))},
                         {"particles", session.particleCount()}};
      top.update(session.jobStats());
      const FrameWriter::Stats written = writer.stats();
      top["output"] = {{"mode", opts.sync_output ? "sync" : "writer_thread"},
                       {"files", written.files},
                       {"write_s", written.write_s},
                       {"wait_s", written.wait_s}};
      // The rest of the top-level object after the frames: top's members without its '{'.
      stats_out << "\n],\n" << top.dump(1).substr(1) << "\n";
      stats_out.close();
      std::error_code ec;
      if (stats_out) std::filesystem::rename(stats_partial, opts.stats, ec);
      if (!stats_out || ec)
        std::fprintf(stderr, "sortlast: warning: could not write stats to %s\n", opts.stats.c_str());
    }
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
