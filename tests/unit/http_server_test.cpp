// The service's HTTP/WebSocket front end (service/http_server.h) on loopback, against a fake frame
// loop that echoes each request's body in its stats. Every client operation runs with a time
// limit (awaitFor), so a server bug fails a test instead of hanging it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast.hpp>
#include <nlohmann/json.hpp>

#include "io/image_encode.h"
#include "service/http_server.h"
#include "service/request_queue.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using json = nlohmann::json;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr const char* kToken = "s3cret";

// Runs one asynchronous operation started by `start(handler)` until it completes, or cancels it
// after `limit` (then the result is timed_out).
template <class Lowest, class Start>
beast::error_code awaitFor(net::io_context& ioc, Lowest& lowest, Start start,
                           std::chrono::milliseconds limit = 5000ms) {
  std::optional<beast::error_code> result;
  ioc.restart();
  start([&](beast::error_code ec, auto&&...) { result = ec; });
  ioc.run_for(limit);
  if (result) return *result;
  lowest.cancel();
  ioc.restart();
  ioc.run_for(1000ms);
  return net::error::timed_out;
}

// A plain HTTP client on one keep-alive connection.
class HttpClient {
 public:
  explicit HttpClient(int port) {
    tcp::endpoint ep(net::ip::make_address("127.0.0.1"), port);
    connected_ = !awaitFor(ioc_, stream_, [&](auto h) { stream_.async_connect(ep, h); });
  }
  bool connected() const { return connected_; }

  beast::error_code write(http::request<http::string_body> req) {
    req_ = std::move(req);
    return awaitFor(ioc_, stream_, [&](auto h) { http::async_write(stream_, req_, h); });
  }
  // The response, or nullopt (with a test failure) on error or timeout.
  std::optional<http::response<http::string_body>> read(std::chrono::milliseconds limit = 5000ms) {
    http::response_parser<http::string_body> parser;
    parser.body_limit(64 << 20);
    auto ec = awaitFor(
        ioc_, stream_, [&](auto h) { http::async_read(stream_, buffer_, parser, h); }, limit);
    if (ec) {
      ADD_FAILURE() << "reading the response: " << ec.message();
      return std::nullopt;
    }
    return parser.release();
  }
  std::optional<http::response<http::string_body>> send(http::request<http::string_body> req) {
    if (auto ec = write(std::move(req))) {
      ADD_FAILURE() << "writing the request: " << ec.message();
      return std::nullopt;
    }
    return read();
  }
  beast::error_code writeRaw(const std::string& bytes) {
    return awaitFor(ioc_, stream_,
                    [&](auto h) { net::async_write(stream_, net::buffer(bytes), h); });
  }
  void close() { stream_.close(); }

 private:
  net::io_context ioc_;
  beast::tcp_stream stream_{ioc_};
  beast::flat_buffer buffer_;
  http::request<http::string_body> req_;
  bool connected_ = false;
};

http::request<http::string_body> request(http::verb method, const std::string& target,
                                         std::string body = "", bool with_token = true) {
  http::request<http::string_body> req(method, target, 11);
  req.set(http::field::host, "127.0.0.1");
  if (with_token) req.set(http::field::authorization, std::string("Bearer ") + kToken);
  if (!body.empty()) req.set(http::field::content_type, "application/json");
  req.body() = std::move(body);
  req.prepare_payload();
  return req;
}

// A WebSocket client of /api/stream.
class WsClient {
 public:
  struct Message {
    bool text;
    std::string data;
  };

  WsClient(int port, const std::string& target = std::string("/api/stream?token=") + kToken) {
    tcp::endpoint ep(net::ip::make_address("127.0.0.1"), port);
    auto& tcp_layer = beast::get_lowest_layer(ws_);
    if (awaitFor(ioc_, tcp_layer, [&](auto h) { tcp_layer.async_connect(ep, h); })) return;
    ws_.read_message_max(64 << 20);
    auto ec = awaitFor(ioc_, tcp_layer,
                       [&](auto h) { ws_.async_handshake(upgrade_, "127.0.0.1", target, h); });
    open_ = !ec;
  }
  bool open() const { return open_; }
  unsigned upgradeStatus() const { return upgrade_.result_int(); }

