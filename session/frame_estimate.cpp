#include "session/frame_estimate.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/box.h"
#include "common/enum_names.h"
#include "common/pixel_threads.h"
#include "io/image.h"

namespace sortlast {

namespace {

constexpr double kZ95 = 1.959964;  // two-sided 95 % normal quantile
constexpr int kOverTolerance = 4;  // IceT's image tests: pixels more than 4/255 off

// The 8-bit value a written frame holds: premultiplied v over background b, as opaqueOver rounds.
uint8_t over8(float v, float a, double b) {
  const float x = std::clamp(v + (1.0f - a) * float(b), 0.0f, 1.0f);
  return uint8_t(std::lround(x * 255.0f));
}

// The luminance of pixel (x, y) over the background, in 8-bit units, unrounded: only the
// contrast that weighs the tiles reads it (a pass over the volume's rectangle every estimate;
// rounding each channel as over8 does took half of the pixel choice's time).
float luminance(const ImageRGBA8& f, const glm::vec3& bg, int x, int y) {
  const uint8_t* p = f.at(x, y);
  const float behind = 255.0f - p[3];
  auto ch = [&](int c) { return std::clamp(float(p[c]) + behind * bg[c], 0.0f, 255.0f); };
  return 0.299f * ch(0) + 0.587f * ch(1) + 0.114f * ch(2);
}

// A tile's draws: splitmix64 (Steele, Lea and Flood), seeded by the tile; seeding a Mersenne
// twister per tile (2,500 words of state) was a fifth of the pixel choice.
struct TileRandom {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi] (Lemire's multiply-shift; its bias, at most (hi - lo + 1) / 2^32 -- a
  // tile holds a few hundred pixels --, is immaterial).
  int between(int lo, int hi) { return lo + int(((next() >> 32) * uint64_t(hi - lo + 1)) >> 32); }
};

// Record of one segment sent to rank 0: sample index, start along the ray, rgb, transmittance.
constexpr int kRecord = 6;

}  // namespace

EstimateSample chooseEstimatePixels(const ImageRGBA8& frame, const glm::dvec3& background,
                                    const Rect& rect, int budget) {
  EstimateSample s;
  s.width = frame.width;
  s.height = frame.height;
  if (rect.empty() || budget <= 0) return s;
  // Tiles: at most budget / 4 of them, so each gets 2 samples or more with room to spare for
  // the contrasty ones; at least 4 pixels a side.
  const double area = double(rect.area());
  const int side = std::max(4, int(std::ceil(std::sqrt(area * 4.0 / budget))));
  const int tx = (rect.w + side - 1) / side, ty = (rect.h + side - 1) / side;
  const int tiles = tx * ty;
  s.tile_pixels.assign(size_t(tiles), 0.0);
  s.tile_samples.assign(size_t(tiles), 0);
  std::vector<double> contrast(size_t(tiles), 0.0);
  // Each pixel's luminance once (the rectangle and the row and column past it), not three times.
  const int lw = std::min(frame.width, rect.x + rect.w + 1) - rect.x,
            lh = std::min(frame.height, rect.y + rect.h + 1) - rect.y;
  std::vector<float> lum(size_t(lw) * size_t(lh));
  const glm::vec3 bg(background);
  for (int y = 0; y < lh; ++y)
    for (int x = 0; x < lw; ++x) lum[size_t(y) * lw + x] = luminance(frame, bg, rect.x + x, rect.y + y);
  auto lum_at = [&](int x, int y) { return lum[size_t(y - rect.y) * lw + size_t(x - rect.x)]; };
  for (int t = 0; t < tiles; ++t) {
    const int x0 = rect.x + (t % tx) * side, y0 = rect.y + (t / tx) * side;
    const int x1 = std::min(rect.x + rect.w, x0 + side), y1 = std::min(rect.y + rect.h, y0 + side);
    s.tile_pixels[size_t(t)] = double(x1 - x0) * (y1 - y0);
    double g = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const double l = lum_at(x, y);
        if (x + 1 < frame.width) g += std::abs(lum_at(x + 1, y) - l);
        if (y + 1 < frame.height) g += std::abs(lum_at(x, y + 1) - l);
      }
    contrast[size_t(t)] = g / s.tile_pixels[size_t(t)];
  }
  double mean_c = 0.0, total_w = 0.0;
  for (int t = 0; t < tiles; ++t) mean_c += contrast[size_t(t)] * s.tile_pixels[size_t(t)];
  mean_c /= area;
  std::vector<double> w(static_cast<size_t>(tiles));
  for (int t = 0; t < tiles; ++t) total_w += w[size_t(t)] = s.tile_pixels[size_t(t)] * (contrast[size_t(t)] + mean_c + 1e-3);
  for (int t = 0; t < tiles; ++t) {
    const int n = int(std::lround(budget * w[size_t(t)] / total_w));
    s.tile_samples[size_t(t)] = std::clamp(n, std::min(2, int(s.tile_pixels[size_t(t)])), int(s.tile_pixels[size_t(t)]));
  }
  // Each tile's samples: distinct pixels, uniformly (a partial Fisher-Yates), seeded by the tile.
  for (int t = 0; t < tiles; ++t) {
    const int x0 = rect.x + (t % tx) * side, y0 = rect.y + (t / tx) * side;
    const int w_t = std::min(rect.x + rect.w, x0 + side) - x0;
    const int n_all = int(s.tile_pixels[size_t(t)]);
    std::vector<int> idx(static_cast<size_t>(n_all));
    std::iota(idx.begin(), idx.end(), 0);
    TileRandom rng{0x5eed0000ull + uint64_t(t)};
    for (int k = 0; k < s.tile_samples[size_t(t)]; ++k) {
      std::swap(idx[size_t(k)], idx[size_t(rng.between(k, n_all - 1))]);
      const int x = x0 + idx[size_t(k)] % w_t, y = y0 + idx[size_t(k)] / w_t;
      s.pixel.push_back(y * frame.width + x);
      s.stratum.push_back(t);
    }
  }
  return s;
}

