// Direct send on one rank (MPI_COMM_SELF) over several frames: a frame handed back through
// Compositor::recycle, scribbled on, gives the next frame the same pixels as a fresh compositor,
// in float and RGBA8 precision, on 1 and 2 pixel threads. Its own executable: it starts MPI.
#include <gtest/gtest.h>
#include <mpi.h>

#include <random>
#include <vector>

#include "common/pixel_threads.h"
#include "compositing/compositor.h"
#include "compositing/rle.h"

namespace sortlast {
namespace {

std::vector<BrickImage> bricks(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<BrickImage> out;
  for (int k = 0; k < 4; ++k) {
    Rect r{int(rng() % unsigned(w / 2)), int(rng() % unsigned(h / 2)), w / 2, h / 2};
    std::vector<uint8_t> px(size_t(r.area()) * 4, 0);
    for (size_t i = 0; i < size_t(r.area()); ++i)
      if (rng() % 3 != 0) {
        uint8_t a = uint8_t(1 + rng() % 255);
        px[4 * i + 3] = a;
        for (int c = 0; c < 3; ++c) px[4 * i + c] = uint8_t(rng() % (a + 1u));
      }
    out.push_back({k, r, rleEncode(px), {}});
  }
  return out;
}

TEST(DirectSendRecycle, HandedBackFrameGivesTheSamePixels) {
  const int w = 640, h = 480;
  VisibilityOrder order{{0, 1, 2, 3}, {0}};
  for (Precision p : {Precision::kFloat, Precision::kRgba8})
    for (int threads : {1, 2}) {
      setPixelThreads(threads);
      CompositeOptions opt;
      opt.precision = p;
      auto kept = makeCompositor(Strategy::kDirect, 0, opt);
      for (unsigned frame = 0; frame < 3; ++frame) {
        CompositeStats stats;
        ImageRGBA8 want = makeCompositor(Strategy::kDirect, 0, opt)
                              ->composite(bricks(w, h, frame), order, w, h, MPI_COMM_SELF, stats);
        ImageRGBA8 got = kept->composite(bricks(w, h, frame), order, w, h, MPI_COMM_SELF, stats);
        ASSERT_EQ(got.px, want.px) << "frame " << frame << ", " << threads << " threads";
        const uint8_t* memory = got.px.data();
        std::fill(got.px.begin(), got.px.end(), uint8_t(0xAB));  // the caller's use of it
        kept->recycle(std::move(got));
        ImageRGBA8 next = kept->composite(bricks(w, h, frame + 10), order, w, h, MPI_COMM_SELF, stats);
        ImageRGBA8 fresh = makeCompositor(Strategy::kDirect, 0, opt)
                               ->composite(bricks(w, h, frame + 10), order, w, h, MPI_COMM_SELF, stats);
        EXPECT_EQ(next.px.data(), memory) << "the handed-back frame's memory is reused";
        ASSERT_EQ(next.px, fresh.px) << "frame " << frame << ", " << threads << " threads";
      }
    }
}

}  // namespace
}  // namespace sortlast

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  MPI_Init(&argc, &argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
