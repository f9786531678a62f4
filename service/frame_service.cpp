#include "service/frame_service.h"

#include <atomic>
#include <chrono>

#include "common/error.h"
#include "io/image_encode.h"
#include "session/collective.h"
#include "service/request_translation.h"

namespace sortlast {

namespace {

ServiceReply errorReply(int status, const std::string& message) {
  ServiceReply r;
  r.status = status;
  r.error = message;
  return r;
}

}  // namespace

void SceneInfo::set(nlohmann::json j) {
  std::lock_guard<std::mutex> lock(mu_);
  info_ = std::move(j);
}

nlohmann::json SceneInfo::get() const {
  std::lock_guard<std::mutex> lock(mu_);
  return info_;
}

void leadFrame(ServiceRequest& req, RenderSession& session, RequestQueue& queue, MPI_Comm comm,
               const std::vector<std::string>& prefix, FrameRecorder* recorder) {
  const double t_start = MPI_Wtime();
  TranslatedRequest tr;
  FrameRequest fr;
  try {
    tr = translateRequest(req.body);
    fr.overrides = prefix;
    fr.overrides.insert(fr.overrides.end(), tr.overrides.begin(), tr.overrides.end());
    session.check(fr);  // a bad request never reaches the other ranks
  } catch (const InputError& e) {
    req.reply(errorReply(400, e.what()));
    return;
  }
  sendCommand({Command::kFrame, packOverrides(fr.overrides)}, comm);
  FrameResult result;
  try {
    result = session.render(fr);
  } catch (const JobFailed& e) {
    req.reply(errorReply(500, "the frame failed: " + e.message));
    return;
  }
  ServiceReply r;
  const double t_encode = MPI_Wtime();
  try {
    r.body = encodeImage(result.image, result.scene.image.background, tr.format, tr.quality);
  } catch (const InputError& e) {
    req.reply(errorReply(400, e.what()));
    return;
  }
  r.content_type = tr.format == "png" ? "image/png" : "image/jpeg";
  r.stats = std::move(result.stats);
  r.stats["encode_image_s"] = MPI_Wtime() - t_encode;
  r.stats["service_s"] = MPI_Wtime() - t_start;
  r.stats["format"] = tr.format;
  r.stats["dropped"] = queue.dropped(req.client);
  r.stats["dropped_total"] = queue.dropped();
  const bool record = recorder && recorder->recording();
  if (record) r.stats["recording"] = {{"name", recorder->name()}, {"frame", recorder->frames()}};
  req.reply(std::move(r));
  // After the answer: the client does not wait for the hand-over (nor, with the encoder's queue
  // full, for the encoder).
  if (record) recorder->add(std::move(result.image), result.scene.image.background);
}

void followFrame(const CommandMessage& m, RenderSession& session) {
  try {
    FrameRequest fr;
    fr.overrides = unpackOverrides(m.payload);
    session.render(fr);
  } catch (const JobFailed&) {
    // Rank 0 answers the client; the session goes on.
  }
}

LiveView::LiveView(const ServerOptions& options) {
  server_ = std::make_unique<HttpServer>(options, queue_, [this] { return info_.get(); });
  server_->start();
}

LiveView::~LiveView() {
  queue_.close();
  server_->stop();
}

int LiveView::port() const { return server_->port(); }
size_t LiveView::pending() const { return queue_.pending(); }
void LiveView::describe(const RenderSession& session, const std::vector<std::string>& base) {
  try {
    info_.set(session.describe(base));
  } catch (const InputError&) {
    info_.set(session.describe());  // keys this step cannot take (they fail its frames too)
  }
}

void LiveView::answerPending(LiveView* view, RenderSession& session, MPI_Comm comm, double budget_s,
                             const std::vector<std::string>& prefix) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0) {
    static const std::atomic<bool> never{false};
    for (;;) {
      CommandMessage m = receiveCommand(comm, never, 0.0);
      if (m.command != Command::kFrame) return;
      followFrame(m, session);
    }
  }
  const double t0 = MPI_Wtime();
  while (view && MPI_Wtime() - t0 < budget_s) {
    std::optional<ServiceRequest> req = view->queue_.pop(std::chrono::milliseconds(0));
    if (!req) break;
    if (req->kind != "frame") {
      req->reply(errorReply(400, "the live view of a simulation cannot load scenes"));
      continue;
    }
    leadFrame(*req, session, view->queue_, comm, prefix);
  }
  sendCommand({Command::kShutdown, ""}, comm);  // "no more requests this time"
}

}  // namespace sortlast