  beast::error_code sendText(const std::string& text) {
    ws_.text(true);
    return awaitFor(ioc_, beast::get_lowest_layer(ws_),
                    [&](auto h) { ws_.async_write(net::buffer(text), h); });
  }
  std::optional<Message> read(std::chrono::milliseconds limit = 5000ms) {
    beast::flat_buffer buf;
    auto ec = awaitFor(
        ioc_, beast::get_lowest_layer(ws_), [&](auto h) { ws_.async_read(buf, h); }, limit);
    if (ec) return std::nullopt;
    return Message{ws_.got_text(), beast::buffers_to_string(buf.data())};
  }
  void drop() { beast::get_lowest_layer(ws_).close(); }  // no closing handshake: a vanished peer

 private:
  net::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_{ioc_};
  websocket::response_type upgrade_;
  bool open_ = false;
};

// The frame loop's stand-in: pops requests and answers each after `work` (a small PNG, stats
// {"echo": body, "id": id}); {"fail": true} gets 422, {"big": N} an N-byte image.
class FakeLoop {
 public:
  explicit FakeLoop(RequestQueue& q) : queue_(q) {
    ImageRGBA8 img(16, 16);
    for (size_t i = 0; i < img.px.size(); ++i) img.px[i] = uint8_t(i % 4 == 3 ? 255 : i);
    png = encodeImage(img, glm::dvec3(0.0), "png", 0);
    thread_ = std::thread([this] { loop(); });
  }
  ~FakeLoop() {
    stop_ = true;
    thread_.join();
  }
  std::string png;
  std::atomic<int> work_ms{0};
  std::atomic<int> frames{0};
  std::atomic<int> started{0};  // requests taken from the queue (frames counts those answered)

 private:
  void loop() {
    while (!stop_) {
      auto r = queue_.pop(20ms);
      if (!r) continue;
      ++started;
      for (int waited = 0; waited < work_ms && !stop_; waited += 5)
        std::this_thread::sleep_for(5ms);
      ServiceReply reply;
      if (r->kind == "load") {
        reply.stats = {{"ok", true}, {"scene", r->body["scene"]}};
      } else if (r->kind == "record") {
        reply.stats = {{"ok", true}, {"echo", r->body}};
      } else if (r->body.value("fail", false)) {
        reply.status = 422;
        reply.error = "failure requested";
      } else {
        reply.content_type = "image/png";
        reply.body = r->body.contains("big") ? std::string(r->body["big"].get<size_t>(), 'x') : png;
        reply.stats = {{"echo", r->body}, {"id", r->id}};
      }
      ++frames;
      r->reply(std::move(reply));
    }
  }
  RequestQueue& queue_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

class Server : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_http_server_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    fs::create_directories(dir_ / "www" / "sub");
    fs::create_directories(dir_ / "data" / "scenes");
    fs::create_directories(dir_ / "outside");
    write(dir_ / "www" / "index.html", "<html>viewer</html>");
    write(dir_ / "www" / "app.js", "console.log(1);");
    write(dir_ / "www" / "sub" / "style.css", "body{}");
    write(dir_ / "outside" / "secret.txt", "secret");
    write(dir_ / "data" / "a.yaml", "volume: {}\n");
    write(dir_ / "data" / "scenes" / "b.yml", "volume: {}\n");
    fs::create_symlink(dir_ / "outside" / "secret.txt", dir_ / "www" / "leak.txt");

