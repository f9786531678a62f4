// bench_compositing: the compositing strategies alone, on synthetic layers.
//
// Every rank makes one brick image per frame size: a soft disc of partial opacity (premultiplied,
// alpha falling off toward the rim) at a seeded position, covering about a fifth of the frame,
// with transparent runs around it inside its bounding rectangle; RLE-encoded as render_job does.
// Each strategy is run `--warmup` times, then `--reps` times; rank 0 prints one CSV line per
// (strategy, size): the median over reps of the slowest rank's seconds, the bytes and messages
// sent by all ranks in one composite, the pixels all ranks decoded from received messages, and
// the median seconds of one memcpy of the frame's RGBA8 bytes x ranks on rank 0.
//
// Rank 0 also reports (stderr) the largest difference between each strategy's frame and the first
// strategy's (every strategy should give the same frame within 1/255).
//
// Messages, bytes and pixels are counted by wrapping MPI_Isend and MPI_Recv (the PMPI profiling
// interface), so the compositors are measured unchanged. Every message the strategies send is a
// packed BrickImage (six int32 then RLE bytes), so a received message's w * h are its pixels.
//
// Real layers: `sortlast render --dump-layers DIR` writes one frame's brick images and their
// visibility order; with `--layers DIR` every rank takes a contiguous run of that order (one
// convex group of bricks, as a kd-split gives) instead of a synthetic disc, and the frame size is
// the dump's.
//
// Variants: each strategy runs with float and/or RGBA8 precision and RLE on and/or off
// (compositing.precision / compositing.rle); synthetic layers are re-encoded without RLE for
// "off".
//
// Usage: mpirun -np N bench_compositing [--sizes 512,1024] [--reps 7] [--warmup 2]
//                                       [--strategies direct,binary-swap,radix-k:4]
//                                       [--precisions float,rgba8] [--rle on,off]
//                                       [--layers DIR] [--header]
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench/comma_list.h"
#include "bench/layer_dump.h"
#include "compositing/compositor.h"
#include "compositing/rle.h"

namespace {
bool g_counting = false;
double g_messages = 0, g_bytes = 0, g_pixels = 0;
}  // namespace

extern "C" int MPI_Isend(const void* buf, int count, MPI_Datatype type, int dest, int tag,
                         MPI_Comm comm, MPI_Request* req) {
  if (g_counting) {
    int sz = 0;
    MPI_Type_size(type, &sz);
    g_messages += 1;
    g_bytes += double(count) * sz;
  }
  return PMPI_Isend(buf, count, type, dest, tag, comm, req);
}

extern "C" int MPI_Recv(void* buf, int count, MPI_Datatype type, int source, int tag,
                        MPI_Comm comm, MPI_Status* status) {
  int rc = PMPI_Recv(buf, count, type, source, tag, comm, status);
  if (g_counting && type == MPI_BYTE && count >= 24) {
    int32_t head[6];
    std::memcpy(head, buf, sizeof head);
    if (head[3] > 0 && head[4] > 0) g_pixels += double(head[3]) * head[4];
  }
  return rc;
}

namespace {

using namespace sortlast;

// One rank's layer: a soft disc of radius ~0.25 * min(w, h) (about a fifth of the frame), seeded
// by rank and size, clipped to the frame.
BrickImage makeLayer(int rank, int w, int h) {
  std::mt19937 rng(uint32_t(12345 + 7919 * rank + w));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r = 0.25 * std::min(w, h) * (0.8 + 0.4 * u(rng));
  const double cx = w * (0.2 + 0.6 * u(rng)), cy = h * (0.2 + 0.6 * u(rng));
  const double peak = 0.3 + 0.5 * u(rng);  // partial opacity at the centre
  const double col[3] = {u(rng), u(rng), u(rng)};
  Rect rect;
  rect.x = std::max(0, int(std::floor(cx - r)));
  rect.y = std::max(0, int(std::floor(cy - r)));
  rect.w = std::min(w, int(std::ceil(cx + r))) - rect.x;
  rect.h = std::min(h, int(std::ceil(cy + r))) - rect.y;
  std::vector<uint8_t> px(size_t(rect.w) * rect.h * 4, 0);
  for (int y = 0; y < rect.h; ++y)
    for (int x = 0; x < rect.w; ++x) {
      double dx = rect.x + x + 0.5 - cx, dy = rect.y + y + 0.5 - cy;
      double d = std::sqrt(dx * dx + dy * dy) / r;
      if (d >= 1.0) continue;
      double a = peak * (1.0 - d * d);
      uint8_t A = uint8_t(std::lround(a * 255));
      if (A == 0) continue;
      uint8_t* p = &px[(size_t(y) * rect.w + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::min<long>(A, std::lround(col[c] * A)));
      p[3] = A;
    }
  BrickImage b{rank, rect, {}};
  rleEncode(px, b.rle);
  return b;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  std::vector<std::string> sizes = {"512", "1024"};
  std::vector<std::string> strategies = {"direct", "binary-swap", "radix-k:4"};
  std::vector<std::string> precisions = {"float"}, rles = {"on"};
  std::string layers_dir;
  int reps = 7, warmup = 2;
  bool header = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        if (rank == 0) std::fprintf(stderr, "bench_compositing: %s needs a value\n", a.c_str());
        MPI_Abort(MPI_COMM_WORLD, 2);
      }
      return argv[++i];
    };
    if (a == "--sizes") sizes = splitCommas(next());
    else if (a == "--strategies") strategies = splitCommas(next());
    else if (a == "--reps") reps = std::max(1, std::stoi(next()));
    else if (a == "--warmup") warmup = std::max(0, std::stoi(next()));
    else if (a == "--precisions") precisions = splitCommas(next());
    else if (a == "--rle") rles = splitCommas(next());
    else if (a == "--layers") layers_dir = next();
    else if (a == "--header") header = true;
    else {
      if (rank == 0) std::fprintf(stderr, "bench_compositing: unknown option %s\n", a.c_str());
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
  }
  if (rank == 0 && header)
    std::printf("strategy,radix,precision,rle,layers,ranks,width,height,seconds,bytes_sent,messages,"
                "pixels_composited,memcpy_s\n");

