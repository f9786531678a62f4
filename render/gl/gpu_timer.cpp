#include "render/gl/gpu_timer.h"

#include <algorithm>

namespace sortlast {

GpuTimer::~GpuTimer() {
  if (!queries_.empty()) gl_.DeleteQueries(GLsizei(queries_.size()), queries_.data());
}

void GpuTimer::begin() {
  if (depth_++ > 0) return;
  if (finish_bounded_) {
    interval_begin_ = std::chrono::steady_clock::now();
    return;
  }
  if (used_ == 0) first_begin_ = std::chrono::steady_clock::now();
  if (used_ == queries_.size()) {
    unsigned q = 0;
    gl_.GenQueries(1, &q);
    queries_.push_back(q);
  }
  gl_.BeginQuery(GL_TIME_ELAPSED, queries_[used_++]);
}

void GpuTimer::end() {
  if (depth_ == 0 || --depth_ > 0) return;
  if (finish_bounded_) {
    gl_.Finish();
    finished_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - interval_begin_).count();
    return;
  }
  gl_.EndQuery(GL_TIME_ELAPSED);
}

double GpuTimer::collect() {
  if (depth_ > 0) {  // an interval still open (a frame abandoned mid-brick): close it
    depth_ = 1;
    end();
  }
  if (finish_bounded_) {
    const double s = finished_s_;
    finished_s_ = 0;
    return s;
  }
  GLuint64 total = 0;
  for (size_t i = 0; i < used_; ++i) {
    GLuint64 ns = 0;
    gl_.GetQueryObjectui64v(queries_[i], GL_QUERY_RESULT, &ns);
    total += ns;
  }
  const double wall = used_ ? std::chrono::duration<double>(std::chrono::steady_clock::now() - first_begin_).count() : 0.0;
  used_ = 0;
  return std::min(double(total) * 1e-9, wall);
}

}  // namespace sortlast
