// RLE codec (compositing/rle.h): round trips, the exact Fig. 7 byte format, runs longer than
// 2^24 - 1, and rejection of malformed streams without writing outside the output.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "compositing/rle.h"

namespace sortlast {
namespace {

// A valid premultiplied RGBA8 image: transparent pixels are all zero (A = 0 implies RGB = 0), and
// transparent runs and visible stretches of random lengths alternate.
std::vector<uint8_t> randomImage(size_t n, std::mt19937& rng) {
  std::vector<uint8_t> px(4 * n, 0);
  std::uniform_int_distribution<int> byte(0, 255), alpha(1, 255), len(1, 40), coin(0, 1);
  size_t i = 0;
  while (i < n) {
    size_t run = std::min(n - i, size_t(len(rng)));
    bool visible = coin(rng);
    for (size_t k = i; k < i + run; ++k)
      if (visible) {
        uint8_t a = uint8_t(alpha(rng));
        for (int c = 0; c < 3; ++c) px[4 * k + c] = uint8_t(byte(rng) % (a + 1));
        px[4 * k + 3] = a;
      }
    i += run;
  }
  return px;
}

std::vector<uint8_t> decode(const std::vector<uint8_t>& stream, size_t n) {
  std::vector<uint8_t> out(4 * n, 0xAB);  // not zero: transparent runs must be written
  rleDecode(stream, n, out);
  return out;
}

uint32_t marker(const std::vector<uint8_t>& s, size_t byte) {
  return uint32_t(s[byte]) | uint32_t(s[byte + 1]) << 8 | uint32_t(s[byte + 2]) << 16;
}

TEST(Rle, RandomImagesRoundTrip) {
  std::mt19937 rng(1234);
  for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(3), size_t(17), size_t(256),
                   size_t(1000), size_t(65537)}) {
    for (int trial = 0; trial < 5; ++trial) {
      auto px = randomImage(n, rng);
      auto enc = rleEncode(px);
      EXPECT_EQ(enc.size() % 4, 0u);
      EXPECT_LE(enc.size(), px.size());  // never larger than the raw image
      EXPECT_EQ(decode(enc, n), px) << "n = " << n << ", trial " << trial;
    }
  }
}

TEST(Rle, EncodeAppendsToExistingOutput) {
  std::mt19937 rng(7);
  auto px = randomImage(300, rng);
  std::vector<uint8_t> out = {9, 9, 9, 9};
  rleEncode(px, out);
  ASSERT_GE(out.size(), 4u);
  EXPECT_EQ(std::vector<uint8_t>(out.begin(), out.begin() + 4), std::vector<uint8_t>({9, 9, 9, 9}));
  EXPECT_EQ(std::vector<uint8_t>(out.begin() + 4, out.end()), rleEncode(px));
}

TEST(Rle, SinglePixelImages) {
  std::vector<uint8_t> transparent = {0, 0, 0, 0}, visible = {1, 2, 3, 4};
  EXPECT_EQ(rleEncode(transparent), std::vector<uint8_t>({1, 0, 0, 0}));
  EXPECT_EQ(rleEncode(visible), visible);
  EXPECT_EQ(decode(rleEncode(transparent), 1), transparent);
  EXPECT_EQ(decode(rleEncode(visible), 1), visible);
  EXPECT_TRUE(rleEncode(std::vector<uint8_t>{}).empty());
  EXPECT_TRUE(decode({}, 0).empty());
}

TEST(Rle, AllTransparentIsOneMarker) {
  const size_t n = 5000;
  std::vector<uint8_t> px(4 * n, 0);
  auto enc = rleEncode(px);
  ASSERT_EQ(enc.size(), 4u);
  EXPECT_EQ(marker(enc, 0), n);
  EXPECT_EQ(enc[3], 0);
  EXPECT_EQ(decode(enc, n), px);
}

TEST(Rle, NoneTransparentIsCopiedVerbatim) {
  std::mt19937 rng(99);
  const size_t n = 4097;
  std::vector<uint8_t> px(4 * n);
  for (size_t i = 0; i < n; ++i) {
    uint8_t a = uint8_t(1 + rng() % 255);
    for (int c = 0; c < 3; ++c) px[4 * i + c] = uint8_t(rng() % (a + 1));
    px[4 * i + 3] = a;
  }
  auto enc = rleEncode(px);
  EXPECT_EQ(enc, px);
  EXPECT_EQ(decode(enc, n), px);
}

