// `sortlast serve` (serve_job.h): the frame loop of the service. Rank 0 pops requests from the
// front end's queue, checks each against the session (a bad one is answered 400 without bothering
// the other ranks), broadcasts the good ones, renders with everyone, encodes and answers.
#include "master/serve_job.h"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include <unistd.h>

#include "common/error.h"
#include "common/image_encode.h"
#include "master/collective.h"
#include "master/data_dir.h"
#include "master/frame_commands.h"
#include "master/http_server.h"
#include "master/render_session.h"
#include "master/request_queue.h"
#include "master/request_translation.h"

#ifndef SORTLAST_VIEWER_SOURCE_DIR
#define SORTLAST_VIEWER_SOURCE_DIR ""
#endif

namespace sortlast {

namespace {

std::atomic<bool> g_stop{false};

extern "C" void onStopSignal(int) { g_stop.store(true); }

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  // A client that vanishes mid-write must not kill the service.
  signal(SIGPIPE, SIG_IGN);
}

// The viewer's files: --viewer-dir, else installed beside the program (PREFIX/share/sortlast/
// viewer for PREFIX/bin/sortlast), else the source tree's (a build that was not installed).
std::string findViewerDir(const std::string& given) {
  if (!given.empty()) return given;
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    auto installed = exe.parent_path().parent_path() / "share" / "sortlast" / "viewer";
    if (std::filesystem::exists(installed / "index.html")) return installed.string();
  }
  return SORTLAST_VIEWER_SOURCE_DIR;
}

// The scene description GET /api/scene returns, updated by the frame loop, read by the front end.
class SceneInfo {
 public:
  void set(nlohmann::json j) {
    std::lock_guard<std::mutex> lock(mu_);
    info_ = std::move(j);
  }
  nlohmann::json get() const {
    std::lock_guard<std::mutex> lock(mu_);
    return info_;
  }

 private:
  mutable std::mutex mu_;
  nlohmann::json info_;
};

ServiceReply errorReply(int status, const std::string& message) {
  ServiceReply r;
  r.status = status;
  r.error = message;
  return r;
}

SessionOptions sessionOptions(const ServeOptions& opts, const std::string& scene_path,
                              const std::vector<std::string>& overrides) {
  SessionOptions so;
  so.scene = readSceneText(scene_path);
  so.overrides = overrides;
  so.resident = true;
  so.max_image_side = opts.max_image_side;
  so.quiet = opts.quiet;
  return so;
}

// Rank 0's part: the front end and the loop that feeds the other ranks.
class Frontend {
 public:
  Frontend(const ServeOptions& opts, std::unique_ptr<RenderSession>& session)
      : opts_(opts), session_(session) {}

