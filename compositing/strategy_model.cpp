#include "compositing/strategy_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compositing/radix_k_plan.h"
#include "compositing/rect_image.h"

namespace sortlast {

namespace {

// Seconds for `pixels` of `work` (wire format of `bytes` per pixel where it matters).
struct Cost {
  const PixelRates& rates;
  double operator()(PixelWork work, double pixels, int bytes = 4) const {
    return pixels <= 0 ? 0.0 : pixels * rates.at(work, bytes) * 1e-9;
  }
};

constexpr double kHeaderBytes = 24;  // packBrickImage's header

StrategyForecast forecastDirect(const FrameFootprint& fp, int width, int height,
                                const CompositeOptions& opt, const ModelSettings& m) {
  const Cost cost{m.rates};
  const int ranks = int(fp.rect.size());
  const int brick_bytes = opt.emission || opt.projection != WireFormat::RGBA8 ? 8 : 4;
  Rect dirty;
  double pixels = 0, bytes_in = 0;
  int messages = 0;
  for (int r = 0; r < ranks; ++r) {
    dirty = unionOf(dirty, fp.rect[size_t(r)]);
    pixels += fp.brick_pixels[size_t(r)];
    if (r != 0) {
      bytes_in += fp.brick_pixels[size_t(r)] * brick_bytes + kHeaderBytes * fp.bricks[size_t(r)];
      messages += fp.bricks[size_t(r)];
    }
  }
  StrategyForecast f{"direct", 0};
  const bool float_frame = opt.precision == Precision::kFloat;
  const double clear = float_frame && !m.first_frame ? cost(PixelWork::Copy, double(dirty.area())) : 0;
  const double blend = cost(float_frame ? PixelWork::DecodeBlend8 : PixelWork::DecodeBlendInto8,
                            pixels, brick_bytes);
  const double round = float_frame ? cost(PixelWork::Fill8, double(width) * height) +
                                         cost(PixelWork::Round8, double(dirty.area()))
                                   : 0;
  // Rank 0 takes one message at a time, and each costs it a latency: a large message goes by
  // rendezvous, its transfer starting when the receive is posted (SMPI sends every message so).
  const double transfer = messages * m.network.latency_s + bytes_in / m.network.bandwidth_Bps;
  f.phases = {{"clear", clear}, {"receive", transfer}, {"blend", blend}, {"round", round}};
  f.compute_s = clear + blend + round;
  for (const auto& [name, s] : f.phases) f.seconds += s;
  return f;
}

StrategyForecast forecastRadixK(const VisibilityOrder& order, const FrameFootprint& fp, int width,
                                int height, int k, const CompositeOptions& opt,
                                const ModelSettings& m) {
  const Cost cost{m.rates};
  const double slow = std::max(1.0, m.ranks_per_core);  // ranks sharing a core share its time
  const double lat = m.network.latency_s, bw = m.network.bandwidth_Bps;
  const int ranks = int(fp.rect.size());
  const int brick_bytes = opt.emission || opt.projection != WireFormat::RGBA8 ? 8 : 4;
  const int partial = opt.emission || opt.projection != WireFormat::RGBA8 ? 8 : opt.precision == Precision::kRgba8 ? 4 : 8;
  StrategyForecast f{k == 2 ? "binary-swap" : "radix-k", k};
  auto phase = [&](const char* name, double compute, double other) {
    f.phases.emplace_back(name, compute * slow + other);
    f.compute_s += compute * slow;
    f.seconds += compute * slow + other;
  };

  // 1. Own bricks into one image (zero fill, decode and blend, active-rectangle scan), then the
  // allgather of rectangles (Bruck: ceil(log2 P) steps).
  double local = 0;
  for (int r = 0; r < ranks; ++r) {
    const double a = double(fp.rect[size_t(r)].area());
    local = std::max(local, cost(PixelWork::Copy, a) +
                                cost(PixelWork::DecodeBlend8, fp.brick_pixels[size_t(r)], brick_bytes) +
                                cost(PixelWork::Scan, a));
  }
  phase("own bricks", local, 0);
  phase("allgather", 0, lat * std::ceil(std::log2(std::max(2, ranks))));

  const RadixKPlan plan = makeRadixKPlan(order.ranks, fp.rect, k);
  const RadixKSchedule& s = plan.schedule;
  const RadixKPlan::Rounds at = plan.everyRound();
  auto encode = [&](double a, int bytes) {
    return cost(PixelWork::Scan, a) + cost(PixelWork::Encode, a, bytes);
  };

  // 2. Folds: the nearer of each pair sends its whole image to the farther.
  double fold_c = 0, fold_n = 0;
  for (int i = 0; i < s.folds; ++i) {
    const Rect& far = plan.content[size_t(2 * i)];
    const Rect& near = plan.content[size_t(2 * i + 1)];
    const double a = double(near.area());
    const double c = encode(a, partial) + cost(PixelWork::Decode, a, partial) +
                     cost(PixelWork::Copy, double(unionOf(far, near).area())) +
                     cost(PixelWork::BlendFloat, double(far.area()) + a);
    if (c > fold_c) fold_c = c, fold_n = lat + (a * partial + kHeaderBytes) / bw;
  }
  if (s.folds) phase("folds", fold_c, fold_n);

  // 3. Rounds: per unit, the parts it encodes and sends, the parts it receives, decodes and
  // blends with its own; the slowest unit sets the round's time. (The group of units differing
  // only in round t's digit: base + j * stride, j < k_t.)
  for (int t = 0; t < s.rounds(); ++t) {
    double worst = 0, worst_c = 0;
    const int kt = s.radices[size_t(t)], stride = s.stride(t);
    const std::vector<Rect>& bound = at.bound[size_t(t)];
    // Group by group (its units share one region, so one split): O(units * k) a round.
    for (int base = 0; base < s.units(); ++base) {
      if (s.digit(t, base) != 0) continue;
      const std::vector<Rect> parts = splitRect(at.region[size_t(t)][size_t(base)], kt);
      for (int me = 0; me < kt; ++me) {
        const Rect& mine = bound[size_t(base + me * stride)];
        double c = 0, out = 0, in = 0;
        int received = 0;
        const Rect own = intersect(mine, parts[size_t(me)]);
        Rect all = own;
        double layers = double(own.area());
        for (int j = 0; j < kt; ++j) {
          if (j == me) continue;
          const double sent = double(intersect(mine, parts[size_t(j)]).area());
          if (sent > 0) c += encode(sent, partial), out += sent * partial + kHeaderBytes;
          const Rect got = intersect(bound[size_t(base + j * stride)], parts[size_t(me)]);
          if (!got.empty()) {
            c += cost(PixelWork::Decode, double(got.area()), partial);
            in += double(got.area()) * partial + kHeaderBytes;
            all = unionOf(all, got);
            layers += double(got.area());
            ++received;
          }
        }
        c += cost(PixelWork::Copy, double(own.area())) + cost(PixelWork::Copy, double(all.area())) +
             cost(PixelWork::BlendFloat, layers);
        // Sends go out together; receives are taken one at a time, a latency each (see direct).
        const double total = c * slow + received * lat + std::max(out, in) / bw;
        if (total > worst) worst = total, worst_c = c;
      }
    }
    phase(("round " + std::to_string(t + 1) + " (k=" + std::to_string(s.radices[size_t(t)]) + ")").c_str(),
          worst_c, worst - worst_c * slow);
  }

  // 4. Gather (radix_k.cpp, step 5): every unit rounds its final part (its bound) where it is and
  // sends it raw; rank 0 has posted a receive for each, straight into the frame, and MPI unpacks
  // each part there as it arrives while the others are still on the wire, so the longer of the
  // transfer and the unpacking counts. Rank 0 zero-filled the frame before the rounds: off its
  // path as far as the rounds last if it takes no part in them, on it otherwise.
  const bool exact = opt.emission || opt.float_frame;
  const int part_bytes = exact ? 20 : 4;  // RGBA8, and the float frame's 16 bytes a pixel
  double enc = 0, place = 0, bytes = 0;
  int messages = 0;
  for (int u = 0; u < s.units(); ++u) {
    const double a = double(at.bound[size_t(s.rounds())][size_t(u)].area());
    if (a <= 0) continue;
    double c = cost(PixelWork::Fill8, a) + cost(PixelWork::Round8, a);
    if (exact)
      c += cost(PixelWork::Copy, a) + cost(PixelWork::Encode, a, 8) + cost(PixelWork::Decode, a, 8);
    enc = std::max(enc, c);
    place += cost(PixelWork::Place, a * part_bytes / 4);
    if (plan.carrier(u) != 0) bytes += a * part_bytes, messages += exact ? 2 : 1;
  }
  const double fill = cost(PixelWork::Fill8, double(width) * height);
  const bool rank0_in_rounds = ranks > 0 && !fp.rect[0].empty();
  const double fill_on_path = rank0_in_rounds ? fill : std::max(0.0, fill - f.seconds);
  const double transfer = (messages ? lat : 0.0) + bytes / bw;
  // Rank 0 alone: its compute is not shared with other ranks' (they are done), so not slowed.
  f.phases.emplace_back("gather", fill_on_path + enc * slow + std::max(transfer, place));
  f.compute_s += fill_on_path + enc * slow + (place >= transfer ? place : 0.0);
  f.seconds += f.phases.back().second;
  return f;
}

}  // namespace

std::string StrategyForecast::label() const {
  return strategy == "radix-k" ? "radix-k k=" + std::to_string(radix) : strategy;
}

std::vector<StrategyForecast> forecastStrategies(const VisibilityOrder& order,
                                                 const FrameFootprint& footprint, int width,
                                                 int height, const CompositeOptions& options,
                                                 const ModelSettings& model,
                                                 const std::vector<int>& radices) {
  const size_t ranks = footprint.rect.size();
  if (footprint.brick_pixels.size() != ranks || footprint.bricks.size() != ranks ||
      order.ranks.size() != ranks)
    throw std::invalid_argument("strategy model: the footprint and the rank order disagree on the rank count");
  std::vector<StrategyForecast> out{forecastDirect(footprint, width, height, options, model)};
  for (int k : radices) out.push_back(forecastRadixK(order, footprint, width, height, k, options, model));
  return out;
}

const StrategyForecast& fastest(const std::vector<StrategyForecast>& forecasts) {
  if (forecasts.empty()) throw std::invalid_argument("strategy model: no candidates");
  size_t best = 0;
  for (size_t i = 1; i < forecasts.size(); ++i)
    if (forecasts[i].seconds <= forecasts[best].seconds + 1e-12) best = i;
  return forecasts[best];
}

}  // namespace sortlast
