// The service's WebSocket (/api/stream). The client sends text messages, each a JSON object of
// scene keys plus an optional integer "id"; each becomes a frame request of this connection, so a
// newer message supersedes one still waiting (latest wins). Per request the client gets:
//   {"id": ID, "status": 200, "stats": {...}, "content_type": "image/png"}  then the image (binary)
//   {"id": ID, "status": 4xx/5xx, "error": "...", "stats": {...}, "content_type": ""}
//   {"id": ID, "dropped": true}                     superseded by a newer one, or see below
//   {"id": null, "status": 400, "error": "..."}     not a request (not a JSON object, bad "id")
// ID is null when the message had none. Every request gets exactly one of these answers.
// A client that reads slower than frames come gets at most kMaxUnsentFrames images queued: an
// older unsent frame is replaced by its "dropped" answer, so memory stays bounded and the client
// gets the newest view as soon as it catches up.
#include "service/ws_session.h"

#include <chrono>

namespace sortlast::front {

namespace websocket = beast::websocket;
using json = nlohmann::json;

namespace {

constexpr size_t kMaxUnsentFrames = 2;
// Text-only answers are small, but a client that sends without ever reading could still pile
// them up.
constexpr size_t kMaxUnsentMessages = 64;

std::string droppedAnswer(const json& id) { return oneLine({{"id", id}, {"dropped", true}}); }

}  // namespace

WsSession::WsSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
    : ws_(std::move(socket)), state_(std::move(state)), client_(state_->next_client++) {
  ++state_->connections;
}

WsSession::~WsSession() {
  if (key_) state_->withdraw(key_);
  --state_->connections;
}

void WsSession::run(Request upgrade) {
  key_ = state_->enroll(weak_from_this());
  if (!key_) return closeNow();
  // The WebSocket has its own timeouts: a ping when the client has been quiet for half the idle
  // time, and the connection dropped when it answers nothing (a client that stopped reading).
  beast::get_lowest_layer(ws_).expires_never();
  websocket::stream_base::timeout timeout{};
  timeout.handshake_timeout = std::chrono::seconds(30);
  timeout.idle_timeout = std::chrono::seconds(60);
  timeout.keep_alive_pings = true;
  ws_.set_option(timeout);
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(beast::http::field::server, "sortlast"); }));
  ws_.read_message_max(state_->options.max_body_bytes);
  ws_.async_accept(upgrade, beast::bind_front_handler(&WsSession::onAccept, shared_from_this()));
}

void WsSession::close() {
  net::post(ws_.get_executor(), [self = shared_from_this()] { self->closeNow(); });
}

void WsSession::closeNow() {
  if (closed_) return;
  closed_ = true;
  state_->queue.forget(client_);
  unsent_.clear();
  beast::error_code ec;
  beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ec);
  beast::get_lowest_layer(ws_).close();
}

void WsSession::onAccept(beast::error_code ec) {
  if (ec) return closeNow();
  readMessage();
}

void WsSession::readMessage() {
  if (closed_) return;
  ws_.async_read(buffer_, beast::bind_front_handler(&WsSession::onRead, shared_from_this()));
}

void WsSession::onRead(beast::error_code ec, size_t) {
  // Closed by the client, timed out, or a message over the size limit (Beast answers that one
  // with a close frame): in every case the connection is over.
  if (ec) return closeNow();
  if (ws_.got_text()) {
    handleText(beast::buffers_to_string(buffer_.data()));
  } else {
    enqueue({nullptr,
             oneLine({{"id", nullptr},
                      {"status", 400},
                      {"error", "requests are JSON text messages, not binary"}}),
             std::nullopt});
  }
  buffer_.consume(buffer_.size());
  readMessage();
}

void WsSession::handleText(const std::string& text) {
  auto reject = [&](const json& id, const std::string& why) {
    enqueue({id, oneLine({{"id", id}, {"status", 400}, {"error", why}}), std::nullopt});
  };
  json body;
  try {
    body = json::parse(text);
  } catch (const json::exception& e) {  // parse errors, and numbers beyond a double (1e999)
    return reject(nullptr, std::string("malformed JSON: ") + e.what());
  }
  if (!body.is_object())
    return reject(nullptr, std::string("a request must be a JSON object, not ") + body.type_name());
  json id = nullptr;
  if (auto it = body.find("id"); it != body.end()) {
    if (!it->is_number_unsigned()) return reject(nullptr, "\"id\" must be a non-negative integer");
    id = *it;
    body.erase(it);
  }

  ServiceRequest r;
  r.client = client_;
  r.id = id.is_null() ? 0 : id.get<uint64_t>();
  r.kind = "frame";
  r.body = std::move(body);
  r.reply = state_->replyOn(ws_.get_executor(), [weak = weak_from_this(), id](ServiceReply reply) {
    if (auto self = weak.lock()) self->onReply(id, std::move(reply));
  });
  state_->queue.push(std::move(r));
}

void WsSession::onReply(const json& id, ServiceReply reply) {
  if (closed_ || reply.status == 499) return;
  if (reply.status == 409) return enqueue({id, droppedAnswer(id), std::nullopt});
  json header = {{"id", id}, {"status", reply.status}};
  if (reply.status != 200) header["error"] = reply.error;
  header["stats"] = reply.stats.is_null() ? json::object() : reply.stats;
  header["content_type"] = reply.content_type;
  Outgoing out{id, oneLine(header), std::nullopt};
  if (reply.status == 200) out.image = std::move(reply.body);
  enqueue(std::move(out));
}

void WsSession::enqueue(Outgoing out) {
  if (closed_) return;
  unsent_.push_back(std::move(out));
  size_t frames = 0;
  for (const Outgoing& o : unsent_) frames += o.image ? 1 : 0;
  for (Outgoing& o : unsent_) {
    if (frames <= kMaxUnsentFrames) break;
    if (!o.image) continue;
    o.header = droppedAnswer(o.id);
    o.image.reset();
    --frames;
    ++slow_dropped_;
    ++state_->slow_dropped;
  }
  while (unsent_.size() > kMaxUnsentMessages) {
    unsent_.pop_front();
    ++slow_dropped_;
    ++state_->slow_dropped;
  }
  writeNext();
}

void WsSession::writeNext() {
  if (writing_ || unsent_.empty() || closed_) return;
  writing_ = std::move(unsent_.front());
  unsent_.pop_front();
  image_part_ = false;
  ws_.text(true);
  ws_.async_write(net::buffer(writing_->header),
                  beast::bind_front_handler(&WsSession::onWrite, shared_from_this()));
}

void WsSession::onWrite(beast::error_code ec, size_t) {
  if (ec) return closeNow();
  if (!image_part_ && writing_->image) {
    image_part_ = true;
    ws_.binary(true);
    return ws_.async_write(net::buffer(*writing_->image),
                           beast::bind_front_handler(&WsSession::onWrite, shared_from_this()));
  }
  writing_.reset();
  writeNext();
}

}  // namespace sortlast::front
