#include "compositing/direct_send.h"

#include <algorithm>
#include <stdexcept>

#include "common/pixel_threads.h"
#include "compositing/blend.h"
#include "compositing/pixel_cost.h"
#include "compositing/rect_image.h"
#include "compositing/projection_pixels.h"

namespace sortlast {

namespace {
constexpr int kBrickTag = 101;
// A message standing in for a brick image that a failed rank will never render (abandon()).
constexpr int kNoImage = -1;
}  // namespace

DirectSend::~DirectSend() {
  // Sends still running here would be erroneous to leave; finish() and abandon() complete them.
  if (!requests_.empty()) MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
}

void DirectSend::begin(const FrameSetup& setup) {
  setup_ = setup;
  MPI_Comm_rank(setup.comm, &rank_);
  stats_ = {};
  packed_.clear();
  requests_.clear();
  held_.clear();
  sent_ = 0;
  pending_.clear();
  next_ = 0;
  received_ = 0;
  error_.clear();
  if (rank_ != 0) return;
  if (isProjection(opt_.projection) && opt_.precision != Precision::kFloat)
    throw std::logic_error("direct send: projections are combined in float only");
  const size_t n = setup.order->bricks.size();
  seen_.assign(n, false);
  expected_ = int(n) - setup.brick_count;
  if (opt_.precision == Precision::kFloat) {
    // The float frame is kept from frame to frame and only what the last frame touched is
    // cleared: a fresh 2048^2 float frame costs more in page faults than all the blending.
    if (frame_f_.width != setup.width || frame_f_.height != setup.height)
      frame_f_ = ImageF(setup.width, setup.height);
    else {
      chargePixels(PixelWork::Copy, dirty_.area());
      const size_t rows_per_part = std::max<size_t>(1, (size_t(1) << 16) / size_t(std::max(dirty_.w, 1)));
      parallelFor(size_t(dirty_.h), rows_per_part, [&](size_t b, size_t e) {
        for (int y = dirty_.y + int(b); y < dirty_.y + int(e); ++y)
          std::fill_n(&frame_f_.px[(size_t(y) * setup.width + size_t(dirty_.x)) * 4],
                      size_t(dirty_.w) * 4, 0.0f);
      });
    }
    dirty_ = {};
  } else {
    frame_8_ = frameImage(setup.width, setup.height);
  }
}

ImageRGBA8 DirectSend::frameImage(int width, int height) {
  if (spare_8_.width != width || spare_8_.height != height) return ImageRGBA8(width, height);
  // Its pages are already faulted in: clearing them is a memset on the pixel threads, not the
  // kernel's fault-and-zero of a fresh allocation page by page.
  ImageRGBA8 out = std::move(spare_8_);
  spare_8_ = {};
  parallelFor(out.px.size(), size_t(1) << 20,
              [&](size_t b, size_t e) { std::fill(out.px.data() + b, out.px.data() + e, uint8_t(0)); });
  return out;
}

void DirectSend::send(const BrickImage& image) {
  double t0 = MPI_Wtime();
  packed_.push_back(std::make_unique<std::vector<uint8_t>>(packBrickImage(image)));
  const std::vector<uint8_t>& bytes = *packed_.back();
  stats_.bytes_sent += double(bytes.size());
  requests_.emplace_back();
  MPI_Isend(bytes.data(), int(bytes.size()), MPI_BYTE, 0, kBrickTag, setup_.comm, &requests_.back());
  ++sent_;
  stats_.transfer_s += MPI_Wtime() - t0;
}

void DirectSend::waitSends() {
  double t0 = MPI_Wtime();
  MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  requests_.clear();
  packed_.clear();
  stats_.transfer_s += MPI_Wtime() - t0;
}

bool DirectSend::takeMessage(bool wait) {
  double t0 = MPI_Wtime();
  MPI_Status st;
  int there = 0;
  if (wait) {
    MPI_Probe(MPI_ANY_SOURCE, kBrickTag, setup_.comm, &st);
    there = 1;
  } else {
    MPI_Iprobe(MPI_ANY_SOURCE, kBrickTag, setup_.comm, &there, &st);
  }
  if (!there) {
    stats_.transfer_s += MPI_Wtime() - t0;
    return false;
  }
  int bytes = 0;
  MPI_Get_count(&st, MPI_BYTE, &bytes);
  buffer_.resize(size_t(bytes));
  MPI_Recv(buffer_.data(), bytes, MPI_BYTE, st.MPI_SOURCE, kBrickTag, setup_.comm, MPI_STATUS_IGNORE);
  ++received_;
  stats_.transfer_s += MPI_Wtime() - t0;
  try {
    accept(unpackBrickImage(buffer_), st.MPI_SOURCE);
  } catch (const std::exception& e) {
    // Keep receiving: every rank's sends must complete before anyone can stop.
    if (error_.empty()) error_ = e.what();
  }
  return true;
}

void DirectSend::accept(BrickImage b, int source) {
  const int id = b.brick_id;
  if (id < 0 || size_t(id) >= seen_.size() || seen_[size_t(id)])
    throw std::runtime_error("direct send: unexpected brick id " + std::to_string(id) +
                             " from rank " + std::to_string(source));
  seen_[size_t(id)] = true;
  pending_[id] = std::move(b);
}

void DirectSend::blendReady() {
  if (!error_.empty()) return;
  double t0 = MPI_Wtime();
  const std::vector<int>& order = setup_.order->bricks;
  // A malformed image is reported once every message is in (finish()), never thrown from here:
  // the other ranks' sends must complete first.
  try {
    blendInOrder(order);
  } catch (const std::exception& e) {
    error_ = e.what();
  }
  stats_.composite_s += MPI_Wtime() - t0;
}

void DirectSend::blendInOrder(const std::vector<int>& order) {
  while (next_ < order.size()) {
    auto it = pending_.find(order[next_]);
    if (it == pending_.end()) break;
    // One image at a time in order: the same sequence of blends as blending all at the end.
    std::vector<const BrickImage*> one{&it->second};
    dirty_ = unionOf(dirty_, it->second.rect);
    if (opt_.precision == Precision::kFloat)
      blendBackToFront(one, frame_f_,
                       isProjection(opt_.projection) ? opt_.projection
                       : opt_.emission               ? WireFormat::Emission
                                                     : WireFormat::RGBA8);
    else
      blendBackToFront(one, frame_8_);
    pending_.erase(it);
    ++next_;
  }
}

void DirectSend::add(BrickImage image) {
  if (rank_ != 0) {
    if (opt_.overlap)
      send(image);
    else
      held_.push_back(std::move(image));
    return;
  }
  try {
    accept(std::move(image), 0);
  } catch (const std::exception& e) {
    if (error_.empty()) error_ = e.what();
  }
  progress();
}

void DirectSend::progress() {
  if (rank_ != 0 || !opt_.overlap) return;
  while (takeMessage(false)) {}
  blendReady();
}

ImageRGBA8 DirectSend::finish(CompositeStats& stats, ImageF* float_frame) {
  if (rank_ != 0) {
    for (const BrickImage& b : held_) send(b);
    held_.clear();
    waitSends();
    stats = stats_;
    return {};
  }
  while (received_ < expected_) {
    takeMessage(true);
    if (opt_.overlap) blendReady();
  }
  blendReady();
  if (error_.empty() && next_ != setup_.order->bricks.size())
    error_ = "direct send: " + std::to_string(setup_.order->bricks.size() - next_) +
             " brick image(s) missing after every rank sent its share";
  if (!error_.empty()) throw std::runtime_error(error_);
  ImageRGBA8 out;
  double t0 = MPI_Wtime();
  if (opt_.precision == Precision::kFloat) {
    // Only the touched rectangle can hold anything but transparent pixels. Emission: the RGBA8
    // frame (colour clamped to alpha) means nothing and the caller makes its own from the float
    // frame, so it stays transparent rather than costing a rounding pass over the frame.
    out = frameImage(frame_f_.width, frame_f_.height);
    chargePixels(PixelWork::Fill8, out.width * static_cast<long long>(out.height));
    if (isProjection(opt_.projection)) {  // the final values, coloured once (rows in place)
      if (!opt_.colour_projection) throw std::logic_error("direct send: a projection without its colouring");
      for (int y = dirty_.y; y < dirty_.y + dirty_.h; ++y)
        opt_.colour_projection(&frame_f_.px[(size_t(y) * frame_f_.width + size_t(dirty_.x)) * 4],
                               size_t(dirty_.w));
    }
    if (!(opt_.emission && float_frame)) {
      chargePixels(PixelWork::Round8, dirty_.area());
      // Rows of the touched rectangle, rounded on the pixel threads.
      const size_t rows_per_part = std::max<size_t>(1, (size_t(1) << 16) / size_t(std::max(dirty_.w, 1)));
      parallelFor(size_t(dirty_.h), rows_per_part, [&](size_t b, size_t e) {
        for (int y = dirty_.y + int(b); y < dirty_.y + int(e); ++y)
          toRGBA8(&frame_f_.px[(size_t(y) * frame_f_.width + size_t(dirty_.x)) * 4],
                  out.at(dirty_.x, y), size_t(dirty_.w));
      });
    }
    if (float_frame) *float_frame = frame_f_;
  } else {
    if (float_frame) *float_frame = toFloat(frame_8_);
    out = std::move(frame_8_);
  }
  stats_.composite_s += MPI_Wtime() - t0;
  stats = stats_;
  return out;
}

void DirectSend::abandon() {
  if (rank_ != 0) {
    // Stand-ins for the images this rank will not send, so rank 0 can count its messages.
    held_.clear();
    while (sent_ < setup_.brick_count) send(BrickImage{kNoImage, {}, {}});
    waitSends();
    return;
  }
  // Drain: every other rank sends exactly its brick count, real or stand-in.
  while (received_ < expected_) {
    MPI_Status st;
    MPI_Probe(MPI_ANY_SOURCE, kBrickTag, setup_.comm, &st);
    int bytes = 0;
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    buffer_.resize(size_t(bytes));
    MPI_Recv(buffer_.data(), bytes, MPI_BYTE, st.MPI_SOURCE, kBrickTag, setup_.comm, MPI_STATUS_IGNORE);
    ++received_;
  }
}

}  // namespace sortlast