// The paper's Fig. 7: a run of N transparent pixels is one pixel (N as 24-bit little endian, 0);
// visible pixels are copied.
TEST(Rle, Fig7ByteFormat) {
  std::vector<uint8_t> px;
  for (int i = 0; i < 3; ++i) px.insert(px.end(), {0, 0, 0, 0});
  px.insert(px.end(), {10, 20, 30, 40});
  for (int i = 0; i < 300; ++i) px.insert(px.end(), {0, 0, 0, 0});
  px.insert(px.end(), {5, 6, 7, 8});
  px.insert(px.end(), {1, 1, 1, 255});
  auto enc = rleEncode(px);
  EXPECT_EQ(enc, std::vector<uint8_t>({3, 0, 0, 0, 10, 20, 30, 40, 44, 1, 0, 0, 5, 6, 7, 8, 1, 1, 1, 255}));
  EXPECT_EQ(decode(enc, px.size() / 4), px);

  // Hand-written streams decode to the same pixels.
  std::vector<uint8_t> three = {3, 0, 0, 0}, three_hundred = {44, 1, 0, 0};
  EXPECT_EQ(decode(three, 3), std::vector<uint8_t>(12, 0));
  EXPECT_EQ(decode(three_hundred, 300), std::vector<uint8_t>(1200, 0));
  EXPECT_EQ(rleEncode(std::vector<uint8_t>(1200, 0)), three_hundred);
  // A 3-byte count: 0x012345 pixels.
  std::vector<uint8_t> big(4 * size_t(0x012345), 0);
  EXPECT_EQ(rleEncode(big), std::vector<uint8_t>({0x45, 0x23, 0x01, 0}));
}

TEST(Rle, RunLongerThanMaxIsSplit) {
  static_assert(kMaxRun == (1u << 24) - 1);
  const size_t n = (size_t(1) << 24) + 5;
  std::vector<uint8_t> px(4 * n, 0);
  auto enc = rleEncode(px);
  ASSERT_EQ(enc.size(), 8u);
  EXPECT_EQ(marker(enc, 0), kMaxRun);
  EXPECT_EQ(enc[3], 0);
  EXPECT_EQ(marker(enc, 4), 6u);
  EXPECT_EQ(enc[7], 0);
  std::vector<uint8_t> out(4 * n, 0xCD);
  rleDecode(enc, n, out);
  EXPECT_TRUE(out == px);

  // A visible pixel just past 2^24: the run before it (2^24 + 1 pixels) is split, the run after it
  // (3 pixels) follows.
  const size_t vis = (size_t(1) << 24) + 1;
  px[4 * vis + 0] = 7, px[4 * vis + 1] = 8, px[4 * vis + 2] = 9, px[4 * vis + 3] = 200;
  enc = rleEncode(px);
  ASSERT_EQ(enc.size(), 16u);
  EXPECT_EQ(marker(enc, 0), kMaxRun);
  EXPECT_EQ(enc[3], 0);
  EXPECT_EQ(marker(enc, 4), 2u);
  EXPECT_EQ(enc[7], 0);
  EXPECT_EQ(std::vector<uint8_t>(enc.begin() + 8, enc.begin() + 12), std::vector<uint8_t>({7, 8, 9, 200}));
  EXPECT_EQ(marker(enc, 12), 3u);
  EXPECT_EQ(enc[15], 0);
  std::fill(out.begin(), out.end(), uint8_t(0xCD));
  rleDecode(enc, n, out);
  EXPECT_TRUE(out == px);
}

// Decodes into a span of exactly 4 * pixel_count bytes inside a larger buffer whose guard bytes
// must stay untouched, whether decoding succeeds or throws.
class GuardedDecode {
 public:
  explicit GuardedDecode(size_t n) : n_(n), buf_(4 * n + 2 * kGuard, kFill) {}
  void run(const std::vector<uint8_t>& stream) {
    rleDecode(stream, n_, std::span<uint8_t>(buf_.data() + kGuard, 4 * n_));
  }
  bool guardsIntact() const {
    for (size_t i = 0; i < kGuard; ++i)
      if (buf_[i] != kFill || buf_[buf_.size() - 1 - i] != kFill) return false;
    return true;
  }
  std::vector<uint8_t> pixels() const {
    return std::vector<uint8_t>(buf_.begin() + kGuard, buf_.end() - kGuard);
  }

 private:
  static constexpr size_t kGuard = 64;
  static constexpr uint8_t kFill = 0x5A;
  size_t n_;
  std::vector<uint8_t> buf_;
};

TEST(Rle, ExactOutputSpanIsEnough) {
  std::mt19937 rng(5);
  for (size_t n : {size_t(1), size_t(9), size_t(333)}) {
    auto px = randomImage(n, rng);
    GuardedDecode g(n);
    g.run(rleEncode(px));
    EXPECT_EQ(g.pixels(), px);
    EXPECT_TRUE(g.guardsIntact());
  }
}