void broadcastSample(EstimateSample& s, MPI_Comm comm) {
  int head[4] = {s.width, s.height, int(s.pixel.size()), int(s.tile_pixels.size())};
  MPI_Bcast(head, 4, MPI_INT, 0, comm);
  s.width = head[0];
  s.height = head[1];
  s.pixel.resize(size_t(head[2]));
  s.stratum.resize(size_t(head[2]));
  s.tile_pixels.resize(size_t(head[3]));
  s.tile_samples.resize(size_t(head[3]));
  MPI_Bcast(s.pixel.data(), head[2], MPI_INT, 0, comm);
  MPI_Bcast(s.stratum.data(), head[2], MPI_INT, 0, comm);
  MPI_Bcast(s.tile_pixels.data(), head[3], MPI_DOUBLE, 0, comm);
  MPI_Bcast(s.tile_samples.data(), head[3], MPI_INT, 0, comm);
}

std::vector<double> exactSampledPixels(const EstimateSample& sample, const Camera& cam,
                                       const EstimateVolume& mine, const glm::dvec3& background,
                                       int threads, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = int(sample.pixel.size());
  const double flat = flatGradient(mine.tf.rangeLo(), mine.tf.rangeHi(), mine.bricks.empty() ? glm::dvec3(1.0)
                                                                                              : mine.bricks[0].grid.spacing);
  // This rank's segments, per sampled pixel, in parts over the pixels.
  const int workers = std::max(1, threads);
  std::vector<std::vector<double>> parts(static_cast<size_t>(workers));
  std::atomic<int> next{0};
  auto work = [&](int w) {
    std::vector<double>& out = parts[size_t(w)];
    for (int i; (i = next.fetch_add(16)) < n;)
      for (int k = i; k < std::min(n, i + 16); ++k) {
        const int p = sample.pixel[size_t(k)];
        const CameraRay ray = cam.pixelRay(p % sample.width, p / sample.width);
        for (size_t b = 0; b < mine.bricks.size(); ++b) {
          double t0, t1;
          if (!intersectRayBox(ray.origin, ray.direction, mine.boxes[b], t0, t1)) continue;
          t0 = std::max(t0, 0.0);
          clipSpan(mine.clip, ray.origin, ray.direction, t0, t1);
          if (!(t1 > t0)) continue;
          const SegmentIntegral s = integrateSegment(mine.bricks[b], mine.tf, mine.shading, flat, ray.origin,
                                                     ray.direction, t0, t1, mine.step, &mine.empty[b]);
          if (s.transmit == 1.0 && s.rgb[0] == 0.0 && s.rgb[1] == 0.0 && s.rgb[2] == 0.0) continue;
          out.insert(out.end(), {double(k), t0, s.rgb[0], s.rgb[1], s.rgb[2], s.transmit});
        }
      }
  };
  parallelParts(workers, work);  // the rank's pixel pool (its share of the node's cores)
  std::vector<double> records;
  for (auto& p : parts) records.insert(records.end(), p.begin(), p.end());
  // To rank 0.
  int count = int(records.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size), 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (rank == 0) {
    for (int r = 1; r < size; ++r) displs[size_t(r)] = displs[size_t(r - 1)] + counts[size_t(r - 1)];
    all.resize(size_t(displs.back() + counts.back()));
  }
  MPI_Gatherv(records.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm);
  if (rank != 0) return {};
  // Front to back per pixel: sort the segments by (pixel, start).
  const size_t m = all.size() / kRecord;
  std::vector<size_t> order(m);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const double* x = &all[a * kRecord];
    const double* y = &all[b * kRecord];
    return x[0] != y[0] ? x[0] < y[0] : x[1] < y[1];
  });
  std::vector<double> rgb(size_t(n) * 3, 0.0), transmit(size_t(n), 1.0);
  for (size_t o : order) {
    const double* r = &all[o * kRecord];
    const size_t k = size_t(r[0]);
    for (int c = 0; c < 3; ++c) rgb[3 * k + size_t(c)] += transmit[k] * r[2 + c];
    transmit[k] *= r[5];
  }
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) rgb[3 * size_t(k) + size_t(c)] += transmit[size_t(k)] * background[c];
  return rgb;
}

