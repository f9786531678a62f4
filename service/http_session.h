#pragma once
// One plain HTTP connection of the service's front end (keep-alive: one request at a time). It
// serves the static viewer files and the /api/ routes, and hands a WebSocket upgrade on
// /api/stream over to a WsSession.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "service/http_common.h"

namespace sortlast::front {

class HttpSession : public Connection, public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state);
  ~HttpSession() override;
  void run();
  void close() override;

 private:
  void readRequest();
  void onHeader(beast::error_code ec, size_t bytes);
  void onRead(beast::error_code ec, size_t bytes);
  bool failed(beast::error_code ec);
  void handle(Request&& req);
  void handleApi(Request&& req, const std::string& path, std::string_view query);
  Response staticFile(const Request& req, const std::string& path);
  void record(const Request& req, const nlohmann::json& object);
  void submit(const Request& req, std::string kind, nlohmann::json body);
  void watchHangUp();
  void pollHangUp();
  bool peerHungUp();
  void onReply(ServiceReply reply);
  void send(Response&& res, bool linger = false);
  void onWrite(bool close, beast::error_code ec, size_t bytes);
  void lingerThenClose();
  void closeNow();

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  Response res_;  // the response being written (it must outlive the write)
  http::response<http::empty_body> continue_;  // "100 Continue", for clients that wait for it
  std::shared_ptr<ServerState> state_;
  uint64_t key_ = 0;  // in state_'s registry
  bool closed_ = false;
  bool linger_ = false;

  // A request handed to the frame loop: the response waits for its reply.
  bool waiting_ = false;
  uint64_t client_ = 0;
  std::string kind_;
  unsigned version_ = 11;
  bool keep_alive_ = true;
  bool pipelined_ = false;  // its next request is already waiting: no hang-up to watch for
  // Keeps the session alive until the reply comes (the reply callback holds only a weak_ptr, so
  // a reply after the server is gone touches nothing).
  std::shared_ptr<HttpSession> self_while_waiting_;
  // The hang-up watch's fallback: a peek every kHangUpPoll while waiting (see watchHangUp()).
  net::steady_timer hangup_poll_;

  std::vector<char> drain_;  // lingerThenClose()'s discard buffer
  size_t drained_ = 0;
};

}  // namespace sortlast::front
