#pragma once
// "frame i of N, time left" on stderr for orbits and long renders; silent with --quiet.
#include <chrono>
#include <cstdio>

namespace sortlast {

class Progress {
 public:
  Progress(int frames, bool quiet) : frames_(frames), quiet_(quiet) {}
  void frameDone(int i) {
    if (quiet_) return;
    double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    double left = elapsed / (i + 1) * (frames_ - i - 1);
    std::fprintf(stderr, "frame %d of %d  %.3f s/frame  %.1f s left\n", i + 1, frames_,
                 elapsed / (i + 1), left);
  }

 private:
  using Clock = std::chrono::steady_clock;
  int frames_;
  bool quiet_;
  Clock::time_point start_ = Clock::now();
};

}  // namespace sortlast