TEST(Rle, RejectsLengthNotMultipleOf4) {
  for (std::vector<uint8_t> s : {std::vector<uint8_t>{1}, std::vector<uint8_t>{2, 0, 0},
                                 std::vector<uint8_t>{2, 0, 0, 0, 1}}) {
    GuardedDecode g(2);
    EXPECT_THROW(g.run(s), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  // A 5-byte stream whose memory continues with what would be a valid marker: a decoder that did
  // not check the length would read past the stream and accept it.
  std::vector<uint8_t> backing = {1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<uint8_t> out(8, 0);
  EXPECT_THROW(rleDecode(std::span<const uint8_t>(backing.data(), 5), 2, out), RleError);
}

TEST(Rle, RejectsZeroLengthRun) {
  GuardedDecode g(4);
  EXPECT_THROW(g.run({0, 0, 0, 0, 4, 0, 0, 0}), RleError);
  EXPECT_TRUE(g.guardsIntact());
  GuardedDecode g2(4);
  EXPECT_THROW(g2.run({3, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1}), RleError);
  EXPECT_TRUE(g2.guardsIntact());
}

TEST(Rle, RejectsRunThatOverflowsTheImage) {
  {
    GuardedDecode g(4);
    EXPECT_THROW(g.run({5, 0, 0, 0}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(4);  // 2 visible then a run of 3: one too many
    EXPECT_THROW(g.run({1, 1, 1, 1, 2, 2, 2, 2, 3, 0, 0, 0}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(4);  // a huge run (2^24 - 1)
    EXPECT_THROW(g.run({0xff, 0xff, 0xff, 0}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(0);  // nothing fits in an empty image
    EXPECT_THROW(g.run({1, 0, 0, 0}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
}

TEST(Rle, RejectsTooFewPixels) {
  {
    GuardedDecode g(5);
    EXPECT_THROW(g.run({4, 0, 0, 0}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(3);
    EXPECT_THROW(g.run({1, 2, 3, 4, 5, 6, 7, 8}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(1);
    EXPECT_THROW(g.run({}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
}

TEST(Rle, RejectsTooManyVisiblePixels) {
  {
    GuardedDecode g(2);
    EXPECT_THROW(g.run({1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(3);  // the run fills the image, then a visible pixel follows
    EXPECT_THROW(g.run({3, 0, 0, 0, 9, 9, 9, 9}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
  {
    GuardedDecode g(0);
    EXPECT_THROW(g.run({9, 9, 9, 9}), RleError);
    EXPECT_TRUE(g.guardsIntact());
  }
}

TEST(Rle, RejectsOutputSpanTooSmall) {
  std::vector<uint8_t> out(4 * 3 - 1, 0);
  EXPECT_THROW(rleDecode(std::vector<uint8_t>{3, 0, 0, 0}, 3, out), RleError);
}

// RGBA16 pixels (partial composites): 8 bytes each, alpha in the last two; a pixel is transparent
// only when both alpha bytes are 0, and a run marker is N in 24 bits then five zero bytes.
TEST(Rle, Rgba16PixelsRoundTripAndFormat) {
  std::vector<uint8_t> px = {
      0, 0, 0, 0, 0, 0, 0, 0,  // transparent
      0, 0, 0, 0, 0, 0, 0, 0,  // transparent
      1, 0, 0, 0, 0, 0, 1, 0,  // alpha 1: visible though its high byte is 0
      0, 0, 0, 0, 0, 0, 0, 1,  // alpha 256: visible though its low byte is 0
      0, 0, 0, 0, 0, 0, 0, 0,  // transparent
  };
  std::vector<uint8_t> enc = rleEncode(px, 8);
  EXPECT_EQ(enc, (std::vector<uint8_t>{2, 0, 0, 0, 0, 0, 0, 0,    // run of 2
                                       1, 0, 0, 0, 0, 0, 1, 0,    // copied
                                       0, 0, 0, 0, 0, 0, 0, 1,    // copied
                                       1, 0, 0, 0, 0, 0, 0, 0}));  // run of 1
  std::vector<uint8_t> out(px.size(), 0xAB);
  rleDecode(enc, 5, out, 8);
  EXPECT_EQ(out, px);
  // Random images widened to 16 bits (v -> 257 v) round-trip too.
  std::mt19937 rng(99);
  for (size_t n : {1, 2, 17, 500}) {
    std::vector<uint8_t> img;
    for (uint8_t v : randomImage(n, rng)) img.insert(img.end(), {v, v});
    std::vector<uint8_t> back(img.size(), 0xAB);
    rleDecode(rleEncode(img, 8), n, back, 8);
    EXPECT_EQ(back, img) << n;
  }
  std::vector<uint8_t> small(7);
  EXPECT_THROW(rleDecode(std::vector<uint8_t>(12, 1), 1, small, 8), RleError);  // not a multiple of 8
  EXPECT_THROW(rleEncode(px, 3), std::invalid_argument);
}

}  // namespace
// max_run = 1: RLE off in the same format; the stream is exactly the raw pixels' length.
TEST(Rle, RunsOfOneKeepTheFormatAndTheRawLength) {
  std::vector<uint8_t> px(4 * 50, 0);
  for (int i = 10; i < 14; ++i) px[4 * i + 3] = 200, px[4 * i] = 100;
  std::vector<uint8_t> raw = rleEncode(px, 4, 1);
  EXPECT_EQ(raw.size(), px.size());
  EXPECT_LT(rleEncode(px).size(), px.size());
  std::vector<uint8_t> back(px.size());
  rleDecode(raw, 50, back);
  EXPECT_EQ(back, px);
  EXPECT_THROW(rleEncode(px, 4, 0), std::invalid_argument);
}

}  // namespace sortlast
