// The service's HTTP routes (all JSON errors are {"error": "..."}):
//   GET  /, /<file>     the viewer's static files (no token: they hold no data)
//   GET  /api/scene     scene_info()
//   GET  /api/health    {"ok", "pending", "dropped", "clients", "slow_dropped"}
//   POST /api/frame     a JSON object of scene keys -> the image; stats in X-Sortlast-Stats
//   GET  /api/files     {"files": [...]}                    (only with a data directory)
//   POST /api/load      {"scene": "rel/path.yaml"} -> JSON  (only with a data directory)
//   POST /api/record    {"path": "rel/name.mp4", "frame_rate", "quality"} starts recording the
//                       frames sent into a movie, {"stop": true} ends it -> JSON (403 without
//                       a record directory)
//   GET  /api/stream    WebSocket upgrade (ws_session.cpp)
// With a token configured, /api/ needs "Authorization: Bearer TOKEN" or ?token=TOKEN.
#include "service/http_session.h"

#include <sys/socket.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <variant>

#include "common/error.h"
#include "service/data_dir.h"
#include "service/ws_session.h"

namespace sortlast::front {

namespace fs = std::filesystem;
namespace websocket = beast::websocket;
using json = nlohmann::json;

namespace {

// A stalled client (one that neither sends its request nor reads our answer) is dropped after
// this long; a frame being rendered does not count, since nothing is read or written meanwhile.
constexpr auto kIdleTimeout = std::chrono::seconds(30);
constexpr auto kHangUpPoll = std::chrono::milliseconds(100);
// After an error answer that leaves part of the request unread (a body over the limit), the rest
// is read and discarded for up to this long before closing, so the client sees the answer rather
// than a connection reset.
constexpr auto kLingerTime = std::chrono::seconds(1);
constexpr size_t kLingerBytes = 64 << 20;

std::string contentType(const fs::path& file) {
  std::string ext = file.extension().string();
  if (ext == ".html" || ext == ".htm") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".txt") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

// The routes under /api/: method and whether they exist only with a data directory.
struct Route {
  std::string_view path;
  http::verb method;
  bool needs_data_dir;
};
constexpr Route kRoutes[] = {
    {"/api/scene", http::verb::get, false},  {"/api/health", http::verb::get, false},
    {"/api/frame", http::verb::post, false}, {"/api/stream", http::verb::get, false},
    {"/api/files", http::verb::get, true},   {"/api/load", http::verb::post, true},
    {"/api/record", http::verb::post, false},
};

// The body as a JSON object, or the reason it is not one. An empty body is an empty object.
std::variant<json, std::string> jsonObject(const std::string& body) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return json::object();
  json j;
  try {
    j = json::parse(body);
  } catch (const json::exception& e) {  // parse errors, and numbers beyond a double (1e999)
    return std::string("malformed JSON: ") + e.what();
  }
  if (!j.is_object())
    return std::string("the request body must be a JSON object, not ") + j.type_name();
  return j;
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
    : stream_(std::move(socket)), state_(std::move(state)), hangup_poll_(stream_.get_executor()) {
  ++state_->connections;
}

HttpSession::~HttpSession() {
  if (key_) state_->withdraw(key_);
  --state_->connections;
}

void HttpSession::run() {
  key_ = state_->enroll(weak_from_this());
  if (!key_) return closeNow();  // the server is stopping
  readRequest();
}

void HttpSession::close() {
  net::post(stream_.get_executor(), [self = shared_from_this()] { self->closeNow(); });
}

void HttpSession::closeNow() {
  if (closed_) return;
  closed_ = true;
  if (waiting_) {
    waiting_ = false;
    state_->queue.forget(client_);
  }
  self_while_waiting_.reset();
  hangup_poll_.cancel();
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
  stream_.close();
}

void HttpSession::readRequest() {
  parser_.emplace();
  parser_->body_limit(state_->options.max_body_bytes);
  stream_.expires_after(kIdleTimeout);
  http::async_read_header(stream_, buffer_, *parser_,
                          beast::bind_front_handler(&HttpSession::onHeader, shared_from_this()));
}

// The header first: a client that sent "Expect: 100-continue" (curl does, for bodies over 1 KiB)
// waits for a go-ahead before the body. A body over the limit is refused here already, from its
// Content-Length.
void HttpSession::onHeader(beast::error_code ec, size_t) {
  if (failed(ec)) return;
  auto readBody = [self = shared_from_this()] {
    http::async_read(self->stream_, self->buffer_, *self->parser_,
                     beast::bind_front_handler(&HttpSession::onRead, self));
  };
  if (!beast::iequals(parser_->get()[http::field::expect], "100-continue")) return readBody();
  continue_ = {http::status::continue_, parser_->get().version()};
  http::async_write(stream_, continue_,
                    [self = shared_from_this(), readBody](beast::error_code ec, size_t) {
                      if (ec) return self->closeNow();
                      readBody();
                    });
}

void HttpSession::onRead(beast::error_code ec, size_t) {
  if (failed(ec)) return;
  handle(parser_->release());
}

// Answers (or just closes, when there is no one to answer) a failed read; false if `ec` is fine.
bool HttpSession::failed(beast::error_code ec) {
  if (!ec && !closed_) return false;
  if (closed_) return true;
  if (ec == http::error::body_limit) {
    Request req = parser_->release();  // the header, so the answer matches its HTTP version
    send(errorResponse(req, 413,
                       "the request body is over the limit of " +
                           std::to_string(state_->options.max_body_bytes) + " bytes"),
         true);
  } else if (ec == http::error::header_limit) {
    send(errorResponse(Request(), 431, "the request header is too large"), true);
  } else if (ec.category() == http::make_error_code(http::error::bad_target).category() &&
             ec != http::error::end_of_stream && ec != http::error::partial_message) {
    send(errorResponse(Request(), 400, "malformed HTTP request: " + ec.message()), true);
  } else {
    closeNow();  // the client closed, timed out or reset: nothing to answer
  }
  return true;
}

void HttpSession::handle(Request&& req) {
  Target target = splitTarget(std::string_view(req.target().data(), req.target().size()));
  if (!target.path) return send(errorResponse(req, 400, "malformed percent-encoding in the path"));
  const std::string& path = *target.path;
  if (path.rfind("/api/", 0) == 0) return handleApi(std::move(req), path, target.query);
  if (websocket::is_upgrade(req)) return send(errorResponse(req, 404, "no WebSocket at " + path));
  if (req.method() != http::verb::get) {
    Response res = errorResponse(req, 405, "static files can only be read (GET)");
    res.set(http::field::allow, "GET");
    return send(std::move(res));
  }
  send(staticFile(req, path));
}

void HttpSession::handleApi(Request&& req, const std::string& path, std::string_view query) {
  if (!authorized(state_->options, req, query))
    return send(errorResponse(req, 401,
                              "missing or wrong token: send \"Authorization: Bearer TOKEN\" or "
                              "add ?token=TOKEN"));
  const Route* route = nullptr;
  for (const Route& r : kRoutes)
    if (r.path == path && (!r.needs_data_dir || !state_->options.data_dir.empty())) route = &r;
  if (!route) return send(errorResponse(req, 404, "no such API route: " + path));
  if (req.method() != route->method) {
    Response res =
        errorResponse(req, 405, path + " takes " + std::string(http::to_string(route->method)));
    res.set(http::field::allow, http::to_string(route->method));
    return send(std::move(res));
  }

  if (path == "/api/stream") {
    if (!websocket::is_upgrade(req))
      return send(errorResponse(req, 426, "/api/stream is a WebSocket: send an upgrade request"));
    // The socket moves to the WebSocket session; this session ends once its handler returns.
    auto ws = std::make_shared<WsSession>(stream_.release_socket(), state_);
    closed_ = true;
    return ws->run(std::move(req));
  }
  if (path == "/api/scene") {
    json info;
    try {
      info = state_->scene_info();
    } catch (const std::exception& e) {
      return send(errorResponse(req, 500, std::string("scene info: ") + e.what()));
    }
    return send(jsonResponse(req, 200, info));
  }
  if (path == "/api/health") {
    return send(jsonResponse(req, 200,
                             {{"ok", true},
                              {"pending", state_->queue.pending()},
                              {"dropped", state_->queue.dropped()},
                              {"clients", state_->connections.load()},
                              {"slow_dropped", state_->slow_dropped.load()}}));
  }
  if (path == "/api/files") {
    try {
      return send(jsonResponse(req, 200, {{"files", listSceneFiles(state_->options.data_dir)}}));
    } catch (const InputError& e) {
      return send(errorResponse(req, 500, e.what()));
    }
  }

  auto body = jsonObject(req.body());
  if (auto* why = std::get_if<std::string>(&body)) return send(errorResponse(req, 400, *why));
  json& object = std::get<json>(body);
  if (path == "/api/frame") return submit(req, "frame", std::move(object));
  if (path == "/api/record") return record(req, object);

  // /api/load: the scene is checked here, so the frame loop only ever sees a file inside the
  // data directory, by its absolute path.
  auto scene = object.find("scene");
  if (scene == object.end() || !scene->is_string())
    return send(
        errorResponse(req, 400, "expected {\"scene\": \"path/relative/to/data-dir.yaml\"}"));
  fs::path resolved;
  try {
    resolved = resolveUnder(state_->options.data_dir, scene->get<std::string>());
  } catch (const InputError& e) {
    return send(errorResponse(req, 400, std::string("scene ") + e.what()));
  }
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec))
    return send(errorResponse(req, 400, "scene \"" + scene->get<std::string>() + "\": not a file"));
  submit(req, "load", {{"scene", resolved.string()}});
}

