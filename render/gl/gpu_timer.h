#pragma once
// The GL work of a frame's bricks, timed by the GPU itself: a GL_TIME_ELAPSED query around each
// brick's draw calls, read when the frame's pixels are all back (the results are ready then, so
// reading them waits for nothing). This is the frame's draw_s: the drawing alone, not the
// read-back or the CPU work that overlaps it, which a wall clock around the draw cannot separate.
// Queries are kept and reused from frame to frame.
//
// On a software renderer (llvmpipe: no hardware device) the queries do not time the draw: Mesa
// rasterizes a scene when something flushes it, and the interval's end may be taken before that
// (measured: 0.016 s of queries for a 0.37 s draw read back synchronously after the interval).
// There the interval is bounded by a fence instead: end() waits for the GL work (glFinish) and
// takes the wall time since begin(). Nothing overlaps on llvmpipe anyway (its reads wait for the
// draw), so the wait costs nothing there. The sum is bounded by the wall time from the
// first begin() to collect(): a draw cannot take longer than the time from its issue to the moment
// its completion was seen, and llvmpipe's first query of a context reports its end timestamp
// alone (about the machine's uptime) — measured: 10,577 s for a 1.2 s frame.
#include <chrono>
#include <vector>

#include "render/gl/gl_api.h"

namespace sortlast {

class GpuTimer {
 public:
  // `finish_bounded`: the software renderer's way (above).
  GpuTimer(const GlApi& gl, bool finish_bounded) : gl_(gl), finish_bounded_(finish_bounded) {}
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void begin();  // a nested begin (one already running) is ignored with its end
  void end();
  // The seconds of every interval since the last collect(), summed; waits for their results.
  double collect();

 private:
  const GlApi& gl_;
  std::vector<unsigned> queries_;
  size_t used_ = 0;
  int depth_ = 0;
  bool finish_bounded_ = false;
  double finished_s_ = 0;  // finish-bounded intervals so far
  std::chrono::steady_clock::time_point interval_begin_;
  std::chrono::steady_clock::time_point first_begin_;
};

}  // namespace sortlast