    options_.port = 0;
    options_.token = kToken;
    options_.static_dir = (dir_ / "www").string();
    options_.data_dir = (dir_ / "data").string();
    options_.max_body_bytes = 64 << 10;
  }
  void TearDown() override {
    if (server_) server_->stop();
    queue_.close();
    loop_.reset();
    server_.reset();
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

  void start() {
    loop_ = std::make_unique<FakeLoop>(queue_);
    server_ = std::make_unique<HttpServer>(options_, queue_, [] {
      return json{{"volume", {{"dims", {64, 64, 64}}}}};
    });
    server_->start();
    ASSERT_GT(server_->port(), 0);
  }
  int port() const { return server_->port(); }
  std::optional<http::response<http::string_body>> get(const std::string& target,
                                                       bool with_token = true) {
    HttpClient c(port());
    return c.send(request(http::verb::get, target, "", with_token));
  }
  std::optional<http::response<http::string_body>> post(const std::string& target,
                                                        const std::string& body) {
    HttpClient c(port());
    return c.send(request(http::verb::post, target, body));
  }
  json health() {
    auto res = get("/api/health");
    return res ? json::parse(res->body()) : json();
  }

  fs::path dir_;
  ServerOptions options_;
  RequestQueue queue_;
  std::unique_ptr<FakeLoop> loop_;
  std::unique_ptr<HttpServer> server_;
};

std::string errorOf(const http::response<http::string_body>& res) {
  EXPECT_EQ(res[http::field::content_type], "application/json");
  return json::parse(res.body()).value("error", "");
}

TEST_F(Server, ServesStaticFilesWithoutToken) {
  start();
  auto index = get("/", false);
  ASSERT_TRUE(index);
  EXPECT_EQ(index->result_int(), 200);
  EXPECT_EQ(index->body(), "<html>viewer</html>");
  EXPECT_EQ(index->at(http::field::content_type), "text/html; charset=utf-8");
  auto js = get("/app.js", false);
  ASSERT_TRUE(js);
  EXPECT_EQ(js->result_int(), 200);
  EXPECT_EQ(js->at(http::field::content_type), "text/javascript; charset=utf-8");
  auto css = get("/sub/style.css", false);
  ASSERT_TRUE(css);
  EXPECT_EQ(css->body(), "body{}");
  EXPECT_EQ(css->at(http::field::content_type), "text/css; charset=utf-8");

  for (const char* bad :
       {"/missing.html", "/../outside/secret.txt", "/sub/../../outside/secret.txt",
        "/%2e%2e/outside/secret.txt", "/leak.txt", "/sub"}) {
    auto res = get(bad, false);
    ASSERT_TRUE(res) << bad;
    EXPECT_EQ(res->result_int(), 404) << bad;
    EXPECT_EQ(res->body().find("secret\""), std::string::npos);
    EXPECT_NE(res->body(), "secret") << bad;
  }
  HttpClient c(port());
  auto post = c.send(request(http::verb::post, "/index.html", "{}", false));
  ASSERT_TRUE(post);
  EXPECT_EQ(post->result_int(), 405);
}

TEST_F(Server, ApiNeedsTheToken) {
  start();
  auto none = get("/api/health", false);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->result_int(), 401);
  EXPECT_NE(errorOf(*none).find("token"), std::string::npos);

  HttpClient c(port());
  auto wrong = request(http::verb::get, "/api/health", "", false);
  wrong.set(http::field::authorization, "Bearer s3creT");
  auto res = c.send(wrong);
  ASSERT_TRUE(res);
  EXPECT_EQ(res->result_int(), 401);

  auto header = get("/api/health");
  ASSERT_TRUE(header);
  EXPECT_EQ(header->result_int(), 200);
  json h = json::parse(header->body());
  EXPECT_EQ(h["ok"], true);
  EXPECT_TRUE(h.contains("pending") && h.contains("dropped") && h.contains("clients"));

  auto query = get(std::string("/api/health?x=1&token=") + kToken, false);
  ASSERT_TRUE(query);
  EXPECT_EQ(query->result_int(), 200);
  auto wrong_query = get("/api/health?token=nope", false);
  ASSERT_TRUE(wrong_query);
  EXPECT_EQ(wrong_query->result_int(), 401);

  // The WebSocket too: refused without the token.
  WsClient ws(port(), "/api/stream");
  EXPECT_FALSE(ws.open());
  EXPECT_EQ(ws.upgradeStatus(), 401u);
}