// POST /api/record: checked here (the keys, their types, the path confined to the record
// directory), so the frame loop only sees a file inside it, by its absolute path.
void HttpSession::record(const Request& req, const json& object) {
  const std::string& dir = state_->options.record_dir;
  if (dir.empty())
    return send(errorResponse(req, 403, "recording is off: the service was started without --record-dir DIR"));
  for (auto it = object.begin(); it != object.end(); ++it)
    if (it.key() != "path" && it.key() != "frame_rate" && it.key() != "quality" && it.key() != "stop")
      return send(errorResponse(req, 400, "record: unknown key '" + it.key() +
                                              "' (expected path, frame_rate, quality, or stop)"));
  if (object.contains("stop")) {
    if (object.size() != 1 || object["stop"] != true)
      return send(errorResponse(req, 400, "record: to stop, send {\"stop\": true} alone"));
    return submit(req, "record", {{"stop", true}});
  }
  auto path = object.find("path");
  if (path == object.end() || !path->is_string())
    return send(errorResponse(
        req, 400, "record: expected {\"path\": \"name.mp4\", \"frame_rate\": 30} or {\"stop\": true}"));
  for (const char* key : {"frame_rate", "quality"})
    if (object.contains(key) && !object[key].is_number_integer())
      return send(errorResponse(req, 400, std::string("record: ") + key + " must be a whole number"));
  json body = object;
  try {
    body["file"] = resolveNewUnder(dir, path->get<std::string>()).string();
  } catch (const InputError& e) {
    return send(errorResponse(req, 400, std::string("record: path ") + e.what()));
  }
  submit(req, "record", std::move(body));
}

