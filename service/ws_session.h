#pragma once
// One WebSocket connection of the service's front end (/api/stream): requests in as JSON text
// messages, frames out as a JSON header followed by the image. The protocol: ws_session.cpp.
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "service/http_common.h"

namespace sortlast::front {

class WsSession : public Connection, public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& socket, std::shared_ptr<ServerState> state);
  ~WsSession() override;
  // Answers the upgrade request (already checked: path and token) and starts reading.
  void run(Request upgrade);
  void close() override;

 private:
  // One answer to the client: a text header and, for a frame, a binary image after it.
  struct Outgoing {
    nlohmann::json id;  // the request's id (null if none)
    std::string header;
    std::optional<std::string> image;
  };

  void onAccept(beast::error_code ec);
  void readMessage();
  void onRead(beast::error_code ec, size_t bytes);
  void handleText(const std::string& text);
  void onReply(const nlohmann::json& id, ServiceReply reply);
  void enqueue(Outgoing out);
  void writeNext();
  void onWrite(beast::error_code ec, size_t bytes);
  void closeNow();

  beast::websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  std::shared_ptr<ServerState> state_;
  uint64_t key_ = 0;     // in state_'s registry
  uint64_t client_ = 0;  // the queue's id for this connection: latest wins per connection
  bool closed_ = false;

  std::optional<Outgoing> writing_;  // being written (its buffers must stay put)
  bool image_part_ = false;          // writing_'s header is out, its image is being written
  std::deque<Outgoing> unsent_;      // bounded: see enqueue()
  uint64_t slow_dropped_ = 0;
};

}  // namespace sortlast::front
