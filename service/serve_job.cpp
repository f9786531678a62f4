// `sortlast serve` (serve_job.h): the frame loop of the service. Rank 0 pops requests from the
// front end's queue, checks each against the session (a bad one is answered 400 without bothering
// the other ranks), broadcasts the good ones, renders with everyone, encodes and answers.
#include "service/serve_job.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include <dlfcn.h>
#include <unistd.h>

#include "common/error.h"
#include "common/install_prefix.h"
#include "session/collective.h"
#include "service/data_dir.h"
#include "service/frame_commands.h"
#include "service/frame_service.h"
#include "service/http_server.h"
#include "common/listen_address.h"
#include "session/render_session.h"
#include "service/request_queue.h"
#include "service/token_file.h"

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
  // The accuracy estimate costs about a frame's time where rays are long, and `auto` would run it
  // for every request that edits the transfer function (the soak test's 2,000 requests: 139 s
  // against 19 s). A client asks for it per request (the viewer: on its full frames, after an
  // edit settles); `--set render.estimate=...` makes another default.
  so.overrides = {"render.estimate=off"};
  so.overrides.insert(so.overrides.end(), overrides.begin(), overrides.end());
  so.resident = true;
  so.max_image_side = opts.max_image_side;
  so.quiet = opts.quiet;
  return so;
}

// POST /api/load on every rank: the session is replaced by one of `path`. The old one goes first
// (a session owns the rank's GL context, and two must not overlap); if the new scene fails, the
// old scene is loaded again. The --set keys belong to the scene the service started with (`initial`)
// and apply to it alone. Returns the error message, or "" on success. Collective.
std::string replaceSession(std::unique_ptr<RenderSession>& session, const ServeOptions& opts,
                           const std::string& path, const std::string& initial, std::string& current,
                           MPI_Comm comm) {
  auto open = [&](const std::string& scene) {
    SessionOptions so;
    collectively(comm, [&] {
      so = sessionOptions(opts, scene, scene == initial ? opts.overrides : std::vector<std::string>());
    });
    session = std::make_unique<RenderSession>(std::move(so), comm);
  };
  session.reset();
  try {
    open(path);
    current = path;
    return "";
  } catch (const JobFailed& e) {
    open(current);  // the scene that loaded before loads again (or the service ends)
    return e.message;
  }
}

// Rank 0's part: the front end and the loop that feeds the other ranks.
class Frontend {
 public:
  Frontend(const ServeOptions& opts, std::unique_ptr<RenderSession>& session, std::string scene)
      : opts_(opts), session_(session), initial_(scene), scene_(scene) {}

  // Collective with the other ranks' follow(): returns when the service stops.
  void lead(MPI_Comm comm) {
    auto [address, port] = parseListen(opts_.listen);
    ServerOptions so;
    so.address = address;
    so.port = port;
    so.token = opts_.token;
    so.static_dir = findViewerDir(opts_.viewer_dir);
    so.data_dir = opts_.data_dir;
    so.record_dir = opts_.record_dir;
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
      else if (req->kind == "record")
        record(*req);
      else
        frame(*req, comm);
    }
    queue_.close();
    if (recorder_.recording()) {  // the movie stays playable: its trailer is written
      try {
        const nlohmann::json r = recorder_.stop();
        std::fprintf(stderr, "sortlast serve: recording %s ended with the service: %d frame(s)\n",
                     r.value("name", "").c_str(), r.value("frames", 0));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "sortlast serve: recording: %s\n", e.what());
      }
    }
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
    j["record_dir"] = !opts_.record_dir.empty();
    return j;
  }

  void frame(ServiceRequest& req, MPI_Comm comm) {
    leadFrame(req, *session_, queue_, comm, {}, &recorder_);
    const int step = session_->currentStep();
    if (step != info_step_) {
      info_step_ = step;
      info_.set(describe());  // the histogram and range of the step now shown
    }
  }

  void load(ServiceRequest& req, MPI_Comm comm) {
    std::string path = req.body.value("scene", "");
    // Answer with the name relative to the data directory, as the client gave it.
    std::error_code ec;
    std::string name = std::filesystem::relative(
        path, std::filesystem::weakly_canonical(opts_.data_dir, ec), ec).string();
    sendCommand({Command::kLoad, path}, comm);
    std::string error = replaceSession(session_, opts_, path, initial_, scene_, comm);
    info_step_ = -1;
    info_.set(describe());
    if (!error.empty()) {
      req.reply(errorReply(400, "cannot load " + name + ": " + error));
      return;
    }
    ServiceReply r;
    r.stats = {{"ok", true}, {"scene", name}};
    req.reply(std::move(r));
  }

  // POST /api/record (rank 0 alone): {"stop": true}, or {"path", "file" (resolved under
  // --record-dir by the front end), "frame_rate", "quality"}; the codec keys default to the scene's
  // movie.frame_rate and movie.quality.
  void record(ServiceRequest& req) {
    const nlohmann::json& b = req.body;
    if (b.contains("stop")) {
      if (!recorder_.recording())
        return req.reply(errorReply(409, "not recording: start with {\"path\": \"name.mp4\"}"));
      ServiceReply r;
      try {
        r.stats = recorder_.stop();
      } catch (const InputError& e) {
        return req.reply(errorReply(500, e.what()));
      }
      r.stats["ok"] = true;
      return req.reply(std::move(r));
    }
    const std::string name = b.value("path", "");
    if (recorder_.recording())
      return req.reply(errorReply(409, "already recording " + recorder_.name() +
                                           ": send {\"stop\": true} first"));
    const MovieSpec& movie = session_->baseScene().image.movie;
    // Whole numbers (the front end checked), clamped into int before the recorder's range checks.
    auto whole = [&](const char* key) { return int(std::clamp(b[key].get<long long>(), -1LL, 1000000LL)); };
    const int frame_rate = b.contains("frame_rate") ? whole("frame_rate") : movie.frame_rate;
    std::optional<int> quality;
    if (b.contains("quality")) quality = whole("quality");
    else if (movie.quality) quality = int(*movie.quality);
    try {
      recorder_.start(b.value("file", ""), name, frame_rate, quality);
    } catch (const InputError& e) {
      return req.reply(errorReply(400, std::string("record: ") + e.what()));
    }
    ServiceReply r;
    r.stats = {{"ok", true}, {"recording", name}, {"frame_rate", frame_rate},
               {"quality", quality.value_or(MovieWriter::defaultQuality(name))}};
    req.reply(std::move(r));
  }

  const ServeOptions& opts_;
  std::unique_ptr<RenderSession>& session_;
  const std::string initial_;  // the scene file the service started with
  std::string scene_;          // the scene file the session has now
  RequestQueue queue_;
  SceneInfo info_;
  std::unique_ptr<HttpServer> server_;
  int info_step_ = -1;
  FrameRecorder recorder_;  // POST /api/record
};