TEST_F(Server, RefusesBadBodies) {
  start();
  auto huge = post("/api/frame", "{\"pad\": \"" + std::string(1 << 20, 'x') + "\"}");
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->result_int(), 413);
  EXPECT_NE(errorOf(*huge).find("limit"), std::string::npos);

  auto malformed = post("/api/frame", "{\"camera\": ");
  ASSERT_TRUE(malformed);
  EXPECT_EQ(malformed->result_int(), 400);
  EXPECT_NE(errorOf(*malformed).find("malformed JSON"), std::string::npos);

  auto array = post("/api/frame", "[1, 2]");
  ASSERT_TRUE(array);
  EXPECT_EQ(array->result_int(), 400);
  EXPECT_NE(errorOf(*array).find("JSON object"), std::string::npos);
  EXPECT_EQ(loop_->frames, 0);
}

TEST_F(Server, UnknownRoutesAndWrongMethods) {
  start();
  auto unknown = get("/api/nope");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->result_int(), 404);
  EXPECT_NE(errorOf(*unknown).find("/api/nope"), std::string::npos);
  auto get_frame = get("/api/frame");
  ASSERT_TRUE(get_frame);
  EXPECT_EQ(get_frame->result_int(), 405);
  EXPECT_EQ(get_frame->at(http::field::allow), "POST");
  auto post_health = post("/api/health", "{}");
  ASSERT_TRUE(post_health);
  EXPECT_EQ(post_health->result_int(), 405);
  auto plain_stream = get("/api/stream");
  ASSERT_TRUE(plain_stream);
  EXPECT_EQ(plain_stream->result_int(), 426);
}

TEST_F(Server, FrameReturnsTheImageAndStats) {
  start();
  HttpClient c(port());
  json body = {{"camera", {{"azimuth", 30}}}, {"format", "png"}};
  for (int i = 0; i < 2; ++i) {  // twice on one keep-alive connection
    auto res = c.send(request(http::verb::post, "/api/frame?ignored=1", body.dump()));
    ASSERT_TRUE(res);
    EXPECT_EQ(res->result_int(), 200);
    EXPECT_EQ(res->at(http::field::content_type), "image/png");
    EXPECT_EQ(res->body(), loop_->png);
    json stats = json::parse(std::string(res->at("X-Sortlast-Stats")));
    EXPECT_EQ(stats["echo"], body);
  }
  auto fail = c.send(request(http::verb::post, "/api/frame", R"({"fail": true})"));
  ASSERT_TRUE(fail);
  EXPECT_EQ(fail->result_int(), 422);
  EXPECT_EQ(errorOf(*fail), "failure requested");

  auto scene = get("/api/scene");
  ASSERT_TRUE(scene);
  EXPECT_EQ(json::parse(scene->body())["volume"]["dims"], json({64, 64, 64}));
}

TEST_F(Server, AnswersExpectContinueBeforeTheBody) {
  start();
  HttpClient c(port());
  std::string body = json{{"pad", std::string(2000, 'x')}}.dump();
  ASSERT_FALSE(c.writeRaw("POST /api/frame HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer " +
                          std::string(kToken) + "\r\nContent-Type: application/json\r\n" +
                          "Content-Length: " + std::to_string(body.size()) +
                          "\r\nExpect: 100-continue\r\n\r\n"));
  auto go_ahead = c.read(2000ms);  // the body is not sent yet: only "100 Continue" can come
  ASSERT_TRUE(go_ahead);
  EXPECT_EQ(go_ahead->result_int(), 100);
  ASSERT_FALSE(c.writeRaw(body));
  auto res = c.read();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->result_int(), 200);
  EXPECT_EQ(res->body(), loop_->png);
}

TEST_F(Server, FilesAndLoadStayInsideTheDataDir) {
  start();
  auto files = get("/api/files");
  ASSERT_TRUE(files);
  EXPECT_EQ(json::parse(files->body())["files"], json({"a.yaml", "scenes/b.yml"}));

  auto load = post("/api/load", R"({"scene": "scenes/b.yml"})");
  ASSERT_TRUE(load);
  EXPECT_EQ(load->result_int(), 200);
  json reply = json::parse(load->body());
  EXPECT_EQ(reply["ok"], true);
  EXPECT_EQ(reply["scene"], fs::canonical(dir_ / "data" / "scenes" / "b.yml").string());

  for (const char* bad : {R"({"scene": "../outside/secret.txt"})", R"({"scene": "/etc/passwd"})",
                          R"({"scene": "none.yaml"})", R"({"scene": "scenes"})", R"({"x": 1})"}) {
    auto res = post("/api/load", bad);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->result_int(), 400) << bad;
  }
}

