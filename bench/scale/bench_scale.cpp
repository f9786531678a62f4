// bench_scale: the compositing strategies at any rank count on synthetic sphere layers
// (scale_layers.h), one brick image per rank. Built twice from this one file: natively with the
// project's MPI (real wall time, for validating the simulation at P = 2-8), and with SimGrid's
// smpicxx (bench/scale/smpi/, -DSORTLAST_SMPI) to run the same strategy code on up to thousands of
// simulated hosts, the compositing kernels charged as simulated computation at measured per-pixel
// rates (--rates; compositing/pixel_cost.h).
//
// Each variant (strategy x precision x RLE) runs --warmup times, then --reps times; rank 0 prints
// one CSV line: the median over reps of the slowest rank's seconds (MPI_Wtime: simulated under
// SMPI), bytes and messages sent by all ranks, the most bytes one rank sent, the pixels decoded
// from received messages, the layers' pixels and how many ranks had something to show.
// Messages and pixels are counted by wrapping MPI_Isend and MPI_Recv (the PMPI interface), per
// rank, since SMPI runs every rank in one process with shared globals.
//
// --check: exit 1 unless every float variant's frame equals the first one's within 1/255 and the
// frame's covered fraction is the requested coverage within 5 % (the ctest of the SMPI build).
//
// Usage: [smpirun ...] bench_scale [--sizes 1024,2048] [--coverage 0.4] [--reps 3] [--warmup 1]
//          [--strategies direct,binary-swap,radix-k:4] [--precisions float,rgba8] [--rle on,off]
//          [--rates RATES.csv] [--platform NAME] [--header] [--check]
//          [--network LATENCY_US,GBIT_PER_S[,RANKS_PER_CORE]] [--ranks-per-core R]
//          [--layers DIR]
// --layers DIR: real brick images instead of spheres, one rendered frame dumped by `sortlast render
// --dump-layers DIR` (bench/layer_dump.h), its brick order dealt to the P ranks as contiguous runs
// (ranks beyond the brick count own nothing); the frame size is the dump's, the coverage column
// the frame's covered fraction, and auto forecasts from the bricks' own rectangles (allgathered
// before the timing).
// Strategy `auto` (compositing.strategy: auto) forecasts from every rank's layer bound
// (scale_layers.h sphereLayerBound, as a renderer forecasts from brick boxes) with the network of
// --network (default 40 us, 10 Gbit/s; scripts/scale_platform.py --print-network gives a platform's) and prints the strategy it chose in the radix column as
// auto:NAME[:k]; stderr gets its forecasts.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "bench/comma_list.h"
#include "bench/layer_dump.h"
#include "compositing/pixel_rates.h"
#include "bench/scale/scale_layers.h"
#include "compositing/compositor.h"
#include "compositing/rect_image.h"
#include "compositing/strategy_model.h"
#ifdef SORTLAST_SMPI
#include "bench/scale/smpi_charge.h"
#include "bench/scale/smpi_probe.h"
#endif

