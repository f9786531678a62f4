#include "service/request_queue.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace sortlast {

namespace {

// Replies run outside the lock: a reply callback may take its own locks (or, in a test, call
// back into the queue), and the frame loop must not wait on a slow callback.
void answer(ServiceRequest& r, int status, const char* error) {
  if (!r.reply) return;
  ServiceReply reply;
  reply.status = status;
  reply.error = error;
  r.reply(std::move(reply));
}

}  // namespace

void RequestQueue::push(ServiceRequest r) {
  std::optional<ServiceRequest> superseded;
  bool refused = false;
  {
    std::lock_guard lock(mu_);
    if (closed_) {
      refused = true;
    } else {
      auto it = pending_.find(r.client);
      if (it == pending_.end()) {
        turn_.push_back(r.client);
        pending_.emplace(r.client, std::move(r));
      } else {
        // Keeps the client's place in line: the newer request is what it was waiting for.
        superseded = std::move(it->second);
        it->second = std::move(r);
        ++dropped_;
        ++dropped_by_client_[superseded->client];
      }
      ready_.notify_one();
    }
  }
  if (superseded) {
    answer(*superseded, 409, "superseded by a newer request");
  } else if (refused) {
    answer(r, 503, "the service is shutting down");
  }
}

std::optional<ServiceRequest> RequestQueue::pop(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  if (!ready_.wait_for(lock, timeout, [&] { return closed_ || !turn_.empty(); })) return {};
  if (closed_) return {};
  uint64_t client = turn_.front();
  turn_.pop_front();
  auto it = pending_.find(client);
  ServiceRequest r = std::move(it->second);
  pending_.erase(it);
  return r;
}

void RequestQueue::forget(uint64_t client) {
  std::optional<ServiceRequest> gone;
  {
    std::lock_guard lock(mu_);
    dropped_by_client_.erase(client);
    auto it = pending_.find(client);
    if (it == pending_.end()) return;
    gone = std::move(it->second);
    pending_.erase(it);
    turn_.erase(std::find(turn_.begin(), turn_.end(), client));
  }
  answer(*gone, 499, "client went away");
}

void RequestQueue::close() {
  std::vector<ServiceRequest> refused;
  {
    std::lock_guard lock(mu_);
    closed_ = true;
    for (uint64_t client : turn_) refused.push_back(std::move(pending_.at(client)));
    pending_.clear();
    turn_.clear();
    ready_.notify_all();
  }
  for (auto& r : refused) answer(r, 503, "the service is shutting down");
}

uint64_t RequestQueue::dropped() const {
  std::lock_guard lock(mu_);
  return dropped_;
}

uint64_t RequestQueue::dropped(uint64_t client) const {
  std::lock_guard lock(mu_);
  auto it = dropped_by_client_.find(client);
  return it == dropped_by_client_.end() ? 0 : it->second;
}

size_t RequestQueue::pending() const {
  std::lock_guard lock(mu_);
  return pending_.size();
}

}  // namespace sortlast
