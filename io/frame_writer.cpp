#include "io/frame_writer.h"

#include <chrono>
#include <new>

#include "common/error.h"

namespace sortlast {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The message of a failed write, naming the file (writeImage's messages do; a bare codec or
// allocation failure gets the name put in front).
std::string failureMessage(const std::string& file, const std::string& what) {
  if (what.find(file) != std::string::npos) return what;
  return "output " + file + ": " + what;
}

}  // namespace

FrameWriter::FrameWriter(size_t queue_files) : sync_(queue_files == 0), queue_(queue_files) {
  if (!sync_) thread_ = std::thread([this] { writerLoop(); });
}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    abandon_ = true;
  }
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

void FrameWriter::run(Job& job) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  try {
    job.write();
  } catch (const std::bad_alloc&) {
    error = "out of memory while encoding or writing (std::bad_alloc)";
  } catch (const std::exception& e) {
    error = e.what();
  } catch (...) {
    error = "unknown error";
  }
  std::lock_guard lock(mutex_);
  stats_.write_s += secondsSince(t0);
  if (!error.empty()) {
    if (failure_.empty()) failure_ = failureMessage(job.file, error);
  } else {
    ++stats_.files;
  }
}

void FrameWriter::rethrowFailure() {
  std::lock_guard lock(mutex_);
  if (!failure_.empty()) throw InputError(failure_);
}

void FrameWriter::writerLoop() {
  while (std::optional<Job> job = queue_.pop()) {
    {
      std::lock_guard lock(mutex_);
      // After a failure the job stops anyway: writing later frames would only leave a series
      // with a hole in it.
      if (abandon_ || !failure_.empty()) continue;
    }
    run(*job);
    job->write = nullptr;  // frees the frame's pixels now, not when the next job arrives
  }
}

void FrameWriter::push(std::string file, std::function<void()> write) {
  rethrowFailure();
  Job job{file, std::move(write)};
  if (sync_) {
    run(job);
    rethrowFailure();
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (!queue_.push(std::move(job))) throw InputError("output " + file + ": the writer was closed");
  std::lock_guard lock(mutex_);
  stats_.wait_s += secondsSince(t0);
}

void FrameWriter::finish() {
  const auto t0 = std::chrono::steady_clock::now();
  queue_.close();
  if (thread_.joinable()) thread_.join();
  {
    std::lock_guard lock(mutex_);
    stats_.wait_s += secondsSince(t0);
  }
  rethrowFailure();
}

FrameWriter::Stats FrameWriter::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace sortlast