namespace {

// Per-rank counters, indexed by rank in MPI_COMM_WORLD.
constexpr int kMaxRanks = 1 << 16;
bool g_counting[kMaxRanks];
double g_messages[kMaxRanks], g_bytes[kMaxRanks], g_pixels[kMaxRanks];

int worldRank() {
  int r = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

}  // namespace

extern "C" int MPI_Isend(const void* buf, int count, MPI_Datatype type, int dest, int tag,
                         MPI_Comm comm, MPI_Request* req) {
  const int r = worldRank();
  if (g_counting[r]) {
    int sz = 0;
    PMPI_Type_size(type, &sz);
    g_messages[r] += 1;
    g_bytes[r] += double(count) * sz;
  }
  return PMPI_Isend(buf, count, type, dest, tag, comm, req);
}

extern "C" int MPI_Recv(void* buf, int count, MPI_Datatype type, int source, int tag,
                        MPI_Comm comm, MPI_Status* status) {
#ifdef SORTLAST_SMPI
  int rc = MPI_SUCCESS;
  if (!sortlast::scale::receiveProbed(buf, count, type, source, tag, comm, status))
    rc = PMPI_Recv(buf, count, type, source, tag, comm, status);
#else
  int rc = PMPI_Recv(buf, count, type, source, tag, comm, status);
#endif
  const int r = worldRank();
  if (g_counting[r] && type == MPI_BYTE && count >= 24) {
    int32_t head[6];
    std::memcpy(head, buf, sizeof head);
    if (head[3] > 0 && head[4] > 0) g_pixels[r] += double(head[3]) * head[4];
  }
  return rc;
}

namespace {

using namespace sortlast;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

[[noreturn]] void fail(int rank, const std::string& msg) {
  if (rank == 0) std::fprintf(stderr, "bench_scale: %s\n", msg.c_str());
  MPI_Abort(MPI_COMM_WORLD, 2);
  std::abort();
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks > kMaxRanks) fail(rank, "at most " + std::to_string(kMaxRanks) + " ranks");
  std::vector<std::string> sizes = {"1024"}, strategies = {"direct", "binary-swap", "radix-k:4"};
  std::vector<std::string> precisions = {"float"}, rles = {"on"};
  std::string rates_file, platform = "native", layers_dir;
  double coverage = 0.4, latency_us = 40, gbps = 10, ranks_per_core = 1;
  int reps = 3, warmup = 1;
  bool header = false, check = false;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) fail(rank, a + " needs a value");
        return argv[++i];
      };
      if (a == "--sizes") sizes = splitCommas(next());
      else if (a == "--coverage") coverage = std::stod(next());
      else if (a == "--strategies") strategies = splitCommas(next());
      else if (a == "--precisions") precisions = splitCommas(next());
      else if (a == "--rle") rles = splitCommas(next());
      else if (a == "--reps") reps = std::max(1, std::stoi(next()));
      else if (a == "--warmup") warmup = std::max(0, std::stoi(next()));
      else if (a == "--rates") rates_file = next();
      else if (a == "--platform") platform = next();
      else if (a == "--ranks-per-core") ranks_per_core = std::stod(next());
      else if (a == "--layers") layers_dir = next();
      else if (a == "--network") {
        const std::vector<std::string> v = splitCommas(next());
        if (v.size() != 2 && v.size() != 3)
          fail(rank, "--network wants LATENCY_US,GBIT_PER_S[,RANKS_PER_CORE]");
        latency_us = std::stod(v[0]), gbps = std::stod(v[1]);
        if (v.size() == 3) ranks_per_core = std::stod(v[2]);
      }
      else if (a == "--header") header = true;
      else if (a == "--check") check = true;
      else fail(rank, "unknown option " + a);
    }
  } catch (const std::exception& e) {
    fail(rank, std::string("bad option value: ") + e.what());
  }
#ifdef SORTLAST_SMPI
  if (rates_file.empty()) fail(rank, "the SMPI build needs --rates FILE (measure_rates writes it)");
  try {
    scale::usePixelRates(readPixelRates(rates_file));
  } catch (const std::exception& e) {
    fail(rank, e.what());
  }
#else
  if (!rates_file.empty()) fail(rank, "--rates is for the SMPI build; this one measures real time");