// The other ranks: do what rank 0 says until it says stop.
void follow(std::unique_ptr<RenderSession>& session, const ServeOptions& opts, const std::string& initial,
            MPI_Comm comm) {
  std::string scene = initial;
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
        followFrame(m, *session);
        break;
      case Command::kLoad:
        replaceSession(session, opts, m.payload, initial, scene, comm);
        break;
    }
  }
}

}  // namespace

std::string findViewerDir(const std::string& given) {
  if (!given.empty()) return given;
  // The binaries we run in, each with the folder it is installed in under the prefix: the program
  // (<prefix>/BINDIR), and for a simulation linking libsortlast.so the library (<prefix>/LIBDIR:
  // Debian's lib/x86_64-linux-gnu, where "../share" would miss). The viewer is under
  // <prefix>/DATADIR/sortlast/viewer (GNUInstallDirs), else at the install path configured in,
  // else in the source tree (a build tree's program).
  std::vector<std::filesystem::path> candidates;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(installPrefixOf(exe, SORTLAST_INSTALL_BINDIR));
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&findViewerDir), &info) && info.dli_fname)
    candidates.push_back(installPrefixOf(std::filesystem::absolute(info.dli_fname), SORTLAST_INSTALL_LIBDIR));
  for (auto& prefix : candidates)
    if (!prefix.empty()) prefix = prefix / SORTLAST_INSTALL_DATADIR / "sortlast" / "viewer";
  candidates.push_back(SORTLAST_VIEWER_INSTALL_DIR);
  for (const auto& dir : candidates)
    if (!dir.empty() && std::filesystem::exists(dir / "index.html")) return dir.string();
  return SORTLAST_VIEWER_SOURCE_DIR;
}

int runServeJob(const ServeOptions& given, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  installStopHandlers();
  ServeOptions opts = given;
  try {
    std::string scene_path = opts.scene;
    collectively(comm, [&] {
      auto [address, port] = parseListen(opts.listen);
      if (!isDefaultLoopback(address) && opts.token.empty() && opts.token_file.empty())
        throw InputError("--listen " + opts.listen + " is not the loopback address (127.0.0.1, ::1, "
                         "localhost): others may reach it, so give --token-file PATH (or --token TOKEN)");
      if (!opts.token.empty() && !opts.token_file.empty())
        throw InputError("--token and --token-file: give one of them");
      // Only rank 0 answers requests, so only it reads the file (the other ranks' nodes need not
      // see it); a bad file still stops every rank here.
      if (rank == 0 && !opts.token_file.empty()) opts.token = readTokenFile(opts.token_file);
      if (rank == 0 && !given.token.empty())
        std::fprintf(stderr, "sortlast serve: warning: --token is on the command line, which every "
                     "user of this node can read (ps, /proc/PID/cmdline); use --token-file PATH\n");
      if (!opts.data_dir.empty()) {
        if (!std::filesystem::is_directory(opts.data_dir))
          throw InputError("--data-dir " + opts.data_dir + ": not a directory");
        // The scene, given relative to the data directory, must lie inside it.
        if (!scene_path.empty()) scene_path = resolveUnder(opts.data_dir, scene_path).string();
      }
      if (!opts.record_dir.empty() && !std::filesystem::is_directory(opts.record_dir))
        throw InputError("--record-dir " + opts.record_dir + ": not a directory");
    });
    std::unique_ptr<RenderSession> session;
    {
      SessionOptions so;
      collectively(comm, [&] { so = sessionOptions(opts, scene_path, opts.overrides); });
      session = std::make_unique<RenderSession>(std::move(so), comm);
    }
    if (rank == 0) {
      Frontend frontend(opts, session, scene_path);
      frontend.lead(comm);
    } else {
      follow(session, opts, scene_path, comm);
    }
    if (rank == 0 && !opts.quiet) std::fprintf(stderr, "sortlast serve: stopped\n");
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
