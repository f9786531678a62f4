#pragma once
// Answering clients' frame requests with a session, the part `sortlast serve` and the in-situ live
// view share: rank 0 checks a request (a bad one is answered 400 without bothering the other
// ranks), broadcasts it, renders with everyone, encodes and answers; the other ranks render what
// it broadcast. The front end (HTTP, WebSocket) is service/http_server.h.
#include <mpi.h>

#include <memory>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "service/frame_commands.h"
#include "service/frame_recorder.h"
#include "service/http_server.h"
#include "session/render_session.h"
#include "service/request_queue.h"

namespace sortlast {

// The scene description GET /api/scene returns: written by the frame loop, read by the front end.
class SceneInfo {
 public:
  void set(nlohmann::json j);
  nlohmann::json get() const;

 private:
  mutable std::mutex mu_;
  nlohmann::json info_;
};

// Rank 0: one frame request through the session on every rank, answered. Collective with
// followFrame() on the other ranks (when the request is good enough to broadcast).
// `prefix`: keys applied before the request's own (the in-situ live view: the first render's).
// `recorder`: while it records, every frame answered goes to it too (after the answer).
void leadFrame(ServiceRequest& req, RenderSession& session, RequestQueue& queue, MPI_Comm comm,
               const std::vector<std::string>& prefix = {}, FrameRecorder* recorder = nullptr);

// The other ranks: render the frame rank 0 broadcast (Command::kFrame).
void followFrame(const CommandMessage& m, RenderSession& session);

// Rank 0's front end for the in-situ live view: the HTTP/WebSocket server and its queue, answered
// between the simulation's steps.
class LiveView {
 public:
  // Rank 0 only. Throws std::runtime_error if it cannot listen.
  LiveView(const ServerOptions& options);
  ~LiveView();
  int port() const;
  size_t pending() const;
  // What GET /api/scene shows now; `base` as in RenderSession::describe.
  void describe(const RenderSession& session, const std::vector<std::string>& base = {});
  // Collective (rank 0 with a LiveView, the others with null): rank 0 answers requests until
  // none is pending or `budget_s` has passed; the others follow.
  static void answerPending(LiveView* view, RenderSession& session, MPI_Comm comm, double budget_s,
                            const std::vector<std::string>& prefix = {});

 private:
  RequestQueue queue_;
  SceneInfo info_;
  std::unique_ptr<HttpServer> server_;
};

}  // namespace sortlast
