#include "common/pixel_threads.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/error.h"

namespace sortlast {

int pixelThreadsFor(int cores_in_mask, int online_cores, int ranks_on_node) {
  const int mask = std::max(1, cores_in_mask);
  const int ranks = std::max(1, ranks_on_node);
  const int online = std::max(mask, online_cores);
  // Ranks that share this rank's cores, assuming the node's ranks spread evenly over its cores.
  const long sharing = std::max(1L, (long(ranks) * mask + online - 1) / online);
  return std::max(1, int(mask / sharing));
}

int affinityCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

#ifndef SORTLAST_SMPI

namespace {

constexpr int kMaxThreads = 256;

// Whether this thread is running a part of a loop (a worker always is): a loop started there
// runs serially.
thread_local bool in_loop = false;

class Pool {
 public:
  ~Pool() { resize(1); }

  int size() const { return int(workers_.size()) + 1; }

  // Joins the workers and starts threads - 1 new ones.
  void resize(int threads) {
    std::lock_guard busy(busy_);
    {
      std::lock_guard lk(m_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
    stop_ = false;
    for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { workerLoop(); });
  }

  void run(int parts, void (*fn)(void*, int), void* ctx) {
    std::unique_lock busy(busy_, std::try_to_lock);
    if (in_loop || !busy.owns_lock() || workers_.empty()) {
      serial(parts, fn, ctx);
      return;
    }
    {
      std::lock_guard lk(m_);
      fn_ = fn;
      ctx_ = ctx;
      parts_ = parts;
      next_.store(0);
      error_ = nullptr;
      open_ = true;
      ++generation_;
    }
    wake_.notify_all();
    in_loop = true;
    work();
    in_loop = false;
    std::unique_lock lk(m_);
    open_ = false;  // a worker waking late does not join a finished loop
    done_.wait(lk, [&] { return active_ == 0; });
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  static void serial(int parts, void (*fn)(void*, int), void* ctx) {
    for (int i = 0; i < parts; ++i) fn(ctx, i);
  }

  void work() {
    for (;;) {
      const int i = next_.fetch_add(1);
      if (i >= parts_) return;
      try {
        fn_(ctx_, i);
      } catch (...) {
        std::lock_guard lk(m_);
        if (!error_) error_ = std::current_exception();
      }
    }
  }

  // Blocks on the condition variable between loops: an idle worker takes no CPU time.
  void workerLoop() {
    in_loop = true;
    uint64_t seen = 0;
    std::unique_lock lk(m_);
    for (;;) {
      wake_.wait(lk, [&] { return stop_ || (open_ && generation_ != seen); });
      if (stop_) return;
      seen = generation_;
      ++active_;
      lk.unlock();
      work();
      lk.lock();
      if (--active_ == 0) done_.notify_all();
    }
  }

  std::mutex busy_;  // held by the thread running a loop (or resizing)
  std::mutex m_;     // guards everything below but next_
  std::condition_variable wake_, done_;
  std::vector<std::thread> workers_;
  bool stop_ = false, open_ = false;
  uint64_t generation_ = 0;
  int active_ = 0;  // workers inside the current loop
  void (*fn_)(void*, int) = nullptr;
  void* ctx_ = nullptr;
  int parts_ = 0;
  std::atomic<int> next_{0};
  std::exception_ptr error_;
};

int envThreads() {
  const char* s = std::getenv("SORTLAST_PIXEL_THREADS");
  if (!s || !*s) return 0;
  char* end = nullptr;
  const long n = std::strtol(s, &end, 10);
  if (*end != '\0' || n < 1 || n > kMaxThreads)
    throw InputError("SORTLAST_PIXEL_THREADS=" + std::string(s) + ": a whole number in [1, " +
                     std::to_string(kMaxThreads) + "]");
  return int(n);
}

Pool& pool() {
  static Pool p;
  return p;
}

std::atomic<int> threads{0};  // 0: not yet chosen

}  // namespace

inline namespace threaded_pixel_loops {

int pixelThreadsFor(int ranks_on_node) {
  if (int n = envThreads()) return n;
  return std::min(kMaxThreads, sortlast::pixelThreadsFor(affinityCores(), int(sysconf(_SC_NPROCESSORS_ONLN)),
                                               ranks_on_node));
}

int pixelThreads() {
  int n = threads.load();
  if (n == 0) {
    setPixelThreads(pixelThreadsFor(1));
    n = threads.load();
  }
  return n;
}

void setPixelThreads(int n) {
  n = std::clamp(n, 1, kMaxThreads);
  if (n == threads.load() && pool().size() == n) return;
  pool().resize(n);
  threads.store(n);
}

namespace detail {
void runParts(int parts, void (*fn)(void*, int), void* ctx) { pool().run(parts, fn, ctx); }
}  // namespace detail

}  // inline namespace threaded_pixel_loops

#endif

}  // namespace sortlast
