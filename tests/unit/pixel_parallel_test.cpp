// The pixel work on the pixel threads (common/pixel_threads.h) against the serial code, bit for
// bit, for 1, 2, 3, 7 and 16 threads: float -> RGBA8 conversion (against the lround formula it
// replaces), RLE encoding and decoding (against the serial codec, on images large enough to be
// cut into parts, with transparent runs across the cuts and small max_run), and blending of brick
// images (against decoding each image and blending it pixel by pixel, as blend.cpp did before).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/pixel_threads.h"
#include "compositing/blend.h"
#include "compositing/over.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"
#include "io/image.h"

namespace sortlast {
namespace {

constexpr int kThreads[] = {1, 2, 3, 7, 16};

// Restores the pool's size after a test that changes it.
struct ThreadsScope {
  int before = pixelThreads();
  ~ThreadsScope() { setPixelThreads(before); }
};

// ---- the pool ----

TEST(PixelThreads, CountFromMaskAndRanks) {
  EXPECT_EQ(pixelThreadsFor(2, 2, 1), 2);    // one rank owns the node
  EXPECT_EQ(pixelThreadsFor(2, 2, 4), 1);    // four ranks share two cores
  EXPECT_EQ(pixelThreadsFor(16, 16, 4), 4);  // unbound ranks split the mask
  EXPECT_EQ(pixelThreadsFor(4, 16, 4), 4);   // bound to four cores each: all of them
  EXPECT_EQ(pixelThreadsFor(1, 16, 16), 1);
  EXPECT_EQ(pixelThreadsFor(8, 16, 4), 4);   // masks of 8 on 16 cores, 4 ranks: two share each
  EXPECT_EQ(pixelThreadsFor(0, 0, 0), 1);    // nonsense in, one thread out
  EXPECT_GE(affinityCores(), 1);
}

TEST(PixelThreads, EveryPartRunsOnceAndErrorsReachTheCaller) {
  ThreadsScope keep;
  for (int t : kThreads) {
    setPixelThreads(t);
    EXPECT_EQ(pixelThreads(), t);
    for (int parts : {1, 2, 5, 16, 100}) {
      std::vector<std::atomic<int>> hits(static_cast<size_t>(parts));
      parallelParts(parts, [&](int p) {
        hits[size_t(p)]++;
        // A loop inside a loop runs serially on its thread: no deadlock, every part once.
        std::atomic<int> inner{0};
        parallelParts(3, [&](int) { inner++; });
        EXPECT_EQ(inner.load(), 3);
      });
      for (auto& h : hits) EXPECT_EQ(h.load(), 1) << t << " threads, " << parts << " parts";
    }
    EXPECT_THROW(parallelParts(8, [](int p) {
                   if (p == 5) throw std::runtime_error("part 5");
                 }),
                 std::runtime_error);
    size_t covered = 0;
    parallelFor(1000, 10, [&](size_t b, size_t e) {
      static std::mutex m;
      std::lock_guard lk(m);
      covered += e - b;
    });
    EXPECT_EQ(covered, 1000u);
  }
}

// Between loops the workers block (llvmpipe's threads share these cores): after a loop, the
// process takes next to no CPU time while its main thread sleeps.
TEST(PixelThreads, IdleWorkersTakeNoCpu) {
  ThreadsScope keep;
  setPixelThreads(4);
  std::vector<float> a(1 << 22, 1.0f);
  parallelFor(a.size(), 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) a[i] = std::sqrt(a[i] + float(i));
  });
  auto cpu = [] {
    rusage u;
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  const double before = cpu();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_LT(cpu() - before, 0.03) << "CPU seconds while idle for 0.3 s";
}

// ---- float -> RGBA8 ----

uint8_t lroundQuantise(float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// The conversion as io/image.cpp wrote it before it was vectorised.
void referenceRGBA8(const float* in, uint8_t* out) {
  out[3] = lroundQuantise(in[3]);
  for (int c = 0; c < 3; ++c) out[c] = std::min(lroundQuantise(in[c]), out[3]);
}

// Floats where rounding changes its mind: every k / 255 and (k + 0.5) / 255 and the floats a
// few ulps either side, specials, negatives, values above 1 and random bit patterns.
std::vector<float> hardFloats() {
  std::vector<float> v;
  const float inf = std::numeric_limits<float>::infinity();
  for (int k = -2; k <= 258; ++k)
    for (float centre : {k / 255.0f, (k + 0.5f) / 255.0f}) {
      float lo = centre, hi = centre;
      v.push_back(centre);
      for (int u = 0; u < 4; ++u) {
        lo = std::nextafter(lo, -inf);
        hi = std::nextafter(hi, inf);
        v.push_back(lo);
        v.push_back(hi);
      }
    }
  for (float s : {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::signaling_NaN(), inf, -inf, 0.0f, -0.0f,
                  std::numeric_limits<float>::denorm_min(), -1.0f, 1.0f, 2.0f, 1e30f, -1e30f})
    v.push_back(s);
  uint32_t nan_bits = 0x7fc01234u;  // a NaN with a payload
  float nan_payload;
  std::memcpy(&nan_payload, &nan_bits, 4);
  v.push_back(nan_payload);
  std::mt19937 rng(41);
  for (int i = 0; i < 20000; ++i) {
    uint32_t bits = rng();
    float f;
    std::memcpy(&f, &bits, 4);
    v.push_back(f);
  }
  return v;
}

TEST(PixelParallel, ConversionMatchesLroundForHardFloats) {
  ThreadsScope keep;
  std::vector<float> vals = hardFloats();
  // Pixels whose channels are shuffled hard floats, and enough of them (> two parts) to split.
  std::mt19937 rng(7);
  const size_t n = 3 * 65536 + 17;
  std::vector<float> px(4 * n);
  for (size_t i = 0; i < 4 * n; ++i) px[i] = i < vals.size() ? vals[i] : vals[rng() % vals.size()];
  // Alpha = each hard float in turn too (channel 3 of the first pixels).
  for (size_t i = 0; i < vals.size() && i < n; ++i) px[4 * i + 3] = vals[i];
  std::vector<uint8_t> want(4 * n);
  for (size_t i = 0; i < n; ++i) referenceRGBA8(&px[4 * i], &want[4 * i]);
  std::vector<bool> seen(256, false);
  for (uint8_t b : want) seen[b] = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 256) << "every byte value reached";
  for (int t : kThreads) {
    setPixelThreads(t);
    std::vector<uint8_t> got(4 * n, 0xAB);
    toRGBA8(px.data(), got.data(), n);
    EXPECT_EQ(got, want) << t << " threads";
    uint8_t one[4];
    toRGBA8(&px[0], one);
    EXPECT_EQ(std::memcmp(one, &want[0], 4), 0);
  }
}

// Every one of the 2^32 float bit patterns against the lround formula (315 s on one thread of
// the 2-core development machine, under load), so run by hand: --gtest_also_run_disabled_tests
// --gtest_filter='*EveryFloat*'. Each pixel holds one float in all four channels, so every
// output byte is that float's.
TEST(PixelParallel, DISABLED_ConversionMatchesLroundForEveryFloat) {
  const size_t block = size_t(1) << 20;
  std::vector<float> px(4 * block);
  std::vector<uint8_t> got(4 * block);
  for (uint64_t start = 0; start < (uint64_t(1) << 32); start += block) {
    for (size_t i = 0; i < block; ++i) {
      const uint32_t bits = uint32_t(start + i);
      std::memcpy(&px[4 * i], &bits, 4);
      px[4 * i + 1] = px[4 * i + 2] = px[4 * i + 3] = px[4 * i];
    }
    toRGBA8(px.data(), got.data(), block);
    for (size_t i = 0; i < block; ++i) {
      const uint8_t want = lroundQuantise(px[4 * i]);
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(got[4 * i + c], want) << "bits " << std::hex << uint32_t(start + i);
    }
  }
}

// ---- RLE ----

// A premultiplied image of `n` pixels of `bytes` each: transparent runs of random lengths (some
// longer than a part of the parallel codec, 64 K pixels) between visible stretches.
std::vector<uint8_t> randomLayer(size_t n, int bytes, std::mt19937& rng, size_t longest_run) {
  std::vector<uint8_t> px(size_t(bytes) * n, 0);
  std::uniform_int_distribution<size_t> run(1, longest_run), stretch(1, 300);
  size_t i = 0;
  bool visible = rng() % 2;
  while (i < n) {
    const size_t len = std::min(n - i, visible ? stretch(rng) : run(rng));
    if (visible)
      for (size_t k = i; k < i + len; ++k) {
        uint8_t* p = &px[size_t(bytes) * k];
        for (int c = 0; c < bytes; ++c) p[c] = uint8_t(rng());
        if (bytes == 4 && p[3] == 0) p[3] = 1;
        if (bytes == 8 && p[6] == 0 && p[7] == 0) p[7] = 1;
        if (bytes == 12 && p[9] == 0 && p[10] == 0 && p[11] == 0) p[11] = 1;  // the bounded sums
        if (bytes == 4)
          for (int c = 0; c < 3; ++c) p[c] = uint8_t(p[c] % (p[3] + 1));
      }
    i += len;
    visible = !visible;
  }
  return px;
}

TEST(PixelParallel, RleEncodeAndDecodeMatchSerial) {
  ThreadsScope keep;
  std::mt19937 rng(2026);
  const size_t big = 200003;  // three parts at 64 K pixels each, and a remainder
  struct Case {
    size_t n, longest_run;
  };
  for (int bytes : {4, 8, 12})
    for (Case c : {Case{big, 30}, Case{big, 70000}, Case{big, 250000}, Case{2 * 65536, 5000},
                   Case{1000, 50}})
      for (uint32_t max_run : {1u, 2u, 3u, 7u, 1000u, kMaxRun}) {
        std::vector<uint8_t> px = randomLayer(c.n, bytes, rng, c.longest_run);
        setPixelThreads(1);
        std::vector<uint8_t> prefix = {1, 2, 3, 4};  // encoding appends
        std::vector<uint8_t> want = prefix;
        rleEncode(px, want, bytes, max_run);
        for (int t : kThreads) {
          setPixelThreads(t);
          std::vector<uint8_t> got = prefix;
          rleEncode(px, got, bytes, max_run);
          ASSERT_EQ(got, want) << t << " threads, " << bytes << " bytes, n " << c.n << ", max_run "
                               << max_run << ", runs up to " << c.longest_run;
          std::vector<uint8_t> back(px.size(), 0xAB);
          rleDecode(std::span(want).subspan(4), c.n, back, bytes);
          ASSERT_EQ(back, px) << t << " threads";
        }
      }
}

TEST(PixelParallel, RleAllTransparentAndAllVisible) {
  ThreadsScope keep;
  const size_t n = 5 * 65536 + 3;
  std::vector<uint8_t> clear(4 * n, 0), solid(4 * n, 0x80);
  for (uint32_t max_run : {1u, 3u, 65536u, 65537u, kMaxRun}) {
    setPixelThreads(1);
    auto want_clear = rleEncode(clear, 4, max_run), want_solid = rleEncode(solid, 4, max_run);
    for (int t : kThreads) {
      setPixelThreads(t);
      EXPECT_EQ(rleEncode(clear, 4, max_run), want_clear) << t << " threads, max_run " << max_run;
      EXPECT_EQ(rleEncode(solid, 4, max_run), want_solid) << t << " threads";
    }
  }
}

// A malformed stream is rejected with the serial decoder's message, whatever the threads.
TEST(PixelParallel, RleDecodeErrorsMatchSerial) {
  ThreadsScope keep;
  std::mt19937 rng(5);
  const size_t n = 3 * 65536;
  std::vector<uint8_t> px = randomLayer(n, 4, rng, 2000);
  setPixelThreads(1);
  std::vector<uint8_t> good = rleEncode(px);
  std::vector<std::vector<uint8_t>> bad;
  bad.push_back(std::vector<uint8_t>(good.begin(), good.end() - 4));  // a pixel short
  bad.push_back(good);
  bad.back().insert(bad.back().end(), {1, 0, 0, 0});  // one run too many
  bad.push_back(good);
  bad.back().push_back(7);  // not a multiple of 4
  bad.push_back(good);
  for (size_t i = bad.back().size() / 2; i < bad.back().size(); i += 4)
    if (bad.back()[i + 3] == 0) {  // a zero-length run in the middle
      std::fill_n(&bad.back()[i], 3, 0);
      break;
    }
  for (const auto& s : bad) {
    std::string want;
    std::vector<uint8_t> out(4 * n);
    setPixelThreads(1);
    try {
      rleDecode(s, n, out);
    } catch (const RleError& e) {
      want = e.what();
    }
    ASSERT_FALSE(want.empty());
    for (int t : kThreads) {
      setPixelThreads(t);
      try {
        rleDecode(s, n, out);
        ADD_FAILURE() << "no error with " << t << " threads";
      } catch (const RleError& e) {
        EXPECT_EQ(std::string(e.what()), want) << t << " threads";
      }
    }
  }
}

// ---- blending ----

// Decode each image whole, then blend pixel by pixel, skipping transparent pixels: blend.cpp's
// code before it blended straight from the stream on the pixel threads.
void referenceBlend(const std::vector<const BrickImage*>& images, int fw, float* frame,
                    WireFormat format) {
  const int bytes = pixelBytes(format);
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    if (r.empty()) continue;
    std::vector<uint8_t> px(size_t(r.area()) * size_t(bytes));
    rleDecode(b->rle, size_t(r.area()), px, bytes);
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x) {
        const uint8_t* s = &px[(size_t(y) * r.w + x) * bytes];
        float* d = frame + (size_t(r.y + y) * fw + size_t(r.x + x)) * 4;
        float f[4];
        if (format == WireFormat::RGBA8) {
          if (s[3] == 0) continue;
          for (int c = 0; c < 4; ++c) f[c] = s[c] / 255.0f;
          overFloat(f, d);
        } else {
          if (s[6] == 0 && s[7] == 0) continue;
          fromEmission16(s, f);
          if (shows(f)) overFloat(f, d);
        }
      }
  }
}

