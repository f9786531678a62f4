#include "service/http_server.h"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include "service/http_common.h"
#include "service/http_session.h"

namespace sortlast {

using namespace front;

struct HttpServer::Impl {
  explicit Impl(std::shared_ptr<ServerState> s)
      : state(std::move(s)), ioc(std::max(1, state->options.threads)) {}

  void accept();
  void runThread();

  std::shared_ptr<ServerState> state;
  net::io_context ioc;
  tcp::acceptor acceptor{net::make_strand(ioc)};
  net::steady_timer retry{acceptor.get_executor()};
  std::vector<std::thread> threads;
  int port = 0;
  bool started = false, stopped = false;

  std::mutex mu;
  std::condition_variable idle;
  int running = 0;  // threads still inside ioc.run()
};

void HttpServer::Impl::accept() {
  acceptor.async_accept(net::make_strand(ioc), [this](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted || !acceptor.is_open()) return;  // stop()
    if (!ec) {
      // No Nagle: a frame goes out as a header message then the image; with Nagle the second
      // write waited for the client's delayed ACK, 40 ms on Linux, on every frame (measured).
      beast::error_code nodelay_ec;
      socket.set_option(tcp::no_delay(true), nodelay_ec);
      std::make_shared<HttpSession>(std::move(socket), state)->run();
      return accept();
    }
    // Out of file descriptors, say: try again shortly rather than spin or give up.
    retry.expires_after(std::chrono::milliseconds(50));
    retry.async_wait([this](beast::error_code wait_ec) {
      if (!wait_ec) accept();
    });
  });
}

void HttpServer::Impl::runThread() {
  for (;;) {
    try {
      ioc.run();
      break;
    } catch (const std::exception& e) {
      // A handler threw (it should not): log it and keep serving the other connections.
      std::fprintf(stderr, "sortlast serve: front end: %s\n", e.what());
    }
  }
  std::lock_guard lock(mu);
  --running;
  idle.notify_all();
}

HttpServer::HttpServer(ServerOptions options, RequestQueue& queue,
                       std::function<nlohmann::json()> scene_info)
    : impl_(std::make_unique<Impl>(
          std::make_shared<ServerState>(std::move(options), queue, std::move(scene_info)))) {}

HttpServer::~HttpServer() { stop(); }

void HttpServer::start() {
  Impl& m = *impl_;
  if (m.started) throw std::logic_error("HttpServer::start() called twice");
  const ServerOptions& o = m.state->options;
  std::string where = o.address + ":" + std::to_string(o.port);
  beast::error_code ec;
  tcp::resolver resolver(m.ioc);
  auto found = resolver.resolve(o.address, std::to_string(o.port),
                                tcp::resolver::passive | tcp::resolver::numeric_service, ec);
  if (ec || found.empty())
    throw std::runtime_error("cannot listen on " + where + ": " +
                             (ec ? ec.message() : "address not found"));
  tcp::endpoint endpoint = found.begin()->endpoint();
  auto check = [&](const char* what) {
    if (ec)
      throw std::runtime_error("cannot listen on " + where + ": " + what + ": " + ec.message());
  };
  m.acceptor.open(endpoint.protocol(), ec);
  check("open");
  m.acceptor.set_option(net::socket_base::reuse_address(true), ec);
  check("reuse_address");
  m.acceptor.bind(endpoint, ec);
  check("bind");
  m.acceptor.listen(net::socket_base::max_listen_connections, ec);
  check("listen");
  m.port = m.acceptor.local_endpoint().port();

  m.started = true;
  m.accept();
  m.running = std::max(1, o.threads);
  for (int i = 0; i < m.running; ++i) m.threads.emplace_back([&m] { m.runThread(); });
}

int HttpServer::port() const { return impl_->port; }

void HttpServer::stop() {
  Impl& m = *impl_;
  if (!m.started || m.stopped) return;
  m.stopped = true;
  net::post(m.acceptor.get_executor(), [&m] {
    beast::error_code ec;
    m.acceptor.close(ec);
    m.retry.cancel();
  });
  m.state->closeAll();
  // Closed connections finish their handlers quickly and the threads leave run() by themselves;
  // whatever is still busy after this (a handler that never returns) is cut off by ioc.stop().
  {
    std::unique_lock lock(m.mu);
    m.idle.wait_for(lock, std::chrono::milliseconds(1500), [&] { return m.running == 0; });
  }
  m.ioc.stop();
  for (auto& t : m.threads) t.join();
  m.threads.clear();
  m.state->gate->shut();  // before the io_context goes: no reply callback holds its strands after this
}

}  // namespace sortlast