Response HttpSession::staticFile(const Request& req, const std::string& path) {
  auto notFound = [&] {
    Response res = errorResponse(req, 404, "not found: " + path);
    return res;
  };
  if (state_->options.static_dir.empty()) return notFound();
  std::string rel = path.substr(1);  // the path starts with '/' (Beast checks the target)
  if (rel.empty() || rel.back() == '/') rel += "index.html";
  fs::path file;
  try {
    file = resolveUnder(state_->options.static_dir, rel);
  } catch (const InputError&) {
    return notFound();
  }
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return notFound();
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) return errorResponse(req, 500, "cannot read " + rel);
  Response res;
  res.version(req.version());
  res.result(http::status::ok);
  res.set(http::field::content_type, contentType(file));
  res.keep_alive(req.keep_alive());
  res.body() = std::move(bytes).str();
  return res;
}

void HttpSession::submit(const Request& req, std::string kind, json body) {
  waiting_ = true;
  pipelined_ = false;
  client_ = state_->next_client++;
  kind_ = kind;
  version_ = req.version();
  keep_alive_ = req.keep_alive();
  self_while_waiting_ = shared_from_this();

  ServiceRequest r;
  r.client = client_;
  r.kind = std::move(kind);
  r.body = std::move(body);
  r.reply = state_->replyOn(stream_.get_executor(), [weak = weak_from_this()](ServiceReply reply) {
    if (auto self = weak.lock()) self->onReply(std::move(reply));
  });
  watchHangUp();
  state_->queue.push(std::move(r));  // may answer at once (503): that reply is posted, not run
}