TEST_F(Server, FilesAndLoadNeedADataDir) {
  options_.data_dir.clear();
  start();
  auto files = get("/api/files");
  ASSERT_TRUE(files);
  EXPECT_EQ(files->result_int(), 404);
  auto load = post("/api/load", R"({"scene": "a.yaml"})");
  ASSERT_TRUE(load);
  EXPECT_EQ(load->result_int(), 404);
}

// POST /api/record: the front end checks the keys and confines the path to --record-dir; the
// frame loop gets the absolute path as "file".
TEST_F(Server, RecordStaysInsideTheRecordDir) {
  options_.record_dir = (dir_ / "data").string();
  start();
  auto start_rec = post("/api/record", R"({"path": "scenes/m.mp4", "frame_rate": 12})");
  ASSERT_TRUE(start_rec);
  EXPECT_EQ(start_rec->result_int(), 200);
  EXPECT_EQ(start_rec->at(http::field::content_type), "application/json");
  json echo = json::parse(start_rec->body())["echo"];
  EXPECT_EQ(echo["file"], (fs::canonical(dir_ / "data" / "scenes") / "m.mp4").string());
  EXPECT_EQ(echo["path"], "scenes/m.mp4");
  EXPECT_EQ(echo["frame_rate"], 12);
  auto stop = post("/api/record", R"({"stop": true})");
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->result_int(), 200);
  EXPECT_EQ(json::parse(stop->body())["echo"], json({{"stop", true}}));
  const int before = loop_->started;
  for (const char* bad : {R"({"path": "../outside/m.mp4"})", R"({"path": "/tmp/m.mp4"})",
                          R"({"path": "nofolder/m.mp4"})", R"({"path": "scenes"})", R"({"path": 1})",
                          R"({"path": "m.mp4", "frame_rate": "x"})", R"({"path": "m.mp4", "quality": 1.5})",
                          R"({"stop": false})", R"({"stop": true, "path": "m.mp4"})", R"({"x": 1})", R"({})"}) {
    auto res = post("/api/record", bad);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->result_int(), 400) << bad;
    EXPECT_NE(errorOf(*res).find("record"), std::string::npos) << bad;
  }
  EXPECT_EQ(loop_->started, before);  // none reached the frame loop
}

TEST_F(Server, RecordNeedsARecordDir) {
  start();
  auto res = post("/api/record", R"({"path": "m.mp4"})");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->result_int(), 403);
  EXPECT_NE(errorOf(*res).find("--record-dir"), std::string::npos);
}

TEST_F(Server, WebSocketRoundTrip) {
  start();
  WsClient ws(port());
  ASSERT_TRUE(ws.open());
  ASSERT_FALSE(ws.sendText(R"({"id": 7, "camera": {"elevation": 10}})"));
  auto header = ws.read();
  ASSERT_TRUE(header);
  ASSERT_TRUE(header->text);
  json h = json::parse(header->data);
  EXPECT_EQ(h["id"], 7);
  EXPECT_EQ(h["status"], 200);
  EXPECT_EQ(h["content_type"], "image/png");
  EXPECT_EQ(h["stats"]["echo"], json({{"camera", {{"elevation", 10}}}}));  // "id" taken out
  EXPECT_EQ(h["stats"]["id"], 7);
  auto image = ws.read();
  ASSERT_TRUE(image);
  EXPECT_FALSE(image->text);
  EXPECT_EQ(image->data, loop_->png);

  // A malformed message is answered, and the connection stays open.
  ASSERT_FALSE(ws.sendText("{oops"));
  auto bad = ws.read();
  ASSERT_TRUE(bad);
  json b = json::parse(bad->data);
  EXPECT_TRUE(b["id"].is_null());
  EXPECT_EQ(b["status"], 400);
  EXPECT_NE(b["error"].get<std::string>().find("malformed JSON"), std::string::npos);

  ASSERT_FALSE(ws.sendText(R"({"id": 8, "fail": true})"));
  auto failed = ws.read();
  ASSERT_TRUE(failed);
  json f = json::parse(failed->data);
  EXPECT_EQ(f["id"], 8);
  EXPECT_EQ(f["status"], 422);
  EXPECT_EQ(f["error"], "failure requested");

  ASSERT_FALSE(ws.sendText(R"({"id": 9})"));
  auto again = ws.read();
  ASSERT_TRUE(again);
  EXPECT_EQ(json::parse(again->data)["id"], 9);
  auto again_image = ws.read();
  ASSERT_TRUE(again_image);
  EXPECT_FALSE(again_image->text);
}

