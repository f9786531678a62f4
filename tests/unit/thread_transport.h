#pragma once
// Ranks as threads for the compositing tests: a Transport whose messages go through one mailbox
// (radix_k_test.cpp, strategy_model_test.cpp).
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "compositing/pixel_cost.h"
#include "compositing/transport.h"

namespace sortlast {

// Messages between threads; a receive that waits over 20 s fails the test instead of hanging it.
struct Mailbox {
  std::mutex mutex;
  std::condition_variable arrived;
  std::map<std::tuple<int, int, int>, std::deque<std::vector<uint8_t>>> queues;  // from, to, tag
  std::vector<std::map<std::pair<int, int>, int>> sent;  // per rank: (to, tag) -> messages
};

class ThreadTransport final : public Transport {
 public:
  ThreadTransport(Mailbox& box, int rank, int size) : box_(box), rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void send(int to, int tag, std::vector<uint8_t> bytes) override {
    std::lock_guard lock(box_.mutex);
    box_.queues[{rank_, to, tag}].push_back(std::move(bytes));
    ++box_.sent[size_t(rank_)][{to, tag}];
    box_.arrived.notify_all();
  }
  std::vector<uint8_t> receive(int from, int tag) override {
    std::unique_lock lock(box_.mutex);
    auto& q = box_.queues[{from, rank_, tag}];
    if (!box_.arrived.wait_for(lock, std::chrono::seconds(20), [&] { return !q.empty(); }))
      throw std::runtime_error("rank " + std::to_string(rank_) + " waited in vain for rank " +
                               std::to_string(from) + " tag " + std::to_string(tag));
    std::vector<uint8_t> bytes = std::move(q.front());
    q.pop_front();
    return bytes;
  }
  // As MpiTransport's: each part's bytes copied into its rows, charged as MPI's unpacking.
  void receivePlaced(const std::vector<PlacedReceive>& parts) override {
    std::string error;
    for (const PlacedReceive& p : parts) {
      const std::vector<uint8_t> bytes = receive(p.from, p.tag);
      chargePixels(PixelWork::Place, 1LL * p.rows * p.row_bytes / 4);
      if (bytes.size() != size_t(p.rows) * size_t(p.row_bytes)) {
        if (error.empty())
          error = "placed receive: the message from rank " + std::to_string(p.from) +
                  " is not the " + std::to_string(1LL * p.rows * p.row_bytes) +
                  " bytes of its rectangle";
        continue;
      }
      for (int y = 0; y < p.rows; ++y)
        std::memcpy(p.dst + size_t(y) * p.stride, bytes.data() + size_t(y) * size_t(p.row_bytes),
                    size_t(p.row_bytes));
    }
    if (!error.empty()) throw std::runtime_error(error);
  }
  void finishSends() override {}
  std::vector<int> allgather(const std::vector<int>& mine) override {
    std::vector<uint8_t> bytes(mine.size() * sizeof(int));
    std::memcpy(bytes.data(), mine.data(), bytes.size());
    for (int r = 0; r < size_; ++r) {
      std::lock_guard lock(box_.mutex);
      box_.queues[{rank_, r, -1}].push_back(bytes);
      box_.arrived.notify_all();
    }
    std::vector<int> all;
    for (int r = 0; r < size_; ++r) {
      std::vector<uint8_t> b = receive(r, -1);
      std::vector<int> v(b.size() / sizeof(int));
      std::memcpy(v.data(), b.data(), b.size());
      all.insert(all.end(), v.begin(), v.end());
    }
    return all;
  }

 private:
  Mailbox& box_;
  int rank_, size_;
};

}  // namespace sortlast
