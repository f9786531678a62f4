#pragma once
// The service's front end: HTTP and WebSocket (Boost.Beast) on its own threads on rank 0. It turns
// client requests into ServiceRequests on a RequestQueue and writes the replies back; it never
// touches MPI or GL, and never blocks the frame loop (a reply only posts a write to the
// connection's strand). Routes, limits and the WebSocket messages: docs in http_session.cpp and
// ws_session.cpp.
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "service/request_queue.h"

namespace sortlast {

struct ServerOptions {
  std::string address = "127.0.0.1";
  int port = 8080;                  // 0: any free port (see HttpServer::port())
  std::string token;                // non-empty: every /api/ request needs it
  std::string static_dir;           // the web viewer's files, served at /
  std::string data_dir;             // non-empty: GET /api/files and POST /api/load are allowed
  std::string record_dir;           // non-empty: POST /api/record may write movies under it
  size_t max_body_bytes = 1 << 20;  // HTTP request bodies and WebSocket messages
  int threads = 2;
};

class HttpServer {
 public:
  // `queue` must outlive the server. `scene_info` is called from the server's threads (GET
  // /api/scene) and must be thread-safe.
  HttpServer(ServerOptions options, RequestQueue& queue,
             std::function<nlohmann::json()> scene_info);
  ~HttpServer();  // stop()s
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds and listens (throws std::runtime_error naming address:port on failure), then starts the
  // threads. Call once.
  void start();
  int port() const;  // the bound port (after start())
  // Closes the listener and every connection and joins the threads; returns within about 2 s.
  // Replies that arrive afterwards are discarded. Safe to call twice.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sortlast
