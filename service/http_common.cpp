#include "service/http_common.h"

#include <algorithm>

#include <vector>

namespace sortlast::front {

uint64_t ServerState::enroll(std::weak_ptr<Connection> c) {
  std::lock_guard lock(mu_);
  if (stopping_) return 0;
  uint64_t key = next_key_++;
  live_.emplace(key, std::move(c));
  return key;
}

void ServerState::withdraw(uint64_t key) {
  std::lock_guard lock(mu_);
  live_.erase(key);
}

void ServerState::closeAll() {
  std::vector<std::shared_ptr<Connection>> open;
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
    for (auto& [key, weak] : live_)
      if (auto c = weak.lock()) open.push_back(std::move(c));
  }
  for (auto& c : open) c->close();
}

ReplySlot::ReplySlot(std::shared_ptr<ReplyGate> g, net::any_io_executor e) : gate(std::move(g)), exec(std::move(e)) {}

ReplySlot::~ReplySlot() {
  std::lock_guard lock(gate->mu);
  exec.reset();
}

void ReplyGate::shut() {
  std::vector<std::shared_ptr<ReplySlot>> live;  // released after the lock: their destructors lock it
  {
    std::lock_guard lock(mu);
    open = false;
    for (auto& w : slots)
      if (auto slot = w.lock()) {
        slot->exec.reset();
        live.push_back(std::move(slot));
      }
    slots.clear();
  }
}

std::function<void(ServiceReply)> ServerState::replyOn(
    net::any_io_executor exec, std::function<void(ServiceReply)> deliver) const {
  auto slot = std::make_shared<ReplySlot>(gate, std::move(exec));
  {
    std::lock_guard lock(gate->mu);
    if (!gate->open) {
      slot->exec.reset();
    } else {
      gate->slots.push_back(slot);
      if (gate->slots.size() >= gate->prune_at) {  // one slot per request: drop the finished ones
        std::erase_if(gate->slots, [](const std::weak_ptr<ReplySlot>& w) { return w.expired(); });
        gate->prune_at = std::max<size_t>(64, 2 * gate->slots.size());
      }
    }
  }
  return [slot = std::move(slot), deliver = std::move(deliver)](ServiceReply r) {
    std::lock_guard lock(slot->gate->mu);
    if (!slot->gate->open || !slot->exec) return;
    net::post(*slot->exec, [deliver, r = std::move(r)]() mutable { deliver(std::move(r)); });
  };
}

namespace {

std::optional<std::string> percentDecode(std::string_view s, bool plus_is_space) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%') {
      if (i + 2 >= s.size()) return std::nullopt;
      int hi = hex(s[i + 1]), lo = hex(s[i + 2]);
      if (hi < 0 || lo < 0) return std::nullopt;
      out.push_back(char(hi * 16 + lo));
      i += 2;
    } else {
      out.push_back(plus_is_space && s[i] == '+' ? ' ' : s[i]);
    }
  }
  // A decoded NUL would cut the name short in the C library underneath std::filesystem.
  if (out.find('\0') != std::string::npos) return std::nullopt;
  return out;
}

// Equal strings take the same time to compare whatever the first differing byte, so a client
// cannot guess the token one byte at a time from response times.
bool constantTimeEqual(std::string_view a, std::string_view b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < a.size(); ++i) diff |= uint8_t(a[i]) ^ uint8_t(i < b.size() ? b[i] : 0);
  return diff == 0;
}

}  // namespace

Target splitTarget(std::string_view target) {
  size_t q = target.find('?');
  Target t;
  t.query = q == std::string_view::npos ? std::string_view() : target.substr(q + 1);
  t.path = percentDecode(target.substr(0, q), false);
  return t;
}

std::optional<std::string> queryParam(std::string_view query, std::string_view key) {
  while (!query.empty()) {
    size_t amp = query.find('&');
    std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    size_t eq = pair.find('=');
    if (pair.substr(0, eq) != key) continue;
    return percentDecode(eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1),
                         true);
  }
  return std::nullopt;
}

bool authorized(const ServerOptions& options, const Request& req, std::string_view query) {
  if (options.token.empty()) return true;
  auto auth = req.find(http::field::authorization);
  if (auth != req.end()) {
    std::string_view value(auth->value().data(), auth->value().size());
    constexpr std::string_view kBearer = "Bearer ";
    if (value.substr(0, kBearer.size()) == kBearer &&
        constantTimeEqual(options.token, value.substr(kBearer.size())))
      return true;
  }
  auto given = queryParam(query, "token");
  return given && constantTimeEqual(options.token, *given);
}

Response jsonResponse(const Request& req, unsigned status, const nlohmann::json& body) {
  Response res;
  res.version(req.version());
  res.result(status >= 100 && status <= 599 ? status : 500);
  res.set(http::field::content_type, "application/json");
  res.set(http::field::cache_control, "no-store");
  res.keep_alive(req.keep_alive());
  res.body() = oneLine(body);
  return res;
}

Response errorResponse(const Request& req, unsigned status, const std::string& message) {
  return jsonResponse(req, status, {{"error", message}});
}

std::string oneLine(const nlohmann::json& j) {
  return j.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

}  // namespace sortlast::front
