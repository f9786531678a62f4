#include "compositing/radix_k.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>

#include "compositing/blend.h"
#include "compositing/mpi_transport.h"
#include "compositing/pixel_cost.h"
#include "compositing/projection_pixels.h"
#include "compositing/radix_k_plan.h"

namespace sortlast {

namespace {

// Round t: kRoundTag + t. The gather's parts: RGBA8 on kGatherTag, the float frame's on
// kGatherExactTag.
constexpr int kFoldTag = 301, kRoundTag = 310, kGatherTag = 399, kGatherExactTag = 398;

using Clock = std::chrono::steady_clock;

// Adds the seconds since the last lap to one of two totals.
class Stopwatch {
 public:
  explicit Stopwatch(CompositeStats& stats) : stats_(stats) {}
  void lapTransfer() { stats_.transfer_s += lap(); }
  void lapComposite() { stats_.composite_s += lap(); }

 private:
  double lap() {
    auto now = Clock::now();
    double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }
  CompositeStats& stats_;
  Clock::time_point last_ = Clock::now();
};

class Exchange {
 public:
  Exchange(Transport& t, CompositeStats& stats, Stopwatch& watch)
      : t_(t), stats_(stats), watch_(watch) {}
  void send(int to, int tag, const BrickImage& part) {
    std::vector<uint8_t> bytes = packBrickImage(part);
    stats_.bytes_sent += double(bytes.size());
    watch_.lapComposite();
    t_.send(to, tag, std::move(bytes));
    watch_.lapTransfer();
  }
  BrickImage receiveEncoded(int from, int tag) {
    watch_.lapComposite();
    std::vector<uint8_t> bytes = t_.receive(from, tag);
    watch_.lapTransfer();
    return unpackBrickImage(bytes);
  }
  // Bytes that need no header (the receiver knows their shape).
  void sendRaw(int to, int tag, std::vector<uint8_t> bytes) {
    stats_.bytes_sent += double(bytes.size());
    watch_.lapComposite();
    t_.send(to, tag, std::move(bytes));
    watch_.lapTransfer();
  }
  void receivePlaced(const std::vector<PlacedReceive>& parts) {
    watch_.lapComposite();
    t_.receivePlaced(parts);
    watch_.lapTransfer();
  }
  RectImage receive(int from, int tag, WireFormat format, const Rect& within) {
    return decodePart(receiveEncoded(from, tag), format, within);
  }
  void finish() {
    watch_.lapComposite();
    t_.finishSends();
    watch_.lapTransfer();
  }