#endif
  if (rank == 0 && header)
    std::printf("platform,strategy,radix,precision,rle,ranks,width,height,coverage,seconds,"
                "bytes_sent,max_rank_bytes,messages,pixels_composited,layer_pixels,active_ranks\n");

  VisibilityOrder order;
  LayerDump dump;
  if (layers_dir.empty()) {
    order = scale::sphereOrder(ranks);
  } else {
    try {
      dump = readLayerDump(layers_dir);
    } catch (const std::exception& e) {
      fail(rank, e.what());
    }
    sizes = {std::to_string(dump.width)};
    order.bricks = dump.order;
    for (int r = 0; r < ranks; ++r) order.ranks.push_back(r);  // rank r: the r-th run, far to near
  }
  int bad = 0;
  for (const std::string& size : sizes) {
    int w = 0;
    try {
      w = std::stoi(size);
    } catch (const std::exception&) {
    }
    if (w < 1) fail(rank, "bad size '" + size + "'");
    const int h = layers_dir.empty() ? w : dump.height;
    // The raw layers only where a variant needs them: at 4,096 ranks every copy of every rank's
    // layer is in this one process's memory.
    std::vector<BrickImage> layers, layers_raw;
    const bool need_raw = std::find(rles.begin(), rles.end(), "off") != rles.end();
    FrameFootprint footprint;
    try {
      if (layers_dir.empty()) {
        layers = {scale::sphereLayer(rank, ranks, w, w, coverage, true)};
        if (need_raw) layers_raw = {scale::sphereLayer(rank, ranks, w, w, coverage, false)};
        // What auto forecasts from: every rank's bound, computed on every rank (no message).
        for (int r = 0; r < ranks; ++r) {
          footprint.rect.push_back(scale::sphereLayerBound(r, ranks, w, w, coverage));
          footprint.brick_pixels.push_back(double(footprint.rect.back().area()));
          footprint.bricks.push_back(1);
        }
      } else {
        for (size_t i = dump.first(rank, ranks); i < dump.last(rank, ranks); ++i) {
          layers.push_back(readDumpedBrick(layers_dir, dump.order[i]));
          if (need_raw) layers_raw.push_back(withoutRle(layers.back()));
        }
      }
    } catch (const std::exception& e) {
      fail(rank, e.what());
    }
    long long area = 0;
    Rect bound;
    for (const BrickImage& b : layers) area += b.rect.area(), bound = unionOf(bound, b.rect);
    if (!layers_dir.empty()) {
      // Real layers: every rank's rectangle and pixels, gathered once, outside the timing.
      const long long mine6[6] = {bound.x, bound.y, bound.w, bound.h, area, (long long)layers.size()};
      std::vector<long long> every(6 * size_t(ranks));
      MPI_Allgather(mine6, 6, MPI_LONG_LONG, every.data(), 6, MPI_LONG_LONG, MPI_COMM_WORLD);
      for (int r = 0; r < ranks; ++r) {
        const long long* e = &every[6 * size_t(r)];
        footprint.rect.push_back(Rect{int(e[0]), int(e[1]), int(e[2]), int(e[3])});
        footprint.brick_pixels.push_back(double(e[4]));
        footprint.bricks.push_back(int(e[5]));
      }
    }
    double mine[2] = {double(area), area > 0 ? 1.0 : 0.0}, all[2] = {0, 0};
    MPI_Reduce(mine, all, 2, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);

    ImageRGBA8 first_frame;
    double covered_fraction = coverage;  // real layers: the first frame's, on rank 0
    for (const std::string& spec : strategies)
    for (const std::string& precision : precisions)
    for (const std::string& rle : rles) {
      std::string name = spec;
      int radix = 2;
      if (auto c = spec.find(':'); c != std::string::npos) {
        name = spec.substr(0, c);
        radix = std::atoi(spec.substr(c + 1).c_str());
      }
      if (name == "binary-swap") radix = 2;
      if (precision != "float" && precision != "rgba8") fail(rank, "bad precision " + precision);
      if (rle != "on" && rle != "off") fail(rank, "bad --rle value " + rle);
      CompositeOptions opts;
      opts.precision = precision == "rgba8" ? Precision::kRgba8 : Precision::kFloat;
      opts.rle = rle == "on";
      opts.network_latency_s = latency_us * 1e-6;
      opts.network_bandwidth_Bps = gbps * 1e9 / 8;
      opts.ranks_per_core = ranks_per_core;
      std::unique_ptr<Compositor> compositor;
      try {
        compositor = makeCompositor(name, radix, opts);
      } catch (const std::exception& e) {
        fail(rank, e.what());
      }
      std::vector<double> times;
      double counts[3] = {0, 0, 0}, max_bytes = 0;
      for (int i = 0; i < warmup + reps; ++i) {
        // Every rank adds its brick even when it shows nothing (an empty rectangle): direct send's
        // rank 0 counts one image per brick of the order.
        std::vector<BrickImage> mine_images = opts.rle ? layers : layers_raw;
        CompositeStats cs;
        g_messages[rank] = g_bytes[rank] = g_pixels[rank] = 0;
        MPI_Barrier(MPI_COMM_WORLD);
        g_counting[rank] = true;
#ifdef SORTLAST_SMPI
        scale::clearGatherStart(rank);
#endif
        const double t0 = MPI_Wtime();
        ImageRGBA8 frame =
            compositor->composite(std::move(mine_images), order, w, h, MPI_COMM_WORLD, cs, &footprint);
        const double dt = MPI_Wtime() - t0;
        g_counting[rank] = false;
        double slowest = 0;
        MPI_Reduce(&dt, &slowest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
#ifdef SORTLAST_SMPI
        // What the gather adds: the frame's end minus the moment the last rank left the rounds
        // (simulated clocks are one clock, so ranks' marks compare).
        const double mark = scale::gatherStartTime(rank);
        const double rounds_done = mark > 0 ? mark - t0 : 0;
        double last_mark = 0;
        MPI_Reduce(&rounds_done, &last_mark, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
        if (rank == 0 && i >= warmup && last_mark > 0)
          std::fprintf(stderr, "bench_scale: %dx%d %s: gather %.6f s of %.6f s (%.1f %%)\n", w, h,
                       spec.c_str(), slowest - last_mark, slowest,
                       100.0 * (slowest - last_mark) / slowest);
#endif
        double c[3] = {g_messages[rank], g_bytes[rank], g_pixels[rank]};
        MPI_Reduce(c, counts, 3, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        MPI_Reduce(&c[1], &max_bytes, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
        if (i >= warmup) times.push_back(slowest);
        if (rank != 0 || i != 0) continue;
        if (first_frame.px.empty()) {
          first_frame = frame;
          long long covered = 0;
          for (size_t p = 3; p < frame.px.size(); p += 4) covered += frame.px[p] > 0;
          const double f = double(covered) / (double(w) * h);
          std::fprintf(stderr, "bench_scale: %dx%d covered fraction %.4f (asked %.4f)\n", w, h, f,
                       layers_dir.empty() ? coverage : f);
          if (layers_dir.empty() && std::abs(f - coverage) > 0.05 * coverage) ++bad;
          if (!layers_dir.empty()) covered_fraction = f;
        } else {
          int worst = 0;
          for (size_t p = 0; p < frame.px.size() && p < first_frame.px.size(); ++p)
            worst = std::max(worst, std::abs(int(frame.px[p]) - int(first_frame.px[p])));
          if (frame.px.size() != first_frame.px.size()) worst = 255;
          std::fprintf(stderr, "bench_scale: %dx%d %s %s rle-%s: largest difference %d/255\n", w, h,
                       spec.c_str(), precision.c_str(), rle.c_str(), worst);
          if (precision == "float" && worst > 1) ++bad;
        }
      }
      std::string radix_col = name == "direct" ? "" : std::to_string(radix);
      if (const StrategyChoice* c = compositor->choice()) {
        radix_col = "auto:" + c->strategy + (c->radix ? ":" + std::to_string(c->radix) : "");
        if (rank == 0) std::fprintf(stderr, "bench_scale: auto %s: %s\n", c->label.c_str(), c->why.c_str());
      }
      if (rank == 0) {
        std::printf("%s,%s,%s,%s,%s,%d,%d,%d,%.4g,%.6g,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f\n",
                    platform.c_str(), name.c_str(),
                    radix_col.c_str(), precision.c_str(),
                    rle.c_str(), ranks, w, h, covered_fraction, median(times), counts[1], max_bytes,
                    counts[0], counts[2], all[0], all[1]);
        std::fflush(stdout);
      }
    }
  }
  MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  if (check && bad) {
    if (rank == 0) std::fprintf(stderr, "bench_scale: --check failed (%d problems)\n", bad);
    return 1;
  }
  return 0;
}