AccuracyEstimate compareWithExact(const EstimateSample& sample, const std::vector<double>& exact,
                                  const ImageRGBA8* frame, const ImageF* float_frame,
                                  const glm::dvec3& background) {
  AccuracyEstimate e;
  const size_t tiles = sample.tile_pixels.size();
  std::vector<double> se_sum(tiles, 0.0), se_sq(tiles, 0.0), over(tiles, 0.0);
  for (size_t k = 0; k < sample.pixel.size(); ++k) {
    const size_t p = size_t(sample.pixel[k]);
    double se = 0.0;
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      uint8_t got;
      if (float_frame)
        got = over8(float_frame->px[4 * p + size_t(c)], float_frame->px[4 * p + 3], background[c]);
      else
        got = over8(frame->px[4 * p + size_t(c)] / 255.0f, frame->px[4 * p + 3] / 255.0f, background[c]);
      const double x = std::clamp(exact[3 * k + size_t(c)], 0.0, 1.0);
      const int want = int(std::lround(float(x) * 255.0f));
      const int diff = std::abs(int(got) - want);
      se += double(diff) * diff;
      worst = std::max(worst, diff);
    }
    se /= 3.0;
    const size_t t = size_t(sample.stratum[k]);
    se_sum[t] += se;
    se_sq[t] += se * se;
    over[t] += worst > kOverTolerance ? 1.0 : 0.0;
    e.largest_seen = std::max(e.largest_seen, worst);
  }
  // Stratified means over the whole frame (pixels outside the tiles: exact).
  const double total = double(sample.width) * sample.height;
  double tiles_area = 0.0;
  for (size_t t = 0; t < tiles; ++t) tiles_area += sample.tile_pixels[t];
  double mse = 0.0, var_mse = 0.0, share = 0.0, var_share = 0.0;
  for (size_t t = 0; t < tiles; ++t) {
    const double n = sample.tile_samples[t], big_n = sample.tile_pixels[t];
    if (n <= 0) continue;
    mse += big_n / total * se_sum[t] / n;
    share += big_n / total * over[t] / n;
  }
  // Their variances, each tile's shrunk toward the frame's by one pseudo-sample. A tile's 2-5
  // samples mostly see none of the few pixels far off (a rim, a band) where the frame has them,
  // and a variance of 0 there made the bounds too narrow. The share: (over + share) / (n + 1) for
  // p (1 - p). The MSE: ((n - 1) s2 + s2_frame) / n, s2_frame the squared error's variance over
  // the tiles. Redrawn on whole frames against their references (bench/accuracy/
  // estimate-coverage, 200 draws a view, 6-8 views each; results/accuracy/estimate_coverage.md):
  // the share's truth inside the plain bound in 0.93-0.94 of the draws on neghip and engine (0.87
  // in the worst view), inside the shrunk one in 0.98-0.99 (0.945), 18-57 % wider.
  const double tiles_share = tiles_area > 0 ? share * total / tiles_area : 0.0;
  const double tiles_mse = tiles_area > 0 ? mse * total / tiles_area : 0.0;
  double s2_frame = 0.0;  // sum over the tiles of N_t / area x their samples' mean (se - tiles_mse)^2
  for (size_t t = 0; t < tiles; ++t) {
    const double n = sample.tile_samples[t];
    if (n <= 0) continue;
    const double mean_sq = (se_sq[t] - 2.0 * tiles_mse * se_sum[t]) / n + tiles_mse * tiles_mse;
    s2_frame += sample.tile_pixels[t] / tiles_area * std::max(0.0, mean_sq);
  }
  for (size_t t = 0; t < tiles; ++t) {
    const double n = sample.tile_samples[t], big_n = sample.tile_pixels[t];
    if (n <= 1) continue;
    const double wgt = big_n / total, fpc = 1.0 - n / big_n;
    const double mean = se_sum[t] / n;
    const double s2 = std::max(0.0, (se_sq[t] - n * mean * mean) / (n - 1));
    var_mse += wgt * wgt * fpc * ((n - 1) * s2 + s2_frame) / n / n;
    const double p = (over[t] + tiles_share) / (n + 1.0);
    var_share += wgt * wgt * fpc * (p * (1 - p) * n / (n - 1)) / n;
  }
  e.mse = mse;
  e.mse_se = std::sqrt(var_mse);
  e.over4_share = share;
  e.over4_se = std::sqrt(var_share);
  e.sampled = int(sample.pixel.size());
  // The rule of three's floor for the share's upper bound: with no pixel over seen among n
  // samples, a share up to 3 / n of the sampled area is still 95 % plausible.
  // Times the share of the tiles' pixels left unsampled (all sampled: the share is known).
  e.rule_of_three = e.sampled > 0 ? 3.0 / e.sampled * std::max(0.0, 1.0 - e.sampled / tiles_area) * tiles_area / total
                                  : 1.0;
  return e;
}