 private:
  Transport& t_;
  CompositeStats& stats_;
  Stopwatch& watch_;
};

// This rank's bricks, far to near, blended into one image shrunk to its active rectangle.
RectImage blendOwnBricks(const std::vector<BrickImage>& mine, const std::vector<int>& brick_order,
                         WireFormat format) {
  std::map<int, const BrickImage*> by_id;
  for (const BrickImage& b : mine) by_id[b.brick_id] = &b;
  std::vector<const BrickImage*> seq;
  for (int id : brick_order) {
    auto it = by_id.find(id);
    if (it != by_id.end()) seq.push_back(it->second);
  }
  if (seq.size() != mine.size() || by_id.size() != mine.size())
    throw std::runtime_error("radix-k: this rank's brick ids are not in the visibility order");
  RectImage img = blendBackToFront(seq, format);
  Rect active = activeRect(img, img.rect);
  return active == img.rect ? img : crop(img, active);
}

}  // namespace

RadixK::RadixK(int k, const CompositeOptions& options) : k_(k), opt_(options) {
  if (k < 2) throw std::invalid_argument("radix-k: k must be >= 2, got " + std::to_string(k));
}

void RadixK::begin(const FrameSetup& setup) {
  setup_ = setup;
  mine_.clear();
}

ImageRGBA8 RadixK::finish(CompositeStats& stats, ImageF* float_frame) {
  MpiTransport transport(setup_.comm);
  stats = {};
  return radixKComposite(std::move(mine_), *setup_.order, setup_.width, setup_.height, k_,
                         transport, stats, opt_, float_frame);
}

ImageRGBA8 radixKComposite(std::vector<BrickImage> mine, const VisibilityOrder& order, int width,
                           int height, int k, Transport& transport, CompositeStats& stats,
                           const CompositeOptions& options, ImageF* float_frame) {
  // Partial composites travel at 16 bits unless the scene asks for the paper's RGBA8.
  const bool projection = isProjection(options.projection);
  const WireFormat partials = projection                            ? options.projection
                              : options.emission                      ? WireFormat::Emission
                              : options.precision == Precision::kRgba8 ? WireFormat::RGBA8
                                                                      : WireFormat::RGBA16;
  Stopwatch watch(stats);
  Exchange ex(transport, stats, watch);
  const int rank = transport.rank(), ranks = transport.size();
  if (int(order.ranks.size()) != ranks)
    throw std::invalid_argument("radix-k: the rank order holds " +
                                std::to_string(order.ranks.size()) + " ranks, the communicator " +
                                std::to_string(ranks));

  // 1. Own bricks, then everyone's content rectangle.
  // In the visibility order: over needs it, and so do the bounded projections' over-like
  // operator (compositing/projection_pixels.h); for the order-free ones it does not matter.
  RectImage image = blendOwnBricks(mine, order.bricks,
                                   projection ? options.projection
                                              : options.emission ? WireFormat::Emission : WireFormat::RGBA8);
  const Rect& c = image.rect;
  watch.lapComposite();
  std::vector<int> rects = transport.allgather({c.x, c.y, c.w, c.h});
  watch.lapTransfer();

  // 2. The participants: ranks with something to show, far to near.
  std::vector<Rect> rect_of_rank(size_t(ranks), Rect{});
  for (int r = 0; r < ranks; ++r)
    rect_of_rank[size_t(r)] = Rect{rects[4 * size_t(r)], rects[4 * size_t(r) + 1],
                                   rects[4 * size_t(r) + 2], rects[4 * size_t(r) + 3]};
  std::vector<int> position_of;
  const RadixKPlan plan = makeRadixKPlan(order.ranks, rect_of_rank, k, &position_of);
  const int pos = position_of[size_t(rank)];
  const RadixKSchedule& s = plan.schedule;

  // Rank 0's frame, zero-filled now rather than after the rounds: the gather then receives the
  // final parts straight into it the moment the rounds end, and the fill (0.14 ns a pixel here,
  // 9.5 ms at 8192^2: results/scale/rates.csv) takes rank 0's idle time if it shows nothing, and
  // otherwise the same time on its path as it would at the end.
  const WireFormat finals = options.emission      ? WireFormat::Emission
                            : options.float_frame ? WireFormat::RGBA16
                                                  : WireFormat::RGBA8;
  const bool exact_frame = options.float_frame || options.emission;  // emission: no RGBA8 parts
  ImageRGBA8 frame;
  ImageF exact;
  if (rank == 0) {
    frame = ImageRGBA8(width, height);
    chargePixels(PixelWork::Fill8, frame.width * static_cast<long long>(frame.height));
    if (exact_frame) exact = ImageF(width, height);
  }

  // 3. Folds: the nearer of each pair sends its whole image to the farther.
  int unit = -1;  // the unit this rank carries, if any
  if (pos >= 0 && pos < 2 * s.folds) {
    if (pos % 2 == 1) {
      ex.send(plan.rank_at[size_t(pos - 1)], kFoldTag,
              encodePart(image, image.rect, pos, partials, options.rle));
      image = {};
    } else {
      RectImage front = ex.receive(plan.rank_at[size_t(pos + 1)], kFoldTag, partials,
                                    plan.content[size_t(pos + 1)]);
      image = blendBackToFront(std::vector<const RectImage*>{&image, &front}, partials);
      unit = pos / 2;
    }
  } else if (pos >= 0) {
    unit = pos - s.folds;
  }

  // 4. Rounds: split the group's region, send each partner its part, composite my part.
  for (int t = 0; t < s.rounds() && unit >= 0; ++t) {
    const std::vector<int> group = s.group(t, unit);
    const int me = s.digit(t, unit);
    const std::vector<Rect> parts = splitRect(s.region(t, unit, plan.whole), int(group.size()));
    const Rect my_bound = plan.bound(t, unit);
    for (size_t m = 0; m < group.size(); ++m)
      if (int(m) != me && !intersect(my_bound, parts[m]).empty())
        ex.send(plan.carrier(group[m]), kRoundTag + t,
                encodePart(image, parts[m], unit, partials, options.rle));
    std::vector<RectImage> received(group.size());
    std::vector<const RectImage*> layers;
    for (size_t m = 0; m < group.size(); ++m) {
      if (int(m) == me) {
        received[m] = crop(image, parts[size_t(me)]);
      } else if (!intersect(plan.bound(t, group[m]), parts[size_t(me)]).empty()) {
        received[m] = ex.receive(plan.carrier(group[m]), kRoundTag + t, partials,
                                 parts[size_t(me)]);
      }
      layers.push_back(&received[m]);
    }
    image = blendBackToFront(layers, partials);
    ex.finish();
  }
  // A projection's final values, coloured where the final part is made (then rounded as any).
  if (projection && unit >= 0 && !image.rect.empty()) {
    if (!options.colour_projection) throw std::logic_error("radix-k: a projection without its colouring");
    options.colour_projection(image.px.data(), size_t(image.rect.area()));
  }

  markGatherStart();
  // 5. Every unit's final part to rank 0. Rank 0 knows every part's rectangle from the plan (the
  // unit's bound after the last round: the parts tile the content's bounding rectangle), so each
  // unit rounds its part where it is (RGBA8; or through the float frame's wire format and back, as
  // decoding would) and sends it raw, and rank 0 receives every part straight into its rows of the
  // frame, decoding nothing: at 8192^2 on 4,096 simulated hosts the old serial decode (and zero
  // fill) of every final pixel was 42 ms of 0.127 s. Raw parts cost more bytes than RLE'd active
  // rectangles (the bound's transparent corners) on rank 0's link: docs/smpi.md has both measured.
  const int last = s.rounds();
  if (unit >= 0 && rank != 0) {
    const Rect bound = plan.bound(last, unit);
    if (!bound.empty()) {
      RawPart part = rawFinalPart(image, bound, finals);
      image = {};
      ex.sendRaw(0, kGatherTag, std::move(part.rgba8));
      if (exact_frame) ex.sendRaw(0, kGatherExactTag, std::move(part.exact));
    }
  }
  if (rank == 0) {
    const std::vector<Rect> bounds = std::move(plan.everyRound().bound[size_t(last)]);
    const size_t row8 = size_t(width) * 4, row_exact = size_t(width) * 16;
    std::vector<PlacedReceive> parts;
    for (int u = 0; u < s.units(); ++u) {
      const Rect& b = bounds[size_t(u)];
      if (b.empty()) continue;
      if (!contains(Rect{0, 0, width, height}, b))
        throw std::runtime_error("radix-k: a final part lies outside the frame");
      uint8_t* at8 = frame.at(b.x, b.y);
      uint8_t* at_exact =
          exact_frame ? reinterpret_cast<uint8_t*>(&exact.px[(size_t(b.y) * width + size_t(b.x)) * 4])
                      : nullptr;
      if (plan.carrier(u) != 0) {
        parts.push_back({plan.carrier(u), kGatherTag, at8, row8, b.w * 4, b.h});
        if (exact_frame)
          parts.push_back({plan.carrier(u), kGatherExactTag, at_exact, row_exact, b.w * 16, b.h});
        continue;
      }
      // Rank 0's own part: the same bytes, copied in as a receive would put them.
      const RawPart own = rawFinalPart(image, b, finals);
      chargePixels(PixelWork::Place, b.area() * (exact_frame ? 5LL : 1LL));
      for (int y = 0; y < b.h; ++y) {
        std::memcpy(at8 + size_t(y) * row8, &own.rgba8[size_t(y) * b.w * 4], size_t(b.w) * 4);
        if (exact_frame)
          std::memcpy(at_exact + size_t(y) * row_exact, &own.exact[size_t(y) * b.w * 16],
                      size_t(b.w) * 16);
      }
    }
    ex.receivePlaced(parts);
    if (float_frame) *float_frame = std::move(exact);
  }
  ex.finish();
  watch.lapComposite();
  return frame;
}

}  // namespace sortlast