// While the frame renders nothing is read, so a client that hangs up would go unnoticed until
// its reply is written. Waiting for the socket to turn readable notices it: readable with nothing
// to read means the peer closed, and its request is withdrawn from the queue. The reactor's
// epoll is edge-triggered, and an edge that comes while no wait is queued (between a spurious
// wake-up and the next wait) is lost: a peek every kHangUpPoll bounds how long that can hide a
// hang-up, whatever the reactor does.
void HttpSession::watchHangUp() {
  stream_.socket().async_wait(
      tcp::socket::wait_read,
      net::bind_executor(stream_.get_executor(), [self = shared_from_this()](beast::error_code ec) {
        if (ec || !self->waiting_ || self->closed_) return;
        // The reactor may report readable spuriously (an edge it saw for data already read), so
        // peek rather than trust the wake-up.
        if (self->peerHungUp()) return self->closeNow();
        if (!self->pipelined_) self->watchHangUp();
      }));
  pollHangUp();
}

void HttpSession::pollHangUp() {
  hangup_poll_.expires_after(kHangUpPoll);
  hangup_poll_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (ec || !self->waiting_ || self->closed_) return;
    if (self->peerHungUp()) return self->closeNow();
    if (!self->pipelined_) self->pollHangUp();
  });
}

// A non-blocking peek: closed (0) or reset (error) is a hang-up; bytes waiting mean the client
// pipelined its next request, read after the answer, and the watch stops (the peer is alive).
bool HttpSession::peerHungUp() {
  char byte;
  ssize_t n = ::recv(stream_.socket().native_handle(), &byte, 1, MSG_PEEK | MSG_DONTWAIT);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return false;
  if (n > 0) {
    pipelined_ = true;
    return false;
  }
  return true;
}

void HttpSession::onReply(ServiceReply reply) {
  if (!waiting_ || closed_) return;  // the client went away meanwhile: discard
  waiting_ = false;
  auto self = std::move(self_while_waiting_);
  beast::error_code ec;
  stream_.socket().cancel(ec);  // the hang-up watch
  hangup_poll_.cancel();

  Request shape;  // the original request's version and keep-alive
  shape.version(version_);
  shape.keep_alive(keep_alive_);
  Response res;
  if (reply.status != 200) {
    res = errorResponse(shape, unsigned(reply.status), reply.error);
  } else if (kind_ == "load" || kind_ == "record") {
    res = jsonResponse(shape, 200, reply.stats.is_null() ? json{{"ok", true}} : reply.stats);
  } else {
    res.version(version_);
    res.result(http::status::ok);
    res.keep_alive(keep_alive_);
    res.set(http::field::content_type,
            reply.content_type.empty() ? "application/octet-stream" : reply.content_type);
    res.set(http::field::cache_control, "no-store");
    res.body() = std::move(reply.body);
  }
  if (!reply.stats.is_null()) res.set("X-Sortlast-Stats", oneLine(reply.stats));
  send(std::move(res));
}

void HttpSession::send(Response&& res, bool linger) {
  if (linger) res.keep_alive(false);
  linger_ = linger;
  res_ = std::move(res);
  res_.set(http::field::server, "sortlast");
  res_.prepare_payload();
  stream_.expires_after(kIdleTimeout);
  http::async_write(
      stream_, res_,
      beast::bind_front_handler(&HttpSession::onWrite, shared_from_this(), res_.need_eof()));
}

void HttpSession::onWrite(bool close, beast::error_code ec, size_t) {
  if (closed_) return;
  if (ec) return closeNow();
  if (linger_) return lingerThenClose();
  if (close) return closeNow();
  readRequest();
}

void HttpSession::lingerThenClose() {
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  if (drain_.empty()) {
    drain_.resize(64 << 10);
    stream_.expires_after(kLingerTime);
  }
  stream_.async_read_some(net::buffer(drain_),
                          [self = shared_from_this()](beast::error_code ec, size_t n) {
                            self->drained_ += n;
                            if (ec || self->closed_ || self->drained_ > kLingerBytes)
                              return self->closeNow();
                            self->lingerThenClose();
                          });
}

}  // namespace sortlast::front
