#pragma once
// Inside the service's front end (service/http_server.h): what every connection shares, and the
// small helpers the HTTP and WebSocket sessions both use. Not for use outside service/http_*.cpp
// and service/ws_session.cpp.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>
// Boost 1.74's asio/awaitable.hpp uses std::exchange without including <utility> (C++20 builds).
#include <utility>

#include <boost/asio.hpp>
#include <boost/beast.hpp>
#include <nlohmann/json.hpp>

#include "service/http_server.h"
#include "service/request_queue.h"

namespace sortlast::front {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;

// An open connection the server can close when it stops.
class Connection {
 public:
  virtual ~Connection() = default;
  virtual void close() = 0;  // any thread: posts the close to the connection's strand
};

// Reply callbacks live in the queue and may run, or be destroyed, after the server (and its
// io_context) is gone. They post only while the gate is open; stop() shuts it after the threads
// are joined. A callback must not hold its connection's executor itself: a strand's executor
// refers to the io_context's strand service, so destroying it after the io_context is a use
// after free (ASan found it in Server.StopReturnsQuicklyWithConnectionsOpen). The executor
// lives in a slot the gate knows, and shut() empties every live slot while the io_context is
// still there.
struct ReplyGate;
struct ReplySlot {
  explicit ReplySlot(std::shared_ptr<ReplyGate> g, net::any_io_executor e);
  ~ReplySlot();  // empties `exec` under the gate's lock (never alongside shut())
  const std::shared_ptr<ReplyGate> gate;
  std::optional<net::any_io_executor> exec;  // guarded by gate->mu
};
struct ReplyGate {
  std::mutex mu;
  bool open = true;
  std::vector<std::weak_ptr<ReplySlot>> slots;  // the live callbacks' slots (pruned as it grows)
  size_t prune_at = 64;
  void shut();  // closes the gate and drops every live slot's executor
};

struct ServerState {
  ServerState(ServerOptions o, RequestQueue& q, std::function<nlohmann::json()> info)
      : options(std::move(o)), queue(q), scene_info(std::move(info)) {}

  const ServerOptions options;
  RequestQueue& queue;
  const std::function<nlohmann::json()> scene_info;
  const std::shared_ptr<ReplyGate> gate = std::make_shared<ReplyGate>();
  std::atomic<uint64_t> next_client{1};   // queue client ids: one per request or WebSocket
  std::atomic<int> connections{0};        // open HTTP and WebSocket connections
  std::atomic<uint64_t> slow_dropped{0};  // WebSocket frames dropped unsent (slow readers)

  // Registers an open connection; returns its key for withdraw(), or 0 if the server is
  // stopping (the caller closes itself then).
  uint64_t enroll(std::weak_ptr<Connection> c);
  void withdraw(uint64_t key);
  void closeAll();  // stop(): close every enrolled connection, refuse new ones

  // A ServiceRequest::reply that runs `deliver` on `exec` (the connection's strand), whichever
  // thread replies, so the frame loop never waits on a socket; dropped once the gate is shut.
  std::function<void(ServiceReply)> replyOn(net::any_io_executor exec,
                                            std::function<void(ServiceReply)> deliver) const;

 private:
  std::mutex mu_;
  bool stopping_ = false;
  uint64_t next_key_ = 1;
  std::unordered_map<uint64_t, std::weak_ptr<Connection>> live_;
};

// The target split at '?', the path percent-decoded (nullopt if malformed).
struct Target {
  std::optional<std::string> path;
  std::string_view query;
};
Target splitTarget(std::string_view target);
// One query parameter's value, percent-decoded; nullopt if absent.
std::optional<std::string> queryParam(std::string_view query, std::string_view key);

// True when the request carries options.token (Authorization: Bearer, or ?token=), or no token
// is configured. Compares in constant time.
bool authorized(const ServerOptions& options, const Request& req, std::string_view query);

// Responses shaped like the request (HTTP version, keep-alive).
Response jsonResponse(const Request& req, unsigned status, const nlohmann::json& body);
Response errorResponse(const Request& req, unsigned status, const std::string& message);

// Stats for a header or a text message: one line, ASCII, never throws on bad UTF-8.
std::string oneLine(const nlohmann::json& j);

}  // namespace sortlast::front
