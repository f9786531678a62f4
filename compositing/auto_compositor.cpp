#include "compositing/auto_compositor.h"

#include <cstdio>
#include <stdexcept>

#include "compositing/strategy_model.h"

namespace sortlast {

AutoCompositor::AutoCompositor(const CompositeOptions& options, std::vector<int> radices)
    : opt_(options), radices_(std::move(radices)) {
  for (int k : radices_)
    if (k < 2) throw std::invalid_argument("auto: every radix must be >= 2, got " + std::to_string(k));
}

void AutoCompositor::begin(const FrameSetup& setup) {
  if (!setup.footprint)
    throw std::logic_error("compositing.strategy auto: the frame has no footprint to forecast from");
  if (current_ && last_footprint_ && *last_footprint_ == *setup.footprint &&
      last_ranks_ == setup.order->ranks && last_width_ == setup.width && last_height_ == setup.height) {
    current_->begin(setup);
    return;
  }
  last_footprint_ = std::make_unique<FrameFootprint>(*setup.footprint);
  last_ranks_ = setup.order->ranks;
  last_width_ = setup.width, last_height_ = setup.height;
  ModelSettings m;
  m.network = {opt_.network_latency_s, opt_.network_bandwidth_Bps};
  m.ranks_per_core = opt_.ranks_per_core;
  const std::vector<StrategyForecast> fc = forecastStrategies(
      *setup.order, *setup.footprint, setup.width, setup.height, opt_, m, radices_);
  const StrategyForecast& best = fastest(fc);
  choice_ = {best.strategy, best.radix, best.label(), best.seconds, {}};
  // The line --stats shows: every forecast, then the chosen one's phases.
  std::string why = "forecast";
  char buf[96];
  for (const StrategyForecast& f : fc) {
    std::snprintf(buf, sizeof buf, " %s %.3g ms%s", f.label().c_str(), 1e3 * f.seconds,
                  &f == &fc.back() ? ";" : ",");
    why += buf;
  }
  why += " " + best.label() + ":";
  for (size_t i = 0; i < best.phases.size(); ++i) {
    std::snprintf(buf, sizeof buf, " %s %.3g ms%s", best.phases[i].first.c_str(),
                  1e3 * best.phases[i].second, i + 1 < best.phases.size() ? "," : "");
    why += buf;
  }
  choice_.why = why;
  auto& slot = made_[{best.strategy, best.radix}];
  if (!slot) slot = makeCompositor(best.strategy, best.radix, opt_);
  current_ = slot.get();
  current_->begin(setup);
}

}  // namespace sortlast