double AccuracyEstimate::psnr_db() const {
  return mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
}
double AccuracyEstimate::psnrLo() const {
  const double m = mse + kZ95 * mse_se;
  return m > 0 ? 10.0 * std::log10(255.0 * 255.0 / m) : std::numeric_limits<double>::infinity();
}
double AccuracyEstimate::psnrHi() const {
  const double m = mse - kZ95 * mse_se;
  return m > 0 ? 10.0 * std::log10(255.0 * 255.0 / m) : std::numeric_limits<double>::infinity();
}
double AccuracyEstimate::over4Hi() const { return std::max(over4_share + kZ95 * over4_se, rule_of_three); }
double AccuracyEstimate::over4Lo() const { return std::max(0.0, over4_share - kZ95 * over4_se); }

nlohmann::json AccuracyEstimate::json() const {
  auto db = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json("inf"); };
  return {{"estimated_psnr_db", db(psnr_db())},
          {"psnr_db_95", {db(psnrLo()), db(psnrHi())}},
          {"over4_share", over4_share},
          {"over4_share_95", {over4Lo(), over4Hi()}},
          {"largest_diff_seen", largest_seen},
          {"pixels_sampled", sampled}};
}

std::string estimateUnavailable(const Scene& sc, bool adaptive, bool in_situ, const StepData* d) {
  if (!sc.hasVolume()) return "no volume";
  if (sc.hasFields()) return "several fields (volumes)";
  if (sc.render.blend != VolumeBlend::kComposite)
    return "render.blend " + std::string(nameOf(sc.render.blend)) + " (the estimate models composite)";
  if (sc.particles.enabled()) return "particles in the frame";
  if (!sc.surfaces.empty()) return "surfaces in the frame";
  if (sc.glow.enabled()) return "glow in the frame";
  if (adaptive) return "adaptive sampling (adaptive.tolerance above 0)";
  if (in_situ) return "in situ without the simulation's samples";
  if (!d || d->dropped) return "the samples are no longer held";
  return "";
}