TEST_F(Server, LatestWinsOverWebSocket) {
  start();
  loop_->work_ms = 100;
  WsClient ws(port());
  ASSERT_TRUE(ws.open());
  for (int id = 1; id <= 10; ++id) ASSERT_FALSE(ws.sendText(json{{"id", id}}.dump()));
  int images = 0, dropped = 0;
  bool last_answered = false;
  for (int n = 0; n < 40 && !last_answered; ++n) {
    auto m = ws.read(3000ms);
    ASSERT_TRUE(m) << "no answer for the last request";
    ASSERT_TRUE(m->text);
    json h = json::parse(m->data);
    if (h.value("dropped", false)) {
      ++dropped;
      EXPECT_NE(h["id"], 10);
      continue;
    }
    EXPECT_EQ(h["status"], 200);
    auto image = ws.read();
    ASSERT_TRUE(image);
    EXPECT_FALSE(image->text);
    ++images;
    last_answered = h["id"] == 10;
  }
  EXPECT_TRUE(last_answered);
  EXPECT_LT(images, 10);
  EXPECT_EQ(images + dropped, 10);
  EXPECT_EQ(queue_.dropped(), uint64_t(dropped));
}

TEST_F(Server, TwentyConcurrentClientsAllAnswered) {
  start();
  loop_->work_ms = 5;
  constexpr int kClients = 20;
  std::vector<int> status(kClients, 0);
  std::vector<json> echo(kClients);
  std::vector<std::thread> clients;
  for (int i = 0; i < kClients; ++i)
    clients.emplace_back([&, i] {
      HttpClient c(port());
      auto res = c.send(request(http::verb::post, "/api/frame", json{{"client", i}}.dump()));
      if (!res) return;
      status[i] = res->result_int();
      echo[i] = json::parse(std::string((*res)["X-Sortlast-Stats"]))["echo"];
    });
  for (auto& t : clients) t.join();
  for (int i = 0; i < kClients; ++i) {
    EXPECT_EQ(status[i], 200) << "client " << i;
    EXPECT_EQ(echo[i], json({{"client", i}})) << "client " << i;
  }
}

TEST_F(Server, SlowClientDoesNotStallOthers) {
  start();
  loop_->work_ms = 2;
  // The slow client asks for 2 MiB frames, one every 10 ms, and never reads: far more than the
  // socket buffers hold.
  WsClient slow(port());
  ASSERT_TRUE(slow.open());
  std::atomic<bool> done{false};
  std::thread asker([&] {
    for (int i = 0; i < 60 && !done; ++i) {
      if (slow.sendText(json{{"id", i}, {"big", 2 << 20}}.dump())) break;
      std::this_thread::sleep_for(10ms);
    }
  });
  // Meanwhile another client's frames come back promptly, over both protocols.
  WsClient other(port());
  ASSERT_TRUE(other.open());
  for (int i = 0; i < 10; ++i) {
    auto t0 = Clock::now();
    ASSERT_FALSE(other.sendText(json{{"id", i}}.dump()));
    auto h = other.read(2000ms);
    ASSERT_TRUE(h) << "request " << i;
    EXPECT_EQ(json::parse(h->data)["id"], i);
    ASSERT_TRUE(other.read(2000ms));
    auto http = post("/api/frame", "{}");
    ASSERT_TRUE(http);
    EXPECT_EQ(http->result_int(), 200);
    EXPECT_LT(Clock::now() - t0, 1500ms);
    std::this_thread::sleep_for(50ms);
  }
  done = true;
  asker.join();
  // The server kept at most a couple of unsent frames for the slow client and dropped the rest.
  EXPECT_GT(health().value("slow_dropped", 0), 0);
}

