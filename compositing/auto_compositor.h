#pragma once
// `compositing.strategy: auto`: each frame, the strategy (and radix-k's k) the cost model
// (strategy_model.h) forecasts fastest for this frame's rank count, image size and footprint, run
// behind the same interface. Every rank forecasts from the same footprint, so every rank makes
// the same choice without a message; the caller can check that it did (render_session.cpp).
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "compositing/compositor.h"
#include "compositing/strategy_model.h"

namespace sortlast {

class AutoCompositor final : public Compositor {
 public:
  // Candidates: direct send, then radix-k with each of `radices` (2: binary-swap).
  explicit AutoCompositor(const CompositeOptions& options,
                          std::vector<int> radices = {2, 4, 8, 16, 32});
  void begin(const FrameSetup& setup) override;  // throws without setup.footprint
  void add(BrickImage image) override { current_->add(std::move(image)); }
  bool takesLocalEmission() const override { return current_ && current_->takesLocalEmission(); }
  void progress() override { current_->progress(); }
  ImageRGBA8 finish(CompositeStats& stats, ImageF* float_frame) override {
    return current_->finish(stats, float_frame);
  }
  void recycle(ImageRGBA8 frame) override {
    if (current_) current_->recycle(std::move(frame));
  }
  void abandon() override {
    if (current_) current_->abandon();
  }
  const StrategyChoice* choice() const override { return current_ ? &choice_ : nullptr; }

 private:
  CompositeOptions opt_;
  std::vector<int> radices_;
  // One compositor per strategy chosen so far (direct send keeps its float frame between frames).
  std::map<std::pair<std::string, int>, std::unique_ptr<Compositor>> made_;
  Compositor* current_ = nullptr;
  StrategyChoice choice_;
  // The last frame's inputs: the same again (a still camera) keeps its choice without a forecast,
  // which costs milliseconds at thousands of ranks.
  std::unique_ptr<FrameFootprint> last_footprint_;
  std::vector<int> last_ranks_;
  int last_width_ = 0, last_height_ = 0;
};

}  // namespace sortlast
