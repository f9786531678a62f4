// sortlast: a distributed sort-last volume renderer. Parses the command line and hands over to
// the job for the subcommand.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"
#include "scene/scene.h"
#include "app/adaptive_stats_job.h"
#include "app/command_line_hint.h"
#include "session/collective.h"
#include "app/compare.h"
#include "reference/surface_roughness.h"
#include "app/compare_surface.h"
#include "session/mpi_errors.h"
#include "app/reference_job.h"
#include "app/render_job.h"
#include "app/singleton_start.h"
#include "service/serve_job.h"

using namespace sortlast;

namespace {

void addSceneOptions(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("scene", o.scene, "Scene file (YAML); omitted: the built-in default scene");
  cmd->add_option("-o,--output", o.output,
                  "Output image (.png, .jpg (quality 95), .ppm (binary, raw RGB) or .exr (float)); a "
                  "series gets _0000 ...");
  cmd->add_option("--set", o.overrides, "Override a scene key: key.path=value (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("-q,--quiet", o.quiet, "No progress lines");
  cmd->add_option("--frames", o.max_frames, "Only the first N frames of an orbit (0: all)")
      ->check(CLI::NonNegativeNumber);
}

int runCompare(const std::string& a, const std::string& b, int max_diff, long long allow_pixels,
               double min_psnr, const std::string& diff_out, const std::vector<std::string>& masks,
               int mask_radius) {
  try {
    ImageRGBA8 ia = readImageRGBA8(a), ib = readImageRGBA8(b);
    if (!masks.empty()) {
      long long masked = 0;
      std::vector<uint8_t> band(size_t(ia.width) * ia.height, 0);
      for (const std::string& m : masks) {
        std::vector<uint8_t> one = silhouetteBand(readSurfaceImage(m), mask_radius);
        if (one.size() != band.size()) throw InputError("compare: " + m + " is not the images' size");
        for (size_t i = 0; i < band.size(); ++i) band[i] |= one[i];
      }
      masked = maskPixels(ia, ib, band);
      std::printf("silhouette_pixels_left_out=%lld\n", masked);
    }
    ImageDifference d = compareImages(ia, ib);
    std::printf("psnr_db=%.3f max_diff=%d worst_pixel=(%d,%d) mean_abs=%.4f over4=%lld over4_share=%.6f\n",
                d.psnr_db, d.max_diff, d.worst_x, d.worst_y, d.mean_abs, d.over4, d.over4_share);
    if (!diff_out.empty()) writeImage(diff_out, differenceImage(ia, ib, 16), glm::dvec3(0.0));
    bool ok = true;
    if (max_diff >= 0) {
      long long over = countPixelsOver(ia, ib, max_diff);
      std::printf("pixels_over_%d=%lld\n", max_diff, over);
      if (over > allow_pixels) {
        std::printf("FAIL: %lld pixels differ by more than %d (allowed: %lld); worst %d at pixel (%d,%d)\n",
                    over, max_diff, allow_pixels, d.max_diff, d.worst_x, d.worst_y);
        ok = false;
      }
    }
    if (!std::isnan(min_psnr) && d.psnr_db < min_psnr) {
      std::printf("FAIL: psnr %.3f dB < required %.3f dB\n", d.psnr_db, min_psnr);
      ok = false;
    }
    return ok ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 2;
  }
}

// `compare --float`: every stored value in float, within |a - b| <= abs + rel * max(|a|, |b|).
int runCompareFloat(const std::string& a, const std::string& b, double abs_tol, double rel_tol,
                    long long allow_values) {
  try {
    FloatDifference d = compareFloatImages(readImageChannels(a), readImageChannels(b), abs_tol, rel_tol);
    std::printf("max_abs=%.9g max_rel=%.9g worst_value=(%d,%d,%d) values_differing=%lld values_over=%lld\n",
                d.max_abs, d.max_rel, d.worst_x, d.worst_y, d.worst_channel, d.values_differing,
                d.values_over);
    if (d.values_over > allow_values) {
      std::printf("FAIL: %lld values differ by more than %g + %g x |value| (allowed: %lld); worst %.9g at pixel (%d,%d) channel %d\n",
                  d.values_over, abs_tol, rel_tol, allow_values, d.max_abs, d.worst_x, d.worst_y, d.worst_channel);
      return 1;
    }
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 2;
  }
}

int runRoughness(const std::string& path, const RoughnessOptions& options, double max_rms_deg) {
  try {
    Roughness r = surfaceRoughness(readSurfaceImage(path), options);
    std::printf("{\"pairs\": %lld, \"roughness_rms_deg\": %.6g, \"roughness_mean_deg\": %.6g, "
                "\"roughness_p95_deg\": %.6g, \"t_min\": %.9g, \"t_max\": %.9g, \"t_centre\": %.9g, "
                "\"pieces\": %lld}\n",
                r.pairs, r.rms_deg, r.mean_deg, r.p95_deg, r.t_min, r.t_max, r.t_centre, r.pieces);
    if (!std::isnan(max_rms_deg) && !(r.rms_deg <= max_rms_deg)) {
      std::printf("FAIL: roughness %.6g deg RMS > allowed %.6g\n", r.rms_deg, max_rms_deg);
      return 2;
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

struct SurfaceBounds {
  long long max_holes = -1, max_extra = -1;  // -1: not checked
  double max_depth_error = std::nan(""), max_normal_deg = std::nan("");
  double depth_tolerance = INFINITY;
  long long max_depth_outliers = -1;
  bool ignore_edges = false;
  double crease_deg = INFINITY;
  bool ignore_depth_jumps = false;
};

int runCompareSurface(const std::string& ref_path, const std::string& test_path,
                      const SurfaceBounds& b) {
  try {
    SurfaceImage ref = readSurfaceImage(ref_path), test = readSurfaceImage(test_path);
    // Inner silhouettes: where the reference's depth jumps between neighbours (one part of a
    // surface in front of another), either renderer may see either part at the pixel.
    std::vector<uint8_t> band;
    if (b.ignore_depth_jumps) band = silhouetteBand(ref, 1);
    SurfaceDifference d = compareSurfaces(ref, test, b.ignore_edges, b.depth_tolerance, b.crease_deg,
                                          b.ignore_depth_jumps ? &band : nullptr);
    std::printf(
        "{\"pixels_hit_both\": %lld, \"holes\": %lld, \"extra_hits\": %lld, "
        "\"edge_pixels_ignored\": %lld, \"crease_pixels_ignored\": %lld, \"depth_error_max\": %.9g, "
        "\"depth_error_rms\": %.9g, \"normal_error_max_deg\": %.6g, "
        "\"normal_error_mean_deg\": %.6g, \"worst_depth_pixel\": [%d, %d], "
        "\"worst_normal_pixel\": [%d, %d], \"first_hole\": [%d, %d], "
        "\"first_extra\": [%d, %d], \"depth_outliers\": %lld}\n",
        d.both, d.holes, d.extra, d.edges_ignored, d.creases_ignored, d.depth_max, d.depth_rms, d.normal_max_deg,
        d.normal_mean_deg, d.worst_depth_x, d.worst_depth_y, d.worst_normal_x, d.worst_normal_y,
        d.first_hole_x, d.first_hole_y, d.first_extra_x, d.first_extra_y, d.depth_outliers);
    bool ok = true;
    if (b.max_holes >= 0 && d.holes > b.max_holes) {
      std::printf("FAIL: %lld holes (allowed: %lld); first at pixel (%d,%d)\n", d.holes,
                  b.max_holes, d.first_hole_x, d.first_hole_y);
      ok = false;
    }
    if (b.max_extra >= 0 && d.extra > b.max_extra) {
      std::printf("FAIL: %lld extra hits (allowed: %lld); first at pixel (%d,%d)\n", d.extra,
                  b.max_extra, d.first_extra_x, d.first_extra_y);
      ok = false;
    }
    if (!std::isnan(b.max_depth_error) && d.depth_max > b.max_depth_error) {
      std::printf("FAIL: depth error %.9g > allowed %.9g at pixel (%d,%d)\n", d.depth_max,
                  b.max_depth_error, d.worst_depth_x, d.worst_depth_y);
      ok = false;
    }
    if (b.max_depth_outliers >= 0 && d.depth_outliers > b.max_depth_outliers) {
      std::printf("FAIL: %lld pixels with depth error over %.9g (allowed: %lld)\n",
                  d.depth_outliers, b.depth_tolerance, b.max_depth_outliers);
      ok = false;
    }
    if (!std::isnan(b.max_normal_deg) && d.normal_max_deg > b.max_normal_deg) {
      std::printf("FAIL: normal error %.6g deg > allowed %.6g deg at pixel (%d,%d)\n",
                  d.normal_max_deg, b.max_normal_deg, d.worst_normal_x, d.worst_normal_y);
      ok = false;
    }
    return ok ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sortlast: distributed sort-last volume rendering"};
  app.require_subcommand(1);

  RenderOptions render_opts;
  auto* render = app.add_subcommand("render", "Render a scene (run under mpirun -np N)");
  addSceneOptions(render, render_opts);
  render->add_option("--steps", render_opts.steps,
                     "Render a time series, one frame per step in order: all, A:B (A to B, both "
                     "included) or A:B:S (every S-th); frame i takes orbit camera i (mod the orbit's "
                     "frames). transfer.range: auto is the union of the steps' ranges (docs/usage.md)");
  render->add_option("--stats", render_opts.stats, "Write per-frame timings and byte counts as JSON");
  render->add_flag("--psnr", render_opts.psnr,
                   "Also measure each frame against the CPU reference (rank 0 loads the whole "
                   "scene; slow): --stats then holds psnr_db, max_diff and reference_s per frame");
  render->add_flag("--sync-output", render_opts.sync_output,
                   "Encode and write each frame before the next one renders, as before the writer "
                   "thread (for benchmarks comparing the two; the default overlaps them)");
  render->add_option("--dump-layers", render_opts.dump_layers,
                     "Write the first frame's brick images (packed, RLE) and their visibility "
                     "order into this directory, for bench_compositing --layers");
  render->add_option("--surface-out", render_opts.surface_out,
                     "Also write the particle, subdivision and opaque isosurfaces (t, nx, ny, nz per "
                     "pixel) as EXR");

  ServeOptions serve_opts;
  auto* serve = app.add_subcommand(
      "serve", "Keep the scene loaded and render frames on request: HTTP API, WebSocket stream and "
               "web viewer (run under mpirun -np N; see docs/service.md)");
  serve->add_option("scene", serve_opts.scene, "Scene file (YAML); omitted: the built-in default scene");
  serve->add_option("--set", serve_opts.overrides, "Override a scene key: key.path=value (repeatable)")
      ->allow_extra_args(false);
  serve->add_option("--listen", serve_opts.listen,
                    "ADDRESS:PORT to serve on (default 127.0.0.1:8080; port 0: any free port). An "
                    "address other than 127.0.0.1, ::1 or localhost needs --token");
  auto* token_opt = serve->add_option(
      "--token", serve_opts.token,
      "Every /api/ request must carry it (Authorization: Bearer TOKEN, or ?token=TOKEN). Every user "
      "of the node can read it in ps: prefer --token-file");
  serve->add_option("--token-file", serve_opts.token_file,
                    "Read the token from this file (one line; readable by you only, chmod 600), so "
                    "that it is not on the command line")
      ->excludes(token_opt);
  serve->add_option("--data-dir", serve_opts.data_dir,
                    "Clients may load scene files from under this directory (POST /api/load); the "
                    "scene argument is then relative to it");
  serve->add_option("--record-dir", serve_opts.record_dir,
                    "Clients may record the frames the service sends into movie files under this "
                    "directory (POST /api/record); refused without it");
  serve->add_option("--viewer-dir", serve_opts.viewer_dir, "Serve the web viewer from this directory");
  serve->add_option("--max-size", serve_opts.max_image_side, "Largest image side a request may ask for")
      ->check(CLI::Range(1, 32768));
  serve->add_flag("-q,--quiet", serve_opts.quiet, "No start-up lines");

  RenderOptions ref_opts;
  ref_opts.output = "reference.png";
  int threads = 0;
  auto* reference = app.add_subcommand("reference", "Render a scene with the CPU reference integrator");
  addSceneOptions(reference, ref_opts);
  reference->add_option("--threads", threads, "Worker threads (default: all cores)");
  std::string surface_out;
  reference->add_option("--surface-out", surface_out,
                        "Also write the metaball, subdivision and opaque isosurfaces (t, nx, ny, nz) as EXR");

  std::string img_a, img_b, diff_out;
  int max_diff = -1;
  long long allow_pixels = 0;
  double min_psnr = std::nan("");
  auto* compare = app.add_subcommand("compare", "Compare two images (PSNR, largest difference)");
  compare->add_option("a", img_a)->required();
  compare->add_option("b", img_b)->required();
  compare->add_option("--max-diff", max_diff, "Fail if any channel differs by more (1/255 units)");
  compare->add_option("--allow-pixels", allow_pixels, "How many pixels may exceed --max-diff (default 0)");
  compare->add_option("--min-psnr", min_psnr, "Fail if PSNR is lower (dB)");
  compare->add_option("--diff", diff_out, "Write a difference image (x16)");
  bool compare_float = false;
  double abs_tol = 0.0, rel_tol = 0.0;
  compare->add_flag("--float", compare_float,
                    "Compare every stored value in float (EXR frames, surface images); fails on any "
                    "value outside --abs + --rel x |value| (both 0 by default: identical values)");
  compare->add_option("--abs", abs_tol, "--float: absolute tolerance per value")->check(CLI::NonNegativeNumber);
  compare->add_option("--rel", rel_tol, "--float: relative tolerance per value")->check(CLI::NonNegativeNumber);
  long long allow_values = 0;
  compare->add_option("--allow-values", allow_values, "--float: how many values may exceed the tolerance (default 0)")
      ->check(CLI::NonNegativeNumber);
  std::vector<std::string> compare_masks;
  int mask_radius = 2;
  compare->add_option("--mask-silhouettes", compare_masks,
                      "Leave out pixels near the silhouettes of this surface image (.exr; may be given "
                      "more than once)");
  compare->add_option("--mask-radius", mask_radius, "Pixels around a silhouette left out (default 2)");

  std::string surf_ref, surf_test;
  SurfaceBounds surf_bounds;
  auto* compare_surface = app.add_subcommand(
      "compare-surface", "Compare two surface images (EXR t, nx, ny, nz): holes, depth, normals");
  compare_surface->add_option("reference", surf_ref, "Reference surface (.exr)")->required();
  compare_surface->add_option("test", surf_test, "Surface to check (.exr)")->required();
  compare_surface->add_option("--max-holes", surf_bounds.max_holes,
                              "Fail if more pixels hit in the reference are missed");
  compare_surface->add_option("--max-extra", surf_bounds.max_extra,
                              "Fail if more pixels are hit that the reference misses");
  compare_surface->add_option("--max-depth-error", surf_bounds.max_depth_error,
                              "Fail if a depth differs by more (world units)");
  compare_surface->add_option("--max-normal-deg", surf_bounds.max_normal_deg,
                              "Fail if a normal differs by more (degrees)");
  compare_surface->add_option("--depth-tolerance", surf_bounds.depth_tolerance,
                              "Depth errors above this count as outliers (world units)");
  compare_surface->add_option("--max-depth-outliers", surf_bounds.max_depth_outliers,
                              "Fail if more pixels exceed --depth-tolerance");
  compare_surface->add_flag("--ignore-edges", surf_bounds.ignore_edges,
                            "Leave out silhouette pixels (a 4-neighbour differs in the reference)");
  compare_surface->add_flag("--ignore-depth-jumps", surf_bounds.ignore_depth_jumps,
                            "Leave out pixels within 1 of a depth jump over 5 % between reference neighbours "
                            "(inner silhouettes: one part of a surface in front of another)");
  compare_surface->add_option("--ignore-creases", surf_bounds.crease_deg,
                              "Leave out crease pixels: the reference normal turns by more than this many "
                              "degrees to a 4-neighbour's (a pixel on a crease may show either side)");

  std::string rough_in;
  RoughnessOptions rough_opts;
  std::vector<int> rough_region;
  double rough_max = std::nan("");
  auto* roughness = app.add_subcommand(
      "roughness",
      "Surface roughness of a surface image (EXR t, nx, ny, nz): RMS angle between the normals of "
      "neighbouring pixels whose depths are continuous; JSON");
  roughness->add_option("surface", rough_in, "Surface image (.exr), e.g. from --surface-out")->required();
  roughness->add_option("--region", rough_region, "Only pixels x0 y0 x1 y1 ([x0, x1) x [y0, y1), row 0 at the top)")
      ->expected(4);
  roughness->add_option("--max-depth-jump", rough_opts.max_depth_jump,
                        "Neighbours are continuous when their depths differ by at most this times the "
                        "nearer depth (default 0.02)");
  roughness->add_option("--max-rms-deg", rough_max, "Fail (exit 2) if the RMS angle is larger");

  AdaptiveStatsOptions adaptive_opts;
  auto* adaptive_stats = app.add_subcommand(
      "adaptive-stats",
      "Adaptive sampling of the scene's volume (adaptive.tolerance, adaptive.blocks): data left, "
      "preprocessing time, error; JSON");
  adaptive_stats->add_option("scene", adaptive_opts.scene, "Scene file (YAML); omitted: the built-in default scene");
  adaptive_stats->add_option("--set", adaptive_opts.overrides, "Override a scene key: key.path=value (repeatable)")
      ->allow_extra_args(false);
  adaptive_stats->add_option("--threads", adaptive_opts.threads, "Worker threads (default: all cores)");
  adaptive_stats->add_option("--runs", adaptive_opts.runs,
                             "Preprocessing runs timed; the first is cold, the best of the rest is reported (default 5)");

  auto* keys = app.add_subcommand("keys", "Print every scene key with its default (Markdown)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A mistyped subcommand or option: name it and the nearest one (CLI11 would say only "A
    // subcommand is required" or "not expected").
    const std::string hint = e.get_exit_code() == 0 ? "" : commandLineHint(app, argc, argv);
    if (hint.empty()) return app.exit(e);
    std::fprintf(stderr, "sortlast: error: %s\n", hint.c_str());
    return e.get_exit_code();
  }

  if (*keys) {
    std::fputs(sceneKeysMarkdown().c_str(), stdout);
    return 0;
  }
  if (*compare && compare_float) {
    if (max_diff >= 0 || !std::isnan(min_psnr) || !diff_out.empty() || !compare_masks.empty()) {
      std::fprintf(stderr, "sortlast: error: compare --float takes --abs, --rel and --allow-values only\n");
      return 2;
    }
    return runCompareFloat(img_a, img_b, abs_tol, rel_tol, allow_values);
  }
  if (*compare) return runCompare(img_a, img_b, max_diff, allow_pixels, min_psnr, diff_out, compare_masks, mask_radius);
  if (*compare_surface) return runCompareSurface(surf_ref, surf_test, surf_bounds);
  if (*roughness) {
    if (rough_region.size() == 4)
      rough_opts.x0 = rough_region[0], rough_opts.y0 = rough_region[1], rough_opts.x1 = rough_region[2],
      rough_opts.y1 = rough_region[3];
    return runRoughness(rough_in, rough_opts, rough_max);
  }
  if (*reference) return runReferenceJob(ref_opts, threads, surface_out);
  if (*adaptive_stats) return runAdaptiveStatsJob(adaptive_opts);

  // The service's front end runs threads on rank 0, but only the main thread calls MPI.
  int provided = 0;
  isolateSingletonStart();
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  installMpiErrorHandler(MPI_COMM_WORLD);
  int code = 1;
  try {
    if (!*serve) {
      code = runRenderJob(render_opts, MPI_COMM_WORLD);
    } else if constexpr (build::kService) {
      code = runServeJob(serve_opts, MPI_COMM_WORLD);
    } else {  // every rank ends with 1; rank 0 says why
      int rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (rank == 0)
        std::fprintf(stderr, "sortlast: error: %s\n",
                     missingFeatureMessage(Feature::kService, "sortlast serve").c_str());
    }
  } catch (const std::bad_alloc&) {
    // Outside any collective step: the other ranks cannot learn of it, so the job ends here.
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::fprintf(stderr, "sortlast: error: rank %d: %s\n", rank, outOfMemoryMessage().c_str());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return code;
}