void referenceBlend8(const std::vector<const BrickImage*>& images, ImageRGBA8& frame) {
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    if (r.empty()) continue;
    std::vector<uint8_t> px(size_t(r.area()) * 4);
    rleDecode(b->rle, size_t(r.area()), px, 4);
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x) {
        const uint8_t* s = &px[(size_t(y) * r.w + x) * 4];
        if (s[3] != 0) overRGBA8(s, frame.at(r.x + x, r.y + y));
      }
  }
}

// Random brick images over a w x h frame: random rectangles (some the whole frame), RGBA8 from
// random layers, or Emission from random float pixels through encodeEmission.
std::vector<BrickImage> randomBricks(int w, int h, WireFormat format, std::mt19937& rng) {
  std::vector<BrickImage> bricks;
  for (int k = 0; k < 6; ++k) {
    BrickImage b;
    b.brick_id = k;
    if (k == 0) {
      b.rect = {0, 0, w, h};
    } else if (k == 5) {
      b.rect = {};  // invisible
    } else {
      const int x = int(rng() % unsigned(w)), y = int(rng() % unsigned(h));
      b.rect = {x, y, 1 + int(rng() % unsigned(w - x)), 1 + int(rng() % unsigned(h - y))};
    }
    const size_t n = size_t(b.rect.area());
    if (format == WireFormat::RGBA8) {
      b.rle = rleEncode(randomLayer(n, 4, rng, 3000), 4, k == 2 ? 5u : kMaxRun);
    } else {
      std::vector<float> f(4 * n, 0.0f);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      for (size_t i = 0; i < n; ++i)
        if (rng() % 3 != 0) {
          f[4 * i + 3] = u(rng) * (rng() % 2);  // some light without opacity
          for (int c = 0; c < 3; ++c) f[4 * i + c] = 3.0f * u(rng);
        }
      encodeEmission(f, b.rle, kMaxRun);
    }
    bricks.push_back(std::move(b));
  }
  return bricks;
}

