// The cost model of `compositing.strategy: auto` (compositing/strategy_model.h) counts the pixels
// the strategies work on. This executable builds compositing/ with SORTLAST_SMPI, as the SMPI
// build does, and defines chargePixels to count each kind of work per rank (ranks are threads);
// radix-k then runs on opaque full-frame brick images (every unit does the same work, so rank 0's
// counts are the critical path) and the model, given a rate of 1 ns for one kind of work and 0
// for the rest, must forecast exactly rank 0's count of that work.
#include "compositing/strategy_model.h"

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "compositing/pixel_cost.h"
#include "compositing/radix_k.h"
#include "compositing/radix_k_plan.h"
#include "compositing/rle.h"
#include "tests/unit/thread_transport.h"

namespace sortlast {

namespace {
// Pixels charged by the calling thread (one rank), by work.
thread_local std::array<long long, int(PixelWork::Count)> t_counted{};
}  // namespace

void chargePixels(PixelWork work, long long pixels, int) { t_counted[size_t(work)] += pixels; }
void markGatherStart() {}  // the SMPI build's timing mark: nothing to time here

namespace {

// Rank 0's pixels of each work kind after radix-k (k) on P ranks, each with one opaque brick image
// covering the whole width x height frame.
std::array<long long, int(PixelWork::Count)> countRadixK(int ranks, int k, int width, int height,
                                                         const CompositeOptions& options) {
  VisibilityOrder order;
  order.bricks.resize(size_t(ranks));
  std::iota(order.bricks.begin(), order.bricks.end(), 0);
  order.ranks = order.bricks;
  std::vector<uint8_t> px(size_t(width) * height * 4, 200);
  Mailbox box;
  box.sent.resize(size_t(ranks));
  std::array<long long, int(PixelWork::Count)> rank0{};
  std::vector<std::string> errors(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      t_counted = {};
      try {
        ThreadTransport t(box, r, ranks);
        BrickImage b;
        b.brick_id = r;
        b.rect = {0, 0, width, height};
        b.rle = rleEncode(px);
        CompositeStats stats;
        radixKComposite({b}, order, width, height, k, t, stats, options);
      } catch (const std::exception& e) {
        errors[size_t(r)] = e.what();
      }
      if (r == 0) rank0 = t_counted;
    });
  for (auto& t : threads) t.join();
  for (int r = 0; r < ranks; ++r) EXPECT_EQ(errors[size_t(r)], "") << "rank " << r;
  return rank0;
}

TEST(StrategyModel, ForecastsTheRadixKPixelsOfEveryKindOfWork) {
  struct Case { int ranks, k, width, height; };
  // No folds (every rank count a product of factors <= k), parts of equal size.
  const Case cases[] = {{2, 2, 64, 48}, {4, 2, 64, 64}, {8, 2, 64, 64}, {4, 4, 64, 48},
                        {8, 4, 64, 64}, {6, 4, 96, 64}, {8, 8, 64, 48}, {1, 4, 40, 30}};
  for (const Case& c : cases)
    for (bool rgba8 : {false, true}) {
      CompositeOptions opt;
      opt.precision = rgba8 ? Precision::kRgba8 : Precision::kFloat;
      const auto counted = countRadixK(c.ranks, c.k, c.width, c.height, opt);
      VisibilityOrder order;
      order.ranks.resize(size_t(c.ranks));
      std::iota(order.ranks.begin(), order.ranks.end(), 0);
      order.bricks = order.ranks;
      FrameFootprint fp;
      fp.rect.assign(size_t(c.ranks), Rect{0, 0, c.width, c.height});
      fp.brick_pixels.assign(size_t(c.ranks), double(c.width) * c.height);
      fp.bricks.assign(size_t(c.ranks), 1);
      for (int w = 0; w < int(PixelWork::Count); ++w) {
        ModelSettings m;
        for (auto& row : m.rates.ns) row[0] = row[1] = 0.0;
        m.rates.ns[w][0] = m.rates.ns[w][1] = 1.0;  // 1 ns per pixel: seconds * 1e9 = pixels
        m.network = {0.0, 1e30};
        const StrategyForecast f =
            forecastStrategies(order, fp, c.width, c.height, opt, m, {c.k})[1];
        EXPECT_NEAR(f.seconds * 1e9, double(counted[size_t(w)]), 1e-6)
            << pixelWorkName(PixelWork(w)) << ", " << c.ranks << " ranks, k = " << c.k << ", "
            << c.width << "x" << c.height << (rgba8 ? ", rgba8" : ", float");
      }
    }
}

TEST(StrategyModel, EveryRoundsBoundsAreTheStrategysBounds) {
  // The model's O(units) table of bounds against RadixKPlan::bound, which radix_k.cpp uses.
  std::mt19937 rng(7);
  for (int ranks : {1, 2, 3, 5, 8, 13, 30, 64, 100})
    for (int k : {2, 3, 4, 8, 16}) {
      std::vector<int> order(static_cast<size_t>(ranks));
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), rng);
      std::vector<Rect> rects;
      for (int r = 0; r < ranks; ++r)
        rects.push_back(rng() % 5 == 0 ? Rect{} : Rect{int(rng() % 200), int(rng() % 100),
                                                        int(rng() % 150) + 1, int(rng() % 90) + 1});
      const RadixKPlan plan = makeRadixKPlan(order, rects, k);
      const RadixKPlan::Rounds at = plan.everyRound();
      for (int t = 0; t <= plan.schedule.rounds(); ++t)
        for (int u = 0; u < plan.schedule.units(); ++u) {
          EXPECT_EQ(at.bound[size_t(t)][size_t(u)], plan.bound(t, u))
              << ranks << " ranks, k = " << k << ", round " << t << ", unit " << u;
          EXPECT_EQ(at.region[size_t(t)][size_t(u)], plan.schedule.region(t, u, plan.whole));
        }
    }
}