EstimateVolume estimateVolumeOf(const Scene& sc, const SessionLayout& layout, const StepData& d,
                                std::pair<double, double> range, EmptyBlocksCache* cache, long long data_id) {
  EstimateVolume v;
  for (size_t i = 0; i < layout.mine.size() && i < d.samples.size(); ++i) {
    const Brick& b = layout.volume_bricks[size_t(layout.mine[i])];
    if (d.samples[i].empty()) continue;
    v.bricks.push_back({layout.grid, b.stored, d.samples[i].data()});
    v.boxes.push_back(b.world);
  }
  v.tf = sc.transfer.build(range.first, range.second, layout.grid.minSpacing());
  v.shading = sc.render.shading;
  v.clip = sc.clip;
  v.step = sc.reference.step * layout.grid.minSpacing();
  // After the step and the shading: the blocks' step multiples depend on both (built before
  // them, every block's multiple was 1 and the estimate marched the fine step everywhere).
  auto build = [&](std::vector<EmptyBlocks>& out) {
    out.clear();
    for (const BrickField& f : v.bricks) out.emplace_back(f, v.tf, v.step, v.shading.enabled);
  };
  if (!cache || data_id < 0) {
    build(v.empty);
    return v;
  }
  // What EmptyBlocks reads besides the samples (the function's range, scale, unit length and
  // points; the step; shading), and which samples.
  std::vector<double> key{v.step, double(v.shading.enabled), double(v.bricks.size())};
  v.tf.appendKey(key);
  if (cache->data != data_id || cache->key != key) {
    build(cache->empty);
    cache->data = data_id;
    cache->key = std::move(key);
  }
  v.empty = cache->empty;
  return v;
}

nlohmann::json estimateFrame(const EstimateVolume& mine, const Camera& cam, const Box3& volume_box,
                             const glm::dvec3& background, const ImageRGBA8* frame,
                             const ImageF* float_frame, int budget, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const double t0 = MPI_Wtime();
  EstimateSample sample;
  if (rank == 0) {
    ImageRGBA8 from_float;
    const ImageRGBA8* f8 = frame;
    if (float_frame) {  // the contrast only: rounded as a written frame is (io/image.h)
      from_float = toRGBA8(*float_frame);
      f8 = &from_float;
    }
    sample = chooseEstimatePixels(*f8, background, screenRectOf(cam, volume_box), budget);
  }
  broadcastSample(sample, comm);
  // This rank's share of the node's cores (common/pixel_threads.h), not all of them: 4 ranks on
  // 2 cores started 8 integrating threads.
  const std::vector<double> exact = exactSampledPixels(sample, cam, mine, background, pixelThreads(), comm);
  if (rank != 0) return nullptr;
  nlohmann::json j = compareWithExact(sample, exact, frame, float_frame, background).json();
  j["seconds"] = MPI_Wtime() - t0;
  return j;
}

}  // namespace sortlast
