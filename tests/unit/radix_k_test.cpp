// Radix-k and binary-swap compositing (compositing/radix_k.h) with ranks as threads: the same frame
// as blending every brick image in order into one frame (what direct send does), for 1-8 ranks,
// k = 2-4, frames whose size is no multiple of the rank count, ranks that own nothing or only
// transparent bricks (and then send nothing).
#include "compositing/radix_k.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "compositing/blend.h"
#include "compositing/rle.h"
#include "tests/unit/thread_transport.h"

namespace sortlast {
namespace {

struct Case {
  int width, height, ranks, bricks;
  unsigned seed;
  bool disjoint = false;  // brick rectangles side by side, never overlapping
};

struct Outcome {
  ImageRGBA8 frame, want;
  ImageF frame_f, want_f;  // rank 0's unrounded frame (options.float_frame), blending in float
  std::vector<CompositeStats> stats;
  std::vector<bool> transparent;  // per rank: its own bricks show nothing
  std::vector<std::map<std::pair<int, int>, int>> sent;
};

// Random brick images (overlapping rectangles, transparent stretches, some wholly transparent or
// empty), dealt to ranks as runs of the brick order in a random rank order, composited by radix-k
// on threads; `want` blends them all in order into one frame.
Outcome run(const Case& c, int k, const CompositeOptions& options = {}) {
  std::mt19937 rng(c.seed);
  std::vector<BrickImage> bricks;
  for (int id = 0; id < c.bricks; ++id) {
    BrickImage b;
    b.brick_id = id;
    int x0 = int(rng() % unsigned(c.width)), y0 = int(rng() % unsigned(c.height));
    int x1 = x0 + int(rng() % unsigned(c.width - x0)) + 1,
        y1 = y0 + int(rng() % unsigned(c.height - y0)) + 1;
    if (c.disjoint) {  // column `id` of `bricks` columns
      x0 = c.width * id / c.bricks;
      x1 = c.width * (id + 1) / c.bricks;
    }
    int kind = int(rng() % 6);
    if (kind == 0) {  // nothing on screen
      bricks.push_back(b);
      continue;
    }
    b.rect = {x0, y0, x1 - x0, y1 - y0};
    std::vector<uint8_t> px(size_t(b.rect.area()) * 4, 0);
    for (size_t i = 0; kind != 1 && i < size_t(b.rect.area()); ++i) {  // kind 1: all transparent
      if (rng() % 3 == 0) continue;
      int a = rng() % 4 == 0 ? 255 : int(rng() % 256);
      px[4 * i + 3] = uint8_t(a);
      for (int ch = 0; ch < 3; ++ch) px[4 * i + ch] = uint8_t(rng() % unsigned(a + 1));
    }
    b.rle = rleEncode(px);
    bricks.push_back(b);
  }
  VisibilityOrder order;
  order.bricks.resize(size_t(c.bricks));
  std::iota(order.bricks.begin(), order.bricks.end(), 0);
  order.ranks.resize(size_t(c.ranks));
  std::iota(order.ranks.begin(), order.ranks.end(), 0);
  std::shuffle(order.ranks.begin(), order.ranks.end(), rng);
  // Cut the brick order into one run per rank (some empty), in rank order.
  std::vector<int> cuts = {0, c.bricks};
  for (int i = 1; i < c.ranks; ++i) cuts.push_back(int(rng() % unsigned(c.bricks + 1)));
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::vector<BrickImage>> mine(size_t(c.ranks));
  Outcome out;
  out.transparent.assign(size_t(c.ranks), true);
  for (int i = 0; i < c.ranks; ++i)
    for (int id = cuts[size_t(i)]; id < cuts[size_t(i) + 1]; ++id) {
      const int r = order.ranks[size_t(i)];
      mine[size_t(r)].push_back(bricks[size_t(id)]);
      std::vector<uint8_t> px(size_t(bricks[size_t(id)].rect.area()) * 4);
      rleDecode(bricks[size_t(id)].rle, size_t(bricks[size_t(id)].rect.area()), px);
      for (size_t p = 3; p < px.size(); p += 4)
        out.transparent[size_t(r)] = out.transparent[size_t(r)] && px[p] == 0;
    }
  // Each rank gets its bricks in a scrambled order: the compositor must order them itself.
  for (auto& m : mine) std::shuffle(m.begin(), m.end(), rng);

  ImageF want(c.width, c.height);  // what direct send does: blend in float, round once
  std::vector<const BrickImage*> all;
  for (const BrickImage& b : bricks) all.push_back(&b);
  blendBackToFront(all, want);
  out.want = toRGBA8(want);
  out.want_f = want;

  Mailbox box;
  box.sent.resize(size_t(c.ranks));
  out.stats.resize(size_t(c.ranks));
  std::vector<ImageRGBA8> frames(size_t(c.ranks));
  std::vector<std::string> errors(size_t(c.ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < c.ranks; ++r)
    threads.emplace_back([&, r] {
      try {
        ThreadTransport t(box, r, c.ranks);
        frames[size_t(r)] =
            radixKComposite(mine[size_t(r)], order, c.width, c.height, k, t, out.stats[size_t(r)],
                            options, r == 0 ? &out.frame_f : nullptr);
      } catch (const std::exception& e) {
        errors[size_t(r)] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  for (int r = 0; r < c.ranks; ++r) EXPECT_EQ(errors[size_t(r)], "") << "rank " << r;
  for (int r = 1; r < c.ranks; ++r)
    EXPECT_EQ(frames[size_t(r)].width, 0) << "rank " << r << " returned a frame";
  out.frame = std::move(frames[0]);
  out.sent = box.sent;
  return out;
}

int maxDiff(const ImageRGBA8& a, const ImageRGBA8& b, int& at) {
  int worst = 0;
  at = -1;
  for (size_t i = 0; i < a.px.size(); ++i) {
    int d = std::abs(int(a.px[i]) - int(b.px[i]));
    if (d > worst) {
      worst = d;
      at = int(i / 4);
    }
  }
  return worst;
}

TEST(RectImage, PartsRoundTripThroughTheWire) {
  RectImage img(Rect{10, 20, 7, 5});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // Visible pixels only in x 12..14, y 21..22; the rest transparent.
  for (int y = 21; y <= 22; ++y)
    for (int x = 12; x <= 14; ++x) {
      float* p = img.at(x, y);
      p[3] = u(rng);
      for (int c = 0; c < 3; ++c) p[c] = u(rng) * p[3];
    }
  EXPECT_EQ(activeRect(img, img.rect), (Rect{12, 21, 3, 2}));
  EXPECT_EQ(activeRect(img, Rect{14, 0, 100, 100}), (Rect{14, 21, 1, 2}));
  EXPECT_TRUE(activeRect(img, Rect{15, 0, 100, 100}).empty());
  RectImage c = crop(img, Rect{13, 0, 100, 22});
  EXPECT_EQ(c.rect, (Rect{13, 20, 4, 2}));
  EXPECT_EQ(c.at(14, 21)[3], img.at(14, 21)[3]);

  BrickImage part = encodePart(img, Rect{0, 0, 14, 100}, 42, WireFormat::RGBA16);
  EXPECT_EQ(part.brick_id, 42);
  EXPECT_EQ(part.rect, (Rect{12, 21, 2, 2}));  // only the active rectangle travels
  RectImage back = decodePart(unpackBrickImage(packBrickImage(part)), WireFormat::RGBA16, img.rect);
  ASSERT_EQ(back.rect, part.rect);
  for (int y = 21; y <= 22; ++y)
    for (int x = 12; x <= 13; ++x)
      for (int ch = 0; ch < 4; ++ch)
        EXPECT_NEAR(back.at(x, y)[ch], img.at(x, y)[ch], 0.5f / 65535.0f);

  BrickImage none = encodePart(img, Rect{0, 0, 12, 100}, 1, WireFormat::RGBA16);  // transparent
  EXPECT_TRUE(none.rect.empty());
  EXPECT_TRUE(none.rle.empty());
  EXPECT_TRUE(decodePart(none, WireFormat::RGBA16, img.rect).rect.empty());

  ImageRGBA8 frame(30, 30);
  pastePart(encodePart(img, img.rect, 0, WireFormat::RGBA8), frame);
  uint8_t want[4];
  toRGBA8(img.at(13, 22), want);
  for (int ch = 0; ch < 4; ++ch) EXPECT_EQ(frame.at(13, 22)[ch], want[ch]);
  EXPECT_EQ(frame.at(11, 22)[3], 0);
  ImageRGBA8 tiny(5, 5);
  EXPECT_THROW(pastePart(encodePart(img, img.rect, 0, WireFormat::RGBA8), tiny), RleError);
}

// Every case of a property: k = 2-4, 1-8 ranks, a few seeds; frame sizes are no multiple of the
// rank count. `check` gets the largest difference from blending in order, where it is, and how many
// of how many pixels differ at all.
template <class Check>
void forEveryCase(int max_bricks, bool disjoint, Check&& check, const CompositeOptions& options = {},
                  std::vector<Outcome>* outcomes = nullptr) {
  for (int k = 2; k <= 4; ++k)
    for (int ranks = 1; ranks <= 8; ++ranks)
      for (unsigned seed = 0; seed < 4; ++seed) {
        Case c{37 + int(seed) * 20,
               23 + int(seed) * 3,
               ranks,
               int(2 + (seed * 7 + unsigned(ranks)) % unsigned(max_bricks - 1)),
               100 * seed + unsigned(ranks),
               disjoint};
        SCOPED_TRACE("k " + std::to_string(k) + " ranks " + std::to_string(ranks) + " bricks " +
                     std::to_string(c.bricks) + " frame " + std::to_string(c.width) + "x" +
                     std::to_string(c.height) + " seed " + std::to_string(seed));
        Outcome o = run(c, k, options);
        EXPECT_EQ(o.frame.width, c.width);
        EXPECT_EQ(o.frame.height, c.height);
        if (o.frame.px.size() != o.want.px.size()) continue;
        int at = -1, worst = maxDiff(o.frame, o.want, at);
        long long n_differ = 0;
        for (size_t i = 0; i < o.frame.px.size(); i += 4)
          n_differ += !std::equal(&o.frame.px[i], &o.frame.px[i] + 4, &o.want.px[i]);
        check(worst,
              "worst pixel " + std::to_string(at % c.width) + "," + std::to_string(at / c.width),
              n_differ, (long long)o.frame.px.size() / 4);
        // A rank whose own bricks show nothing takes no part: it sends no byte.
        for (int r = 0; r < ranks; ++r)
          if (o.transparent[size_t(r)]) {
            EXPECT_EQ(o.stats[size_t(r)].bytes_sent, 0.0)
                << "rank " << r << " shows nothing but sent";
            EXPECT_TRUE(o.sent[size_t(r)].empty()) << "rank " << r << " shows nothing but sent";
          }
        if (outcomes) outcomes->push_back(std::move(o));
      }
}

double totalBytes(const std::vector<Outcome>& outcomes) {
  double bytes = 0;
  for (const Outcome& o : outcomes)
    for (const CompositeStats& s : o.stats) bytes += s.bytes_sent;
  return bytes;
}

// Up to 10 random semi-transparent layers over a pixel. "over" is associative, and partial
// composites travel at 16 bits: the frame rounds to the same RGBA8 values within 1, and almost
// every pixel exactly.
TEST(RadixK, SameFrameAsBlendingInOrder) {
  long long differ = 0, pixels = 0;
  forEveryCase(10, false,
               [&](int worst, const std::string& where, long long n_differ, long long n) {
                 EXPECT_LE(worst, 1) << where;
                 differ += n_differ;
                 pixels += n;
               });
  EXPECT_LT(double(differ), 1e-3 * double(pixels))
      << differ << " of " << pixels << " pixels differ";
}

// Where no two images overlap, no blend rounds at all: the frames are identical.
TEST(RadixK, DisjointImagesGiveTheIdenticalFrame) {
  forEveryCase(10, true, [](int worst, const std::string& where, long long, long long) {
    EXPECT_EQ(worst, 0) << where;
  });
}

// RLE off changes the bytes on the wire, never the frame.
TEST(RadixK, RleOffGivesTheSameFrameWithMoreBytes) {
  std::vector<Outcome> on, off;
  forEveryCase(10, false, [](int, const std::string&, long long, long long) {}, {}, &on);
  CompositeOptions raw;
  raw.rle = false;
  forEveryCase(10, false, [](int, const std::string&, long long, long long) {}, raw, &off);
  ASSERT_EQ(on.size(), off.size());
  for (size_t i = 0; i < on.size(); ++i) EXPECT_EQ(on[i].frame.px, off[i].frame.px) << "case " << i;
  EXPECT_GT(totalBytes(off), totalBytes(on));
}

// The paper's RGBA8 partials: half a step of rounding per round, fewer bytes than 16-bit ones.
TEST(RadixK, Rgba8PartialsStayWithinAFewStepsWithFewerBytes) {
  std::vector<Outcome> f, b8;
  forEveryCase(10, false, [](int, const std::string&, long long, long long) {}, {}, &f);
  CompositeOptions eight;
  eight.precision = Precision::kRgba8;
  int worst_all = 0;
  forEveryCase(10, false,
               [&](int worst, const std::string& where, long long, long long) {
                 EXPECT_LE(worst, 3) << where;
                 worst_all = std::max(worst_all, worst);
               },
               eight, &b8);
  EXPECT_GE(worst_all, 1) << "RGBA8 partials never rounded: the option does nothing";
  // Both totals hold the gather's raw RGBA8 final parts, the same bytes either way.
  EXPECT_LT(totalBytes(b8), 0.9 * totalBytes(f));
}

// Asked for the unrounded frame, rank 0 gets the float composite (16-bit parts) and its rounding.
TEST(RadixK, FloatFrameIsTheUnroundedComposite) {
  CompositeOptions opt;
  opt.float_frame = true;
  std::vector<Outcome> all;
  forEveryCase(6, false, [](int worst, const std::string& where, long long, long long) {
    EXPECT_LE(worst, 1) << where;
  }, opt, &all);
  for (const Outcome& o : all) {
    ASSERT_EQ(o.frame_f.px.size(), o.want_f.px.size());
    float worst = 0;
    for (size_t i = 0; i < o.frame_f.px.size(); ++i)
      worst = std::max(worst, std::abs(o.frame_f.px[i] - o.want_f.px[i]));
    EXPECT_LT(worst, 8.0f / 65535.0f);
    EXPECT_EQ(toRGBA8(o.frame_f).px, o.frame.px);
  }
}

// A random float image of `r`: transparent stretches, pixels that round to nothing, and (for
// Emission) light without opacity and colour above 1.
RectImage randomImage(const Rect& r, std::mt19937& rng, bool emission) {
  RectImage img(r);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t i = 0; i < size_t(r.area()); ++i) {
    float* p = &img.px[4 * i];
    const int kind = int(rng() % 6);
    if (kind == 0) continue;                         // transparent
    p[3] = kind == 1 ? u(rng) * 1e-4f : u(rng);      // kind 1: rounds to alpha 0
    for (int c = 0; c < 3; ++c) p[c] = u(rng) * p[3];
    if (emission && kind == 2) p[3] = 0.0f;          // light alone
    if (emission && kind == 3) p[0] = 3.0f + u(rng);  // brighter than white
  }
  return img;
}

// The raw final part is, byte for byte, what rank 0 used to get by decoding the RLE'd part into
// the frame: RGBA8 parts as pastePart puts them, 16-bit and Emission parts as decodePart gives them
// (and their RGBA8 rounding as toRGBA8 of that float frame); zero where the image is not.
TEST(RectImage, RawFinalPartIsTheDecodedPartBitForBit) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 60; ++trial) {
    const Rect bound{int(rng() % 9), int(rng() % 7), 1 + int(rng() % 23), 1 + int(rng() % 17)};
    const int x0 = bound.x + int(rng() % unsigned(bound.w)), y0 = bound.y + int(rng() % unsigned(bound.h));
    const Rect inner{x0, y0, 1 + int(rng() % unsigned(bound.x + bound.w - x0)),
                     1 + int(rng() % unsigned(bound.y + bound.h - y0))};
    for (WireFormat f : {WireFormat::RGBA8, WireFormat::RGBA16, WireFormat::Emission}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " format " + std::to_string(int(f)));
      const RectImage img = trial % 10 == 9 ? RectImage{} : randomImage(inner, rng, f == WireFormat::Emission);
      const RawPart raw = rawFinalPart(img, bound, f);
      ASSERT_EQ(raw.rect, bound);
      ASSERT_EQ(raw.rgba8.size(), size_t(bound.area()) * 4);
      const int W = bound.x + bound.w, H = bound.y + bound.h;
      const BrickImage wire = unpackBrickImage(packBrickImage(encodePart(img, bound, 0, f)));
      ImageRGBA8 old8(W, H);
      if (f == WireFormat::RGBA8) {
        pastePart(wire, old8);
        EXPECT_TRUE(raw.exact.empty());
      } else {
        ImageF oldf(W, H);
        pastePart(decodePart(wire, f, bound), oldf);
        old8 = toRGBA8(oldf);
        ASSERT_EQ(raw.exact.size(), size_t(bound.area()) * 16);
        for (int y = 0; y < bound.h; ++y)
          EXPECT_EQ(0, std::memcmp(&raw.exact[size_t(y) * bound.w * 16],
                                   &oldf.px[(size_t(bound.y + y) * W + size_t(bound.x)) * 4],
                                   size_t(bound.w) * 16))
              << "float row " << y;
      }
      for (int y = 0; y < bound.h; ++y)
        EXPECT_EQ(0, std::memcmp(&raw.rgba8[size_t(y) * bound.w * 4], old8.at(bound.x, bound.y + y),
                                 size_t(bound.w) * 4))
            << "RGBA8 row " << y;
    }
  }
  RectImage outside(Rect{0, 0, 4, 4});
  EXPECT_THROW(rawFinalPart(outside, Rect{1, 0, 4, 4}, WireFormat::RGBA8), std::logic_error);
  EXPECT_TRUE(rawFinalPart(outside, Rect{}, WireFormat::RGBA8).rgba8.empty());
}

// Rank counts past 8 and odd, radices that do not divide them (folds), k up to 5: the frame is the
// in-order blend within a step, and the unrounded one that frame's rounding.
TEST(RadixK, OddRankCountsGatherTheWholeFrame) {
  for (int k : {3, 5})
    for (int ranks : {9, 11, 13})
      for (bool exact : {false, true}) {
        SCOPED_TRACE("k " + std::to_string(k) + " ranks " + std::to_string(ranks) +
                     (exact ? " float frame" : ""));
        CompositeOptions opt;
        opt.float_frame = exact;
        const Outcome o = run(Case{61, 29, ranks, 17, 7u * unsigned(ranks + k)}, k, opt);
        ASSERT_EQ(o.frame.px.size(), o.want.px.size());
        int at = -1;
        EXPECT_LE(maxDiff(o.frame, o.want, at), 1) << "pixel " << at;
        if (exact) EXPECT_EQ(toRGBA8(o.frame_f).px, o.frame.px);
      }
}

// A transport that cuts the last 4 bytes off every final part a rank sends to rank 0.
class TruncatingTransport final : public Transport {
 public:
  explicit TruncatingTransport(ThreadTransport& t) : t_(t) {}
  int rank() const override { return t_.rank(); }
  int size() const override { return t_.size(); }
  void send(int to, int tag, std::vector<uint8_t> bytes) override {
    if (to == 0 && tag == 399 && bytes.size() >= 4) bytes.resize(bytes.size() - 4);
    t_.send(to, tag, std::move(bytes));
  }
  std::vector<uint8_t> receive(int from, int tag) override { return t_.receive(from, tag); }
  void receivePlaced(const std::vector<PlacedReceive>& parts) override { t_.receivePlaced(parts); }
  void finishSends() override { t_.finishSends(); }
  std::vector<int> allgather(const std::vector<int>& mine) override { return t_.allgather(mine); }

 private:
  ThreadTransport& t_;
};

// A final part of the wrong size is an error on rank 0 that names its sender, not a torn frame.
TEST(RadixK, MalformedFinalPartIsAClearError) {
  const int ranks = 3;
  VisibilityOrder order;
  order.bricks = {0, 1, 2};
  order.ranks = {0, 1, 2};
  std::vector<uint8_t> px(16 * 16 * 4, 200);
  Mailbox box;
  box.sent.resize(size_t(ranks));
  std::vector<std::string> errors(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      try {
        ThreadTransport inner(box, r, ranks);
        TruncatingTransport t(inner);
        BrickImage b;
        b.brick_id = r;
        b.rect = {0, 0, 16, 16};
        b.rle = rleEncode(px);
        CompositeStats stats;
        radixKComposite({b}, order, 16, 16, 3, t, stats);
      } catch (const std::exception& e) {
        errors[size_t(r)] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_NE(errors[0].find("placed receive: the message from rank"), std::string::npos) << errors[0];
  EXPECT_EQ(errors[1], "");
  EXPECT_EQ(errors[2], "");
}

}  // namespace
}  // namespace sortlast
