// The overlapped read-back on the GL driver (OSMesa: llvmpipe): the GPU's RGBA8 conversion
// (render/gl/rgba8.frag.glsl) against toRGBA8 bit for bit, on every byte value and on floats on
// both sides of every rounding boundary; the pixel-buffer ring (render/gl/pixel_readback.h) with
// several reads in flight, slots reused across frames, a resize mid-orbit, and a read started on
// a full ring refused. Its own executable: it makes a GL context.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "io/image.h"
#include "render/gl/float_target.h"
#include "render/gl/gl_context.h"
#include "tests/unit/gl_test_context.h"
#include "render/gl/gpu_timer.h"
#include "render/gl/pixel_readback.h"

namespace sortlast {
namespace {

// Values that probe toRGBA8's rounding: every k / 255 and the floats next to each (k + 1/2) / 255
// boundary after scaling, plus values outside [0, 1], infinities and signed zeros.
std::vector<float> probeValues() {
  std::vector<float> v;
  for (int k = 0; k <= 255; ++k) {
    v.push_back(k / 255.0f);
    const float half = (k + 0.5f) / 255.0f;
    float below = half, above = half;
    for (int i = 0; i < 3; ++i) {
      below = std::nextafter(below, 0.0f);
      above = std::nextafter(above, 2.0f);
      v.push_back(below);
      v.push_back(above);
    }
    v.push_back(half);
  }
  for (float x : {-1.0f, -0.0f, 0.0f, 1.0f, 1.5f, 1e30f, std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min()})
    v.push_back(x);
  return v;
}

// Pixels of `w` x `h` whose channels walk through `values` (alpha taken from a shifted index, so
// colour above, at and below alpha all occur).
std::vector<float> probePixels(const std::vector<float>& values, int w, int h) {
  std::vector<float> px(size_t(w) * h * 4);
  for (size_t i = 0; i < px.size() / 4; ++i)
    for (int c = 0; c < 4; ++c) px[4 * i + c] = values[(i * 7 + size_t(c) * 131 + (c == 3 ? i / 3 : 0)) % values.size()];
  return px;
}

// Fills the float target's colour texture with `px` (w x h, the target's size).
void upload(const GlApi& gl, unsigned texture, int w, int h, const std::vector<float>& px) {
  gl.BindTexture(GL_TEXTURE_2D, texture);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, px.data());
}

TEST(PixelReadback, GpuConversionEqualsToRGBA8BitForBit) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  const int w = 97, h = 61;  // odd sizes: no row padding hides an error
  const std::vector<float> src = probePixels(probeValues(), w, h);
  FloatTarget target(gl, w, h);
  upload(gl, target.colourTexture(), w, h, src);
  const Rect r{0, 0, w, h};
  PendingPixels p = target.readAsync(r);
  ASSERT_TRUE(p.pending());
  std::span<const uint8_t> got = p.ring->map(p);
  ASSERT_EQ(got.size(), size_t(w) * h * 4);
  size_t wrong = 0;
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    uint8_t want[4];
    toRGBA8(&src[4 * i], want);
    if (std::memcmp(want, &got[4 * i], 4) != 0 && wrong++ < 5)
      ADD_FAILURE() << "pixel " << i << ": GPU " << int(got[4 * i]) << "," << int(got[4 * i + 1]) << ","
                    << int(got[4 * i + 2]) << "," << int(got[4 * i + 3]) << " CPU " << int(want[0]) << ","
                    << int(want[1]) << "," << int(want[2]) << "," << int(want[3]) << " from " << src[4 * i]
                    << " " << src[4 * i + 1] << " " << src[4 * i + 2] << " " << src[4 * i + 3];
  }
  EXPECT_EQ(wrong, 0u);
  p.ring->release(p);
  EXPECT_FALSE(p.pending());
}