TEST(PixelParallel, BlendMatchesSerialBitForBit) {
  ThreadsScope keep;
  std::mt19937 rng(99);
  for (auto [w, h] : {std::pair{700, 400}, std::pair{33, 17}})
    for (WireFormat format : {WireFormat::RGBA8, WireFormat::Emission}) {
      std::vector<BrickImage> bricks = randomBricks(w, h, format, rng);
      std::vector<const BrickImage*> order;
      for (const BrickImage& b : bricks) order.push_back(&b);
      ImageF want(w, h);
      referenceBlend(order, w, want.px.data(), format);
      ImageRGBA8 want8(w, h);
      if (format == WireFormat::RGBA8) referenceBlend8(order, want8);
      for (int t : kThreads) {
        setPixelThreads(t);
        ImageF got(w, h);
        blendBackToFront(order, got, format);
        ASSERT_EQ(std::memcmp(got.px.data(), want.px.data(), want.px.size() * 4), 0)
            << t << " threads, " << w << "x" << h << (format == WireFormat::RGBA8 ? " RGBA8" : " Emission");
        if (format == WireFormat::RGBA8) {
          ImageRGBA8 got8(w, h);
          blendBackToFront(order, got8);
          ASSERT_EQ(got8.px, want8.px) << t << " threads";
        }
        RectImage rect = blendBackToFront(order, format);  // into the rectangle they cover
        for (int y = 0; y < rect.rect.h; ++y)
          ASSERT_EQ(std::memcmp(rect.at(rect.rect.x, rect.rect.y + y),
                                &want.px[(size_t(rect.rect.y + y) * w + rect.rect.x) * 4],
                                size_t(rect.rect.w) * 16),
                    0)
              << t << " threads, row " << y;
      }
    }
}

