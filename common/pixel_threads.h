#pragma once
// The threads a rank's CPU pixel work runs on: float -> RGBA8 conversion, RLE encoding and
// decoding, blending. A small pool of our own rather than oneTBB: the loops are few, flat and
// large (a handful per frame, each a megabyte or more), so a static split into one part per
// thread is all they need and work stealing buys nothing; its workers block on a condition
// variable the moment a loop ends (no spinning to compete with llvmpipe's own threads on the same
// cores); and it adds no library to link, the SMPI build's smpicxx included.
//
// Threads: the caller of a loop runs parts of it too and returns when every part is done. MPI
// stays on the main thread (the job is MPI_THREAD_FUNNELED): a loop body must never call MPI.
// A loop started inside a loop body, or from a second thread while the pool is busy, runs
// serially on its caller, so nesting and concurrent callers cannot deadlock.
//
// In the SMPI build (SORTLAST_SMPI) a simulated host is one core: every loop runs serially on
// its caller, compiled in (an inline namespace keeps those definitions apart from the threaded
// ones where both are linked into one program, as in strategy_model_tests).
#include <cstddef>
#include <type_traits>
#include <utility>

namespace sortlast {

// How many threads `cores_in_mask` cores give a rank when `ranks_on_node` ranks run on a node of
// `online_cores`: ranks bound to disjoint cores (ranks * mask <= online) each use their whole
// mask; ranks sharing one mask split it. At least 1.
int pixelThreadsFor(int cores_in_mask, int online_cores, int ranks_on_node);
// The cores in this process's affinity mask (sched_getaffinity; 1 if it cannot be read).
int affinityCores();

#ifndef SORTLAST_SMPI

inline namespace threaded_pixel_loops {

// The count for this rank (what the session passes to setPixelThreads): SORTLAST_PIXEL_THREADS
// if set (benchmarks and tests; a positive integer), else pixelThreadsFor(affinityCores(),
// online cores, ranks_on_node). `ranks_on_node` from MPI_Comm_split_type(MPI_COMM_TYPE_SHARED).
int pixelThreadsFor(int ranks_on_node);
// The pool's size, caller included. Until set: pixelThreadsFor(1). Set it between frames from
// the main thread, never inside a loop (it joins and restarts the workers when it changes).
int pixelThreads();
void setPixelThreads(int threads);

namespace detail {
void runParts(int parts, void (*fn)(void*, int), void* ctx);
}

// Runs f(part) for part in [0, parts) on the pool; returns when all are done. The first
// exception a part throws is rethrown here (the other parts still run to their end).
template <class F>
void parallelParts(int parts, F&& f) {
  if (parts <= 1) {
    if (parts == 1) f(0);
    return;
  }
  detail::runParts(parts, [](void* c, int i) { (*static_cast<std::remove_reference_t<F>*>(c))(i); },
                   const_cast<void*>(static_cast<const void*>(&f)));
}

#else  // SORTLAST_SMPI: one core a host, every loop serial.

inline namespace serial_pixel_loops {

inline int pixelThreadsFor(int) { return 1; }
inline int pixelThreads() { return 1; }
inline void setPixelThreads(int) {}
template <class F>
void parallelParts(int parts, F&& f) {
  for (int i = 0; i < parts; ++i) f(i);
}

#endif

// How many parts a loop over `n` items is split into: one per thread, but none smaller than
// `min_per_part` items (below that the wake-up of a thread costs more than the part saves).
inline int pixelParts(size_t n, size_t min_per_part) {
  const size_t by_size = min_per_part ? n / min_per_part : n;
  const size_t threads = size_t(pixelThreads());
  return int(by_size < 1 ? 1 : by_size < threads ? by_size : threads);
}

// Item range [begin, end) of part `part` of `parts` over `n` items: contiguous, in order, sizes
// differing by at most one.
inline std::pair<size_t, size_t> partRange(size_t n, int parts, int part) {
  return {n * size_t(part) / size_t(parts), n * size_t(part + 1) / size_t(parts)};
}

// f(begin, end) over contiguous ranges covering [0, n), in parallel.
template <class F>
void parallelFor(size_t n, size_t min_per_part, F&& f) {
  const int parts = pixelParts(n, min_per_part);
  parallelParts(parts, [&](int p) {
    auto [b, e] = partRange(n, parts, p);
    f(b, e);
  });
}

}  // inline namespace threaded_pixel_loops or serial_pixel_loops

}  // namespace sortlast