  // Far to near: a seeded permutation of the ranks (one brick per rank, brick id = rank), or the
  // dump's brick order cut into one contiguous run per rank.
  VisibilityOrder order;
  LayerDump dump;
  std::vector<BrickImage> dumped;  // this rank's run
  if (!layers_dir.empty()) {
    dump = readLayerDump(layers_dir);
    sizes = {std::to_string(dump.width)};
    order.bricks = dump.order;
    for (int r = 0; r < ranks; ++r) order.ranks.push_back(r);
    for (size_t i = dump.first(rank, ranks); i < dump.last(rank, ranks); ++i)
      dumped.push_back(readDumpedBrick(layers_dir, dump.order[i]));
  } else {
    for (int r = 0; r < ranks; ++r) order.ranks.push_back(r);
    std::shuffle(order.ranks.begin(), order.ranks.end(), std::mt19937(42));
    order.bricks = order.ranks;
  }

  for (const std::string& size : sizes) {
    const int w = layers_dir.empty() ? std::stoi(size) : dump.width;
    const int h = layers_dir.empty() ? w : dump.height;
    const std::vector<BrickImage> layer =
        layers_dir.empty() ? std::vector<BrickImage>{makeLayer(rank, w, h)} : dumped;
    std::vector<BrickImage> layer_raw;
    for (const BrickImage& b : layer) layer_raw.push_back(withoutRle(b));

    // memcpy of the frame's RGBA8 bytes x ranks (rank 0 only; the others wait at the barrier).
    double memcpy_s = 0;
    if (rank == 0) {
      size_t n = size_t(w) * h * 4 * ranks;
      std::vector<uint8_t> src(n, 1), dst(n, 0);
      std::vector<double> t;
      for (int i = 0; i < warmup + reps; ++i) {
        auto t0 = std::chrono::steady_clock::now();
        std::memcpy(dst.data(), src.data(), n);
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (i >= warmup) t.push_back(s);
        src[size_t(i) % n] ^= dst[n - 1 - size_t(i) % n];  // keep the copies observable
      }
      memcpy_s = median(t);
    }
    MPI_Barrier(MPI_COMM_WORLD);

    ImageRGBA8 first_frame;  // rank 0: the first strategy's frame, to check the others against
    std::string first_name;
    for (const std::string& spec : strategies)
    for (const std::string& precision : precisions)
    for (const std::string& rle : rles) {
      std::string name = spec;
      int radix = 2;
      if (auto c = spec.find(':'); c != std::string::npos) {
        name = spec.substr(0, c);
        radix = std::stoi(spec.substr(c + 1));
      }
      if (name == "binary-swap") radix = 2;
      CompositeOptions opts;
      opts.precision = precision == "rgba8" ? Precision::kRgba8 : Precision::kFloat;
      opts.rle = rle != "off";
      auto compositor = makeCompositor(name, radix, opts);
      const std::string label = spec + "/" + precision + "/rle-" + rle;
      std::vector<double> times;
      double counts[3] = {0, 0, 0};
      for (int i = 0; i < warmup + reps; ++i) {
        std::vector<BrickImage> mine = opts.rle ? layer : layer_raw;
        CompositeStats cs;
        g_messages = g_bytes = g_pixels = 0;
        MPI_Barrier(MPI_COMM_WORLD);
        g_counting = true;
        double t0 = MPI_Wtime();
        ImageRGBA8 frame = compositor->composite(std::move(mine), order, w, h, MPI_COMM_WORLD, cs);
        double dt = MPI_Wtime() - t0;
        g_counting = false;
        double slowest = 0;
        MPI_Reduce(&dt, &slowest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
        double mine_counts[3] = {g_messages, g_bytes, g_pixels};
        MPI_Reduce(mine_counts, counts, 3, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        if (i >= warmup) times.push_back(slowest);
        if (rank == 0 && i == 0) {
          if (first_frame.px.empty()) {
            first_frame = frame;
            first_name = label;
          } else {
            int worst = 0;
            for (size_t p = 0; p < frame.px.size() && p < first_frame.px.size(); ++p)
              worst = std::max(worst, std::abs(int(frame.px[p]) - int(first_frame.px[p])));
            std::fprintf(stderr, "bench_compositing: %dx%d %s vs %s: largest difference %d/255%s\n",
                         w, h, label.c_str(), first_name.c_str(), worst,
                         frame.px.size() == first_frame.px.size() ? "" : " (sizes differ!)");
          }
        }
      }
      if (rank == 0) {
        std::printf("%s,%s,%s,%s,%s,%d,%d,%d,%.6g,%.0f,%.0f,%.0f,%.6g\n", name.c_str(),
                    name == "direct" ? "" : std::to_string(radix).c_str(), precision.c_str(),
                    rle.c_str(), layers_dir.empty() ? "synthetic" : "real", ranks, w, h,
                    median(times), counts[1], counts[0], counts[2], memcpy_s);
        std::fflush(stdout);
      }
    }
  }
  MPI_Finalize();
  return 0;
}