// Unencoded Emission images (direct send's rank 0 blends its own that way) and float layers:
// banded over the threads, the same bits as on one thread.
TEST(PixelParallel, FloatBlendsMatchOneThread) {
  ThreadsScope keep;
  std::mt19937 rng(3);
  const int w = 640, h = 480;
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto floats = [&](size_t n) {
    std::vector<float> f(4 * n, 0.0f);
    for (size_t i = 0; i < n; ++i)
      if (rng() % 4 != 0) {
        f[4 * i + 3] = u(rng);
        for (int c = 0; c < 3; ++c) f[4 * i + c] = f[4 * i + 3] * u(rng) * (1 + rng() % 2);
      }
    return f;
  };
  BrickImage own{0, Rect{10, 20, 600, 400}, {}, floats(600 * 400)};
  RectImage a(Rect{0, 0, w, h}), b(Rect{50, 60, 500, 300});
  a.px = floats(size_t(w) * h);
  b.px = floats(500 * 300);
  setPixelThreads(1);
  ImageF want(w, h);
  blendBackToFront({&own}, want, WireFormat::Emission);
  RectImage want_layers = blendBackToFront(std::vector<const RectImage*>{&a, &b});
  for (int t : kThreads) {
    setPixelThreads(t);
    ImageF got(w, h);
    blendBackToFront({&own}, got, WireFormat::Emission);
    EXPECT_EQ(std::memcmp(got.px.data(), want.px.data(), want.px.size() * 4), 0) << t << " threads";
    RectImage layers = blendBackToFront(std::vector<const RectImage*>{&a, &b});
    EXPECT_EQ(std::memcmp(layers.px.data(), want_layers.px.data(), want_layers.px.size() * 4), 0)
        << t << " threads";
  }
}

}  // namespace
}  // namespace sortlast
