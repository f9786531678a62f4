#pragma once
// Direct send (the paper's scheme): every rank sends each brick image to rank 0, which blends all
// of them in visibility order. Simple and exact, but rank 0 receives everything: it does not
// scale.
//
// Overlap: a worker starts sending a brick's image (non-blocking) as soon as it is rendered and
// goes on to the next brick; rank 0, between its own bricks and then while waiting, takes what has
// arrived and blends every image whose turn has come (all images behind it in the visibility
// order already blended), so little is left to do when the last image arrives.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compositing/compositor.h"

namespace sortlast {

class DirectSend final : public Compositor {
 public:
  explicit DirectSend(const CompositeOptions& options) : opt_(options) {}
  ~DirectSend() override;
  void begin(const FrameSetup& setup) override;
  void add(BrickImage image) override;
  bool takesLocalEmission() const override {
    return rank_ == 0 && opt_.emission && opt_.precision == Precision::kFloat;
  }
  void progress() override;
  ImageRGBA8 finish(CompositeStats& stats, ImageF* float_frame) override;
  void recycle(ImageRGBA8 frame) override { spare_8_ = std::move(frame); }
  void abandon() override;

 private:
  // Worker side.
  void send(const BrickImage& image);
  void waitSends();
  // Rank 0.
  bool takeMessage(bool wait);  // receives one message if one is there (or until one is)
  void accept(BrickImage image, int source);
  void blendReady();            // blends images in order while the next one is at hand
  void blendInOrder(const std::vector<int>& order);
  // A transparent frame: the recycled one (cleared) if it has this size, else a fresh one.
  ImageRGBA8 frameImage(int width, int height);

  CompositeOptions opt_;
  FrameSetup setup_;
  int rank_ = 0;
  CompositeStats stats_;
  // Worker side: packed messages stay alive until their sends complete.
  std::vector<std::unique_ptr<std::vector<uint8_t>>> packed_;
  std::vector<MPI_Request> requests_;
  std::vector<BrickImage> held_;  // without overlap: sent in finish()
  int sent_ = 0;
  // Rank 0.
  std::map<int, BrickImage> pending_;  // received (or own), not yet blended
  std::vector<bool> seen_;             // per brick id
  size_t next_ = 0;                    // position in the visibility order of the next blend
  int expected_ = 0, received_ = 0;    // messages from other ranks
  std::string error_;                  // first malformed message; reported after draining
  ImageF frame_f_;                     // kept between frames (see begin())
  Rect dirty_;                         // the part of frame_f_ this frame has blended into
  ImageRGBA8 frame_8_;
  ImageRGBA8 spare_8_;  // a returned frame handed back (recycle()): the next frame's memory
  std::vector<uint8_t> buffer_;
};

}  // namespace sortlast
