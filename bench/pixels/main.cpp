// The CPU pixel work of a frame, each kernel timed back to back in one process: the serial code
// it replaced ("old", copied here as it was), and the new code on 1 and on 2 pixel threads
// (common/pixel_threads.h). Kernels: float -> RGBA8 conversion of a frame, RLE encoding and
// decoding of a frame, and blending 8 brick images over a float frame (direct send's rank 0).
// Every result is checked equal to the old code's before any time is taken.
//
// The layer is a soft disc over about 60 % of the frame with a dithered edge (a brick image's
// look: transparent corners, visible stretches cut by runs at the edge).
//
// Usage: bench_pixels [--sizes 1024,2048] [--reps N] [--threads 1,2]
// Prints CSV: kernel,variant,threads,width,height,median_ms,min_ms,reps
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "../comma_list.h"
#include "common/pixel_threads.h"
#include "compositing/blend.h"
#include "compositing/over.h"
#include "compositing/rle.h"
#include "io/image.h"

using namespace sortlast;

namespace {

// --- the code before the pixel threads, as it was ---
void oldToRGBA8(const float* in, uint8_t* out, size_t n) {
  auto q = [](float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  for (size_t i = 0; i < n; ++i) {
    out[4 * i + 3] = q(in[4 * i + 3]);
    for (int c = 0; c < 3; ++c) out[4 * i + c] = std::min(q(in[4 * i + c]), out[4 * i + 3]);
  }
}

void oldBlend(const std::vector<const BrickImage*>& images, ImageF& frame) {
  std::vector<uint8_t> pixels;
  for (const BrickImage* b : images) {
    const Rect& r = b->rect;
    pixels.resize(size_t(r.area()) * 4);
    rleDecode(b->rle, size_t(r.area()), pixels, 4);
    for (int y = 0; y < r.h; ++y) {
      const uint8_t* s = &pixels[size_t(y) * r.w * 4];
      float* d = &frame.px[(size_t(r.y + y) * frame.width + size_t(r.x)) * 4];
      for (int x = 0; x < r.w; ++x)
        if (s[4 * x + 3] != 0) {
          float f[4];
          for (int c = 0; c < 4; ++c) f[c] = s[4 * x + c] / 255.0f;
          overFloat(f, d + 4 * x);
        }
    }
  }
}

std::vector<float> discLayer(int w, int h, unsigned seed) {
  std::vector<float> px(size_t(w) * h * 4, 0.0f);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float cx = w * 0.5f, cy = h * 0.5f, rad = 0.44f * std::min(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float d = std::hypot(x - cx, y - cy) / rad;
      if (d > 1.0f || (d > 0.9f && u(rng) < (d - 0.9f) * 10.0f)) continue;
      float* p = &px[(size_t(y) * w + x) * 4];
      p[3] = 0.9f * (1.0f - d * d) + 0.05f;
      for (int c = 0; c < 3; ++c) p[c] = p[3] * u(rng);
    }
  return px;
}

double ms(const std::function<void()>& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Variant {
  std::string kernel, name;
  int threads;
  std::function<void()> run;
  std::vector<double> t;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {1024, 2048}, threads = {1, 2};
  int reps = 15;
  auto ints = [](const char* s) {
    std::vector<int> v;
    for (const std::string& t : splitCommas(s)) v.push_back(std::stoi(t));
    return v;
  };
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i];
    if (a == "--sizes") sizes = ints(argv[i + 1]);
    else if (a == "--threads") threads = ints(argv[i + 1]);
    else if (a == "--reps") reps = std::stoi(argv[i + 1]);
    else { std::fprintf(stderr, "bench_pixels: unknown option %s\n", argv[i]); return 2; }
  }
  std::printf("kernel,variant,threads,width,height,median_ms,min_ms,reps\n");
  for (int n : sizes) {
    const size_t pixels = size_t(n) * n;
    std::vector<float> layer = discLayer(n, n, 1);
    std::vector<uint8_t> rgba(4 * pixels), want(4 * pixels);
    oldToRGBA8(layer.data(), want.data(), pixels);
    std::vector<uint8_t> stream = rleEncode(want), enc;
    enc.reserve(stream.size());
    std::vector<uint8_t> decoded(4 * pixels);
    // 8 brick images: the frame cut into 8 row bands, each a whole brick-sized layer of its own.
    std::vector<BrickImage> bricks;
    for (int k = 0; k < 8; ++k) {
      std::vector<float> l = discLayer(n, n / 2, 10 + k);
      std::vector<uint8_t> l8(l.size());
      oldToRGBA8(l.data(), l8.data(), l.size() / 4);
      bricks.push_back({k, Rect{0, (k % 2) * (n / 2), n, n / 2}, rleEncode(l8), {}});
    }
    std::vector<const BrickImage*> order;
    for (const BrickImage& b : bricks) order.push_back(&b);
    ImageF frame(n, n), frame_want(n, n);
    oldBlend(order, frame_want);

    std::vector<Variant> vs;
    vs.push_back({"convert", "old", 1, [&] { oldToRGBA8(layer.data(), rgba.data(), pixels); }, {}});
    for (int t : threads) {
      vs.push_back({"convert", "new", t, [&] { toRGBA8(layer.data(), rgba.data(), pixels); }, {}});
      vs.push_back({"rle_encode", "new", t, [&] { enc.clear(); rleEncode(want, enc); }, {}});
      vs.push_back({"rle_decode", "new", t, [&] { rleDecode(stream, pixels, decoded); }, {}});
      vs.push_back({"blend8_float", "new", t, [&] {
                      std::fill(frame.px.begin(), frame.px.end(), 0.0f);
                      blendBackToFront(order, frame);
                    }, {}});
    }
    vs.push_back({"blend8_float", "old", 1, [&] {
                    std::fill(frame.px.begin(), frame.px.end(), 0.0f);
                    oldBlend(order, frame);
                  }, {}});
    // Check every variant against the old code once (this also warms the buffers and the pool).
    for (Variant& v : vs) {
      setPixelThreads(v.threads);
      v.run();
      bool ok = true;
      if (v.kernel == "convert") ok = rgba == want;
      if (v.kernel == "rle_encode") ok = enc == stream;
      if (v.kernel == "rle_decode") ok = decoded == want;
      if (v.kernel == "blend8_float")
        ok = std::memcmp(frame.px.data(), frame_want.px.data(), frame.px.size() * 4) == 0;
      if (!ok) {
        std::fprintf(stderr, "bench_pixels: %s %s on %d threads differs from the old code\n",
                     v.kernel.c_str(), v.name.c_str(), v.threads);
        return 1;
      }
    }
    // Repetitions interleaved: each round times every variant once, so load on the machine
    // spreads over all of them alike.
    for (int r = 0; r < reps; ++r)
      for (Variant& v : vs) {
        setPixelThreads(v.threads);
        v.t.push_back(ms(v.run));
      }
    for (Variant& v : vs) {
      std::sort(v.t.begin(), v.t.end());
      std::printf("%s,%s,%d,%d,%d,%.3f,%.3f,%d\n", v.kernel.c_str(), v.name.c_str(), v.threads, n, n,
                  v.t[v.t.size() / 2], v.t[0], reps);
    }
  }
  return 0;
}
