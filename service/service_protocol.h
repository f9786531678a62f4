#pragma once
// What the HTTP/WebSocket front end (service/http_server.h, its own threads on rank 0) and the frame
// loop (service/serve_job.cpp, rank 0's main thread, which drives every MPI rank) hand each other.
// The front end never touches MPI or GL; the frame loop never touches a socket. Everything here is
// thread-safe.
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace sortlast {

// The answer to one frame request, made by the frame loop.
struct ServiceReply {
  int status = 200;          // 200, or 4xx/5xx with `error` set
  std::string error;         // message naming the problem (status != 200)
  std::string content_type;  // image/png or image/jpeg (status 200)
  std::string body;          // the encoded image (status 200)
  nlohmann::json stats;      // the frame's stats (the --stats fields, the resolved camera, ...)
};

// One frame request from a client, queued by the front end for the frame loop.
struct ServiceRequest {
  uint64_t client = 0;   // one id per WebSocket connection; each plain HTTP request gets its own
  uint64_t id = 0;       // the client's own request id (WebSocket "id"), echoed in the reply
  // "frame": render `body`. "load" (only with --data-dir): replace the session's scene with the
  // scene file body["scene"], a path relative to the data directory; the reply has no image.
  std::string kind = "frame";
  nlohmann::json body;   // a JSON object: scene keys (dotted or nested) plus format/quality
  // Called exactly once, from any thread (the frame loop, or the queue when the request is
  // superseded or the service stops). Must not block: the front end queues the write.
  std::function<void(ServiceReply)> reply;
};

}  // namespace sortlast
