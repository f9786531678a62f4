// The batch render's writer thread (io/frame_writer.h): files written in the order handed over,
// no more than the queue's worth waiting, a failed write thrown with its file's name at the next
// hand-off or at the end, and nothing written after it.
#include "io/frame_writer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "common/error.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

using namespace std::chrono_literals;

TEST(FrameWriter, WritesInOrderAndHoldsAtMostTheQueue) {
  constexpr size_t kQueue = 2;
  FrameWriter writer(kQueue);
  std::mutex m;
  std::vector<int> written;
  std::atomic<int> finished{0};
  for (int i = 0; i < 12; ++i) {
    // Uneven write times, slower than the hand-offs: the queue fills and push must wait.
    writer.push("f" + std::to_string(i), [&, i] {
      std::this_thread::sleep_for(std::chrono::milliseconds(i % 3 == 0 ? 6 : 1));
      {
        std::lock_guard lock(m);
        written.push_back(i);
      }
      ++finished;
    });
    // Handed over but not written: the queue's capacity and the one in the writer's hands, at
    // most (memory stays bounded).
    EXPECT_LE(i + 1 - finished.load(), int(kQueue) + 1) << "after push " << i;
  }
  writer.finish();
  std::vector<int> want(12);
  for (int i = 0; i < 12; ++i) want[size_t(i)] = i;
  EXPECT_EQ(written, want);
  EXPECT_EQ(writer.stats().files, 12);
  EXPECT_GT(writer.stats().wait_s, 0.0);
}

TEST(FrameWriter, AFailedWriteIsThrownWithItsFileAndStopsTheWrites) {
  FrameWriter writer(2);
  std::atomic<int> after{0};
  writer.push("out/a.png", [] {});
  writer.push("out/b.png", [] { throw InputError("cannot create (No space left on device)"); });
  // The failure reaches the caller at a later hand-off or at finish(), whichever comes first.
  std::string msg = inputErrorOf([&] {
    for (int i = 0; i < 50; ++i) {
      writer.push("out/c" + std::to_string(i) + ".png", [&] { ++after; });
      std::this_thread::sleep_for(1ms);
    }
    writer.finish();
  });
  EXPECT_EQ(msg, "output out/b.png: cannot create (No space left on device)");
  // Drained already: no hang, the same failure again.
  EXPECT_EQ(inputErrorOf([&] { writer.finish(); }), msg);
  EXPECT_EQ(after.load(), 0) << "a file was written after the failed one";
  EXPECT_EQ(writer.stats().files, 1);
}

TEST(FrameWriter, AMessageNamingTheFileIsKeptAsItIs) {
  FrameWriter writer(1);
  writer.push("x.png", [] { throw InputError("output x.png: cannot create (Not a directory)"); });
  EXPECT_EQ(inputErrorOf([&] { writer.finish(); }),
            "output x.png: cannot create (Not a directory)");
}

TEST(FrameWriter, SyncWritesInPushOnTheCallersThread) {
  FrameWriter writer(0);
  std::thread::id where;
  writer.push("a.png", [&] { where = std::this_thread::get_id(); });
  EXPECT_EQ(where, std::this_thread::get_id());
  EXPECT_EQ(
      inputErrorOf([&] { writer.push("b.png", [] { throw std::runtime_error("encoder"); }); }),
      "output b.png: encoder");
  EXPECT_EQ(writer.stats().files, 1);
}

TEST(FrameWriter, DestroyedWithoutFinishDropsWhatWaitsAndReturns) {
  std::atomic<int> ran{0};
  {
    FrameWriter writer(2);
    for (int i = 0; i < 3; ++i)
      writer.push("f", [&] {
        std::this_thread::sleep_for(50ms);
        ++ran;
      });
  }  // another rank failed: the job ends without writing the rest
  // The one being written (if it had started) completes; those waiting are dropped.
  EXPECT_LE(ran.load(), 1);
}

}  // namespace
}  // namespace sortlast
