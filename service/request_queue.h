#pragma once
// The hand-over point between the front end's threads (push, forget) and the frame loop (pop).
// At most one request per client waits: an interactive client only cares about its newest view,
// so a newer request supersedes the pending one (ParaView's "answer the newest, drop the stale").
// Clients take turns (round robin), so one busy client cannot starve the others.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "service/service_protocol.h"

namespace sortlast {

class RequestQueue {
 public:
  // Queues `r` for its client. A pending request of the same client is answered at once with 409
  // and counted as dropped; `r` takes its turn. After close(), `r` is answered at once with 503.
  void push(ServiceRequest r);

  // The next request, clients in turn (a client goes to the back once served); nullopt when none
  // came within `timeout` or the queue is closed.
  std::optional<ServiceRequest> pop(std::chrono::milliseconds timeout);

  // The client went away: its pending request, if any, is answered with 499 and removed.
  void forget(uint64_t client);

  // Answers every pending request with 503 and refuses new ones. pop() returns nullopt from now on.
  void close();

  uint64_t dropped() const;                 // requests superseded, all clients
  uint64_t dropped(uint64_t client) const;  // ... of one client (reset when it is forgotten)
  size_t pending() const;

 private:
  mutable std::mutex mu_;
  std::condition_variable ready_;
  std::unordered_map<uint64_t, ServiceRequest> pending_;  // client -> its one pending request
  std::deque<uint64_t> turn_;                             // clients with a pending request, in turn
  // Only clients that had a drop are here, and forget() erases them: plain HTTP requests each
  // get a new client id, so a counter per id would grow forever.
  std::unordered_map<uint64_t, uint64_t> dropped_by_client_;
  uint64_t dropped_ = 0;
  bool closed_ = false;
};

}  // namespace sortlast