TEST(PixelReadback, RingKeepsReadsInFlightAcrossFramesAndResizes) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int w = 64, h = 48;
  FloatTarget target(gl, w, h);
  // Three "frames" of three bricks each, the image resized before the last; two reads in flight
  // at once (the session's depth), each checked against toRGBA8 of what was drawn.
  for (int frame = 0; frame < 3; ++frame) {
    if (frame == 2) {
      w = 150, h = 90;  // larger: the ring's slots grow
      target.resize(w, h);
    }
    std::vector<std::vector<float>> drawn;
    std::vector<PendingPixels> pending;
    std::vector<Rect> rects;
    for (int brick = 0; brick < 3; ++brick) {
      std::vector<float> px(size_t(w) * h * 4);
      for (float& v : px) v = u(rng);
      upload(gl, target.colourTexture(), w, h, px);
      const Rect r{brick * 3, brick * 2, w - brick * 7, h - brick * 5};
      pending.push_back(target.readAsync(r));
      rects.push_back(r);
      drawn.push_back(std::move(px));
      // The depth-2 pipeline: map and release the brick before the last.
      if (pending.size() >= 2) {
        const size_t k = pending.size() - 2;
        std::span<const uint8_t> got = pending[k].ring->map(pending[k]);
        const Rect& rk = rects[k];
        ASSERT_EQ(got.size(), size_t(rk.area()) * 4);
        for (int y = 0; y < rk.h; ++y)
          for (int x = 0; x < rk.w; ++x) {
            uint8_t want[4];
            toRGBA8(&drawn[k][4 * (size_t(rk.y + y) * w + size_t(rk.x + x))], want);
            ASSERT_EQ(std::memcmp(want, &got[4 * (size_t(y) * rk.w + x)], 4), 0)
                << "frame " << frame << " brick " << k << " pixel " << x << "," << y;
          }
        pending[k].ring->release(pending[k]);
      }
    }
    PendingPixels& last = pending.back();
    EXPECT_EQ(last.ring->map(last).size(), size_t(rects.back().area()) * 4);
    last.ring->release(last);
    EXPECT_EQ(last.ring, nullptr);
  }
}

TEST(PixelReadback, FullRingRefusesAnotherRead) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  FloatTarget target(gl, 16, 16);
  PixelReadback ring(gl, 2);
  gl.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
  PendingPixels a = ring.start({0, 0, 8, 8}, GL_RGBA, GL_FLOAT, 16);
  PendingPixels b = ring.start({0, 0, 4, 4}, GL_RGBA, GL_FLOAT, 16);
  EXPECT_EQ(ring.inFlight(), 2);
  EXPECT_THROW(ring.start({0, 0, 2, 2}, GL_RGBA, GL_FLOAT, 16), std::logic_error);
  ring.release(a);  // released unread (an abandoned frame): the slot is free again
  PendingPixels c = ring.start({0, 0, 2, 2}, GL_RGBA, GL_FLOAT, 16);
  EXPECT_EQ(ring.map(c).size(), 2u * 2 * 16);
  ring.release(c);
  ring.release(b);
  EXPECT_EQ(ring.inFlight(), 0);
  EXPECT_EQ(ring.capacity(), size_t(8 * 8 * 16 + 4 * 4 * 16));  // no slot shrank or grew twice
}

TEST(GpuTimer, SumsIntervalsWithinTheWallTime) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  FloatTarget target(gl, 256, 256);
  for (bool finish_bounded : {false, true}) {  // timer queries; the software renderer's fence
    GpuTimer timer(gl, finish_bounded);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 3; ++i) {
      timer.begin();
      timer.begin();  // nested: ignored with its end
      target.begin({0, 0, 256, 256}, nullptr);
      timer.end();
      timer.end();
    }
    gl.Finish();
    const double s = timer.collect();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(s, 0.0) << finish_bounded;
    EXPECT_LE(s, wall) << finish_bounded;
    EXPECT_EQ(timer.collect(), 0.0) << finish_bounded;  // nothing since
  }
}

}  // namespace
}  // namespace sortlast