TEST(StrategyModel, DirectSendIsRankZerosDecodingAndTheNetworksBytes) {
  // Three ranks, two bricks each of 100 x 50 pixels on a 200 x 100 frame; rank 0 receives four.
  VisibilityOrder order;
  order.ranks = {2, 0, 1};
  order.bricks = {0, 1, 2, 3, 4, 5};
  FrameFootprint fp;
  fp.rect = {Rect{0, 0, 100, 50}, Rect{100, 0, 100, 50}, Rect{0, 50, 200, 50}};
  fp.brick_pixels = {10000, 10000, 10000};
  fp.bricks = {2, 2, 2};
  ModelSettings m;
  for (auto& row : m.rates.ns) row[0] = row[1] = 0.0;
  m.rates.ns[int(PixelWork::DecodeBlend8)][0] = 2.0;
  m.rates.ns[int(PixelWork::Round8)][0] = 1.0;
  m.network = {1e-6, 1e9};
  const StrategyForecast f = forecastStrategies(order, fp, 200, 100, {}, m, {})[0];
  EXPECT_EQ(f.strategy, "direct");
  // Blend 30,000 px at 2 ns, round the 200 x 100 union at 1 ns, 4 messages of 5,000 px at 4 bytes
  // (and a 24-byte header) at 1 GB/s, a microsecond each.
  const double want = 30000 * 2e-9 + 20000 * 1e-9 + 4 * 1e-6 + (20000 * 4 + 4 * 24) / 1e9;
  EXPECT_NEAR(f.seconds, want, 1e-12);
}

TEST(StrategyModel, ForecastsAreTheSameForTheSameFrame) {
  // auto's promise that every rank chooses alike rests on this: no state, no clock.
  VisibilityOrder order;
  order.ranks = {3, 1, 0, 2, 4};
  order.bricks = order.ranks;
  FrameFootprint fp;
  for (int r = 0; r < 5; ++r) {
    fp.rect.push_back(Rect{10 * r, 5 * r, 300 - 20 * r, 200});
    fp.brick_pixels.push_back(double(fp.rect.back().area()));
    fp.bricks.push_back(1);
  }
  const ModelSettings m;
  const auto a = forecastStrategies(order, fp, 400, 300, {}, m);
  const auto b = forecastStrategies(order, fp, 400, 300, {}, m);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].seconds, b[i].seconds) << a[i].label();
  EXPECT_EQ(fastest(a).label(), fastest(b).label());
}

}  // namespace
}  // namespace sortlast
