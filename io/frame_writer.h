#pragma once
// A batch render's output files, encoded and written by one thread of their own while the next
// frame renders, so the encode and the write (~0.1 s for a 1024² PNG through zlib's defaults,
// outside the frame's timer) leave the critical path. Files are written in the order they were
// handed over; at most `queue_files` wait, so memory stays bounded (a frame that finds the queue
// full waits for the writer). No MPI here: the caller reports a failure to the other ranks.
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "common/bounded_queue.h"

namespace sortlast {

class FrameWriter {
 public:
  // queue_files 0: every write runs in push(), on the caller's thread (the old, synchronous way,
  // kept so a benchmark can compare the two: `sortlast render --sync-output`).
  explicit FrameWriter(size_t queue_files);
  // Without finish(): the files not yet written are dropped (the job failed elsewhere), the one
  // being written is completed, and the thread joined.
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Hands over the write of `file` (`write` encodes and writes it). Throws first, as InputError
  // naming its file, the failure of a write handed over before; after one failure no further
  // file is written.
  void push(std::string file, std::function<void()> write);
  // Waits until every file handed over is written, ends the thread, and throws the first failure.
  void finish();

  struct Stats {
    int files = 0;       // written
    double write_s = 0;  // spent encoding and writing (on the writer thread, or in push)
    double wait_s = 0;   // the caller waited for the writer: a full queue, and finish()
  };
  Stats stats() const;

 private:
  struct Job {
    std::string file;
    std::function<void()> write;
  };
  void run(Job& job);  // the write, timed; its failure kept as failure_
  void rethrowFailure();
  void writerLoop();

  const bool sync_;
  BoundedQueue<Job> queue_;
  mutable std::mutex mutex_;  // guards failure_, stats_
  std::string failure_;       // the first failed write's message, naming its file
  bool abandon_ = false;      // the destructor without finish(): write no more
  Stats stats_;
  std::thread thread_;
};

}  // namespace sortlast