TEST_F(Server, ClientThatHangsUpMidFrameIsForgotten) {
  start();
  // The first frame must outlast everything below even on a loaded machine (CI builds beside it),
  // and each wait allows for a slow wake-up: bounds, not timings.
  loop_->work_ms = 4000;
  auto waitPending = [&](size_t n) {
    for (int i = 0; i < 600 && queue_.pending() != n; ++i) std::this_thread::sleep_for(5ms);
    return queue_.pending();
  };
  HttpClient busy(port());  // its frame is being rendered meanwhile
  ASSERT_FALSE(busy.write(request(http::verb::post, "/api/frame", R"({"n": 1})")));
  // Wait for the loop to take it: an empty queue alone may come before the request is even read
  // (CI once saw busy's request, pushed late, taken for the hung-up client's below).
  for (int i = 0; i < 600 && loop_->started == 0; ++i) std::this_thread::sleep_for(5ms);
  ASSERT_EQ(loop_->started, 1);
  ASSERT_EQ(waitPending(0), 0u);
  ASSERT_EQ(loop_->frames, 0);
  {
    HttpClient gone(port());  // its frame waits in the queue, then it hangs up
    ASSERT_FALSE(gone.write(request(http::verb::post, "/api/frame", R"({"n": 2})")));
    ASSERT_EQ(waitPending(1), 1u);
    gone.close();
    EXPECT_EQ(waitPending(0), 0u) << "the hung-up client's request is withdrawn";
  }
  {
    WsClient ws(port());  // the same over a WebSocket
    ASSERT_TRUE(ws.open());
    ASSERT_FALSE(ws.sendText(R"({"n": 3})"));
    ASSERT_EQ(waitPending(1), 1u);
    ws.drop();
    EXPECT_EQ(waitPending(0), 0u) << "the closed WebSocket's request is withdrawn";
  }
  EXPECT_EQ(loop_->frames, 0) << "all that happened while the first frame rendered";
  auto res = busy.read();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->result_int(), 200);

  // A client that hangs up while its own frame renders: the reply is discarded, the loop goes on.
  {
    HttpClient gone(port());
    ASSERT_FALSE(gone.write(request(http::verb::post, "/api/frame", R"({"n": 4})")));
    std::this_thread::sleep_for(50ms);
    gone.close();
  }
  loop_->work_ms = 0;
  auto after = post("/api/frame", R"({"n": 5})");
  ASSERT_TRUE(after);
  EXPECT_EQ(after->result_int(), 200);
}

TEST_F(Server, StopReturnsQuicklyWithConnectionsOpen) {
  start();
  loop_->work_ms = 1500;
  std::vector<std::unique_ptr<HttpClient>> idle;
  for (int i = 0; i < 3; ++i) {
    idle.push_back(std::make_unique<HttpClient>(port()));
    ASSERT_TRUE(idle.back()->connected());
  }
  WsClient ws(port());
  ASSERT_TRUE(ws.open());
  ASSERT_FALSE(ws.sendText(R"({"id": 1})"));  // being rendered when the server stops
  HttpClient waiting(port());
  ASSERT_FALSE(waiting.write(request(http::verb::post, "/api/frame", "{}")));
  std::this_thread::sleep_for(100ms);

  auto t0 = Clock::now();
  server_->stop();
  EXPECT_LT(Clock::now() - t0, 2000ms);
  server_->stop();  // twice is fine
  // The server is gone; the frame loop's late replies are discarded without harm.
  server_.reset();
  std::this_thread::sleep_for(100ms);
}

TEST_F(Server, StartNamesTheAddressWhenItCannotListen) {
  start();
  options_.port = port();  // taken
  HttpServer second(options_, queue_, [] { return json::object(); });
  try {
    second.start();
    FAIL() << "listening twice on one port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port())), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sortlast