  // Collective with the other ranks' follow(): returns when the service stops.
  void lead(MPI_Comm comm) {
    auto [address, port] = parseListen(opts_.listen);
    ServerOptions so;
    so.address = address;
    so.port = port;
    so.token = opts_.token;
    so.static_dir = findViewerDir(opts_.viewer_dir);
    so.data_dir = opts_.data_dir;
    so.max_body_bytes = opts_.max_body_bytes;
    info_.set(describe());
    server_ = std::make_unique<HttpServer>(so, queue_, [this] { return info_.get(); });
    bool started = true;
    try {
      server_->start();
      std::fprintf(stderr, "sortlast serve: http://%s:%d/ (%d rank(s)); viewer files from %s\n",
                   address.find(':') != std::string::npos ? ("[" + address + "]").c_str() : address.c_str(),
                   server_->port(), size(comm), so.static_dir.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sortlast: error: %s\n", e.what());
      started = false;
    }
    while (started && !g_stop.load()) {
      std::optional<ServiceRequest> req = queue_.pop(std::chrono::milliseconds(100));
      if (!req) continue;
      if (req->kind == "load")
        load(*req, comm);
      else
        frame(*req, comm);
    }
    queue_.close();
    server_->stop();
    sendCommand({Command::kShutdown, ""}, comm);
    if (!started) throw JobFailed{"the service could not start"};
  }

 private:
  static int size(MPI_Comm comm) {
    int n = 1;
    MPI_Comm_size(comm, &n);
    return n;
  }

  nlohmann::json describe() const {
    nlohmann::json j = session_->describe();
    j["data_dir"] = !opts_.data_dir.empty();
    return j;
  }

  void frame(ServiceRequest& req, MPI_Comm comm) {
    const double t_start = MPI_Wtime();
    TranslatedRequest tr;
    FrameRequest fr;
    try {
      tr = translateRequest(req.body);
      fr.overrides = tr.overrides;
      session_->check(fr);  // a bad request never reaches the other ranks
    } catch (const InputError& e) {
      req.reply(errorReply(400, e.what()));
      return;
    }
    sendCommand({Command::kFrame, packOverrides(fr.overrides)}, comm);
    FrameResult result;
    try {
      result = session_->render(fr);
    } catch (const JobFailed& e) {
      req.reply(errorReply(500, "the frame failed: " + e.message));
      return;
    }
    ServiceReply r;
    const double t_encode = MPI_Wtime();
    try {
      r.body = encodeImage(result.image, result.scene.background, tr.format, tr.quality);
    } catch (const InputError& e) {
      req.reply(errorReply(400, e.what()));
      return;
    }
    r.content_type = tr.format == "png" ? "image/png" : "image/jpeg";
    r.stats = std::move(result.stats);
    r.stats["encode_image_s"] = MPI_Wtime() - t_encode;
    r.stats["service_s"] = MPI_Wtime() - t_start;
    r.stats["format"] = tr.format;
    r.stats["dropped"] = queue_.dropped(req.client);
    r.stats["dropped_total"] = queue_.dropped();
    if (r.stats.value("step", 0) != info_step_) {
      info_step_ = r.stats.value("step", 0);
      info_.set(describe());  // the histogram and range of the step now shown
    }
    req.reply(std::move(r));
  }

  void load(ServiceRequest& req, MPI_Comm comm) {
    std::string path = req.body.value("scene", "");
    sendCommand({Command::kLoad, path}, comm);
    try {
      auto next = std::make_unique<RenderSession>(sessionOptions(opts_, path, {}), comm);
      session_ = std::move(next);
    } catch (const JobFailed& e) {
      req.reply(errorReply(400, "cannot load " + path + ": " + e.message));
      return;
    }
    info_step_ = -1;
    info_.set(describe());
    ServiceReply r;
    r.stats = {{"ok", true}, {"scene", path}};
    req.reply(std::move(r));
  }

  const ServeOptions& opts_;
  std::unique_ptr<RenderSession>& session_;
  RequestQueue queue_;
  SceneInfo info_;
  std::unique_ptr<HttpServer> server_;
  int info_step_ = -1;
};

// The other ranks: do what rank 0 says until it says stop.
void follow(std::unique_ptr<RenderSession>& session, const ServeOptions& opts, MPI_Comm comm) {
  for (;;) {
    CommandMessage m = receiveCommand(comm, g_stop, 10.0);
    if (m.gave_up) {
      std::fprintf(stderr, "sortlast: error: stopped by a signal, and rank 0 did not end the service\n");
      MPI_Abort(comm, 1);
    }
    switch (m.command) {
      case Command::kShutdown:
        return;
      case Command::kFrame:
        try {
          FrameRequest fr;
          fr.overrides = unpackOverrides(m.payload);
          session->render(fr);
        } catch (const JobFailed&) {
          // Rank 0 answers the client; the session goes on.
        }
        break;
      case Command::kLoad:
        try {
          auto next = std::make_unique<RenderSession>(sessionOptions(opts, m.payload, {}), comm);
          session = std::move(next);
        } catch (const JobFailed&) {
        }
        break;
    }
  }
}

}  // namespace

bool isDefaultLoopback(const std::string& address) {
  return address == "127.0.0.1" || address == "::1" || address == "localhost";
}

std::pair<std::string, int> parseListen(const std::string& listen) {
  std::string host, port;
  if (!listen.empty() && listen[0] == '[') {
    auto close = listen.find(']');
    if (close == std::string::npos || close + 1 >= listen.size() || listen[close + 1] != ':')
      throw InputError("--listen " + listen + ": expected [ADDRESS]:PORT");
    host = listen.substr(1, close - 1);
    port = listen.substr(close + 2);
  } else {
    auto colon = listen.rfind(':');
    if (colon == std::string::npos || colon == 0)
      throw InputError("--listen " + listen + ": expected ADDRESS:PORT, e.g. 127.0.0.1:8080");
    host = listen.substr(0, colon);
    port = listen.substr(colon + 1);
  }
  char* end = nullptr;
  long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || p < 0 || p > 65535)
    throw InputError("--listen " + listen + ": the port must be a number in [0, 65535] (0: any free port)");
  return {host, int(p)};
}

int runServeJob(const ServeOptions& opts, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  installStopHandlers();
  try {
    std::string scene_path = opts.scene;
    collectively(comm, [&] {
      auto [address, port] = parseListen(opts.listen);
      if (!isDefaultLoopback(address) && opts.token.empty())
        throw InputError("--listen " + opts.listen + " is not the loopback address (127.0.0.1, ::1, "
                         "localhost): others may reach it, so give --token TOKEN");
      if (!opts.data_dir.empty()) {
        if (!std::filesystem::is_directory(opts.data_dir))
          throw InputError("--data-dir " + opts.data_dir + ": not a directory");
        // The scene, given relative to the data directory, must lie inside it.
        if (!scene_path.empty()) scene_path = resolveUnder(opts.data_dir, scene_path).string();
      }
    });
    std::unique_ptr<RenderSession> session;
    {
      SessionOptions so;
      collectively(comm, [&] { so = sessionOptions(opts, scene_path, opts.overrides); });
      session = std::make_unique<RenderSession>(std::move(so), comm);
    }
    if (rank == 0) {
      Frontend frontend(opts, session);
      frontend.lead(comm);
    } else {
      follow(session, opts, comm);
    }
    if (rank == 0 && !opts.quiet) std::fprintf(stderr, "sortlast serve: stopped\n");
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
