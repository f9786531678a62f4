// The service's request queue (service/request_queue.h): latest wins per client, clients in turn,
// forget, close.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "service/request_queue.h"

namespace sortlast {
namespace {

using namespace std::chrono_literals;

// Each request records the replies it got (status, error) in a shared log.
struct Answer {
  uint64_t client, id;
  int status;
  std::string error;
};

class Queue : public ::testing::Test {
 protected:
  ServiceRequest request(uint64_t client, uint64_t id) {
    ServiceRequest r;
    r.client = client;
    r.id = id;
    r.reply = [log = log_, client, id](ServiceReply reply) {
      log->push_back({client, id, reply.status, reply.error});
    };
    return r;
  }
  std::shared_ptr<std::vector<Answer>> log_ = std::make_shared<std::vector<Answer>>();
  RequestQueue q_;
};

TEST_F(Queue, LatestWinsPerClientAndCountsTheDropped) {
  q_.push(request(1, 10));
  q_.push(request(1, 11));
  q_.push(request(2, 20));
  q_.push(request(1, 12));
  EXPECT_EQ(q_.pending(), 2u);
  EXPECT_EQ(q_.dropped(), 2u);
  EXPECT_EQ(q_.dropped(1), 2u);
  EXPECT_EQ(q_.dropped(2), 0u);
  ASSERT_EQ(log_->size(), 2u);
  EXPECT_EQ((*log_)[0].id, 10u);
  EXPECT_EQ((*log_)[0].status, 409);
  EXPECT_EQ((*log_)[0].error, "superseded by a newer request");
  EXPECT_EQ((*log_)[1].id, 11u);

  // Client 1 keeps its place in line (it came first) with its newest request.
  auto a = q_.pop(0ms);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->client, 1u);
  EXPECT_EQ(a->id, 12u);
  auto b = q_.pop(0ms);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->id, 20u);
  EXPECT_FALSE(q_.pop(0ms));
  EXPECT_EQ(q_.pending(), 0u);
}

TEST_F(Queue, ClientsTakeTurns) {
  // Client 1 asks again after every frame; clients 2 and 3 must still get theirs in between.
  q_.push(request(1, 1));
  q_.push(request(2, 1));
  q_.push(request(3, 1));
  std::vector<uint64_t> order;
  for (int i = 0; i < 6; ++i) {
    auto r = q_.pop(0ms);
    ASSERT_TRUE(r);
    order.push_back(r->client);
    if (r->client == 1) q_.push(request(1, 2 + i));
  }
  EXPECT_EQ(order, (std::vector<uint64_t>{1, 2, 3, 1, 1, 1}));
}

TEST_F(Queue, RoundRobinUnderContinuousLoad) {
  // Every client resubmits at once after being served: the pops cycle 1, 2, 3, 1, 2, 3, ...
  for (uint64_t c = 1; c <= 3; ++c) q_.push(request(c, 0));
  for (int i = 0; i < 9; ++i) {
    auto r = q_.pop(0ms);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->client, uint64_t(i % 3 + 1)) << "pop " << i;
    q_.push(request(r->client, i));
  }
}

TEST_F(Queue, PopWaitsAndWakesOnPush) {
  auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(q_.pop(30ms));
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 25ms);

  std::thread pusher([&] {
    std::this_thread::sleep_for(20ms);
    q_.push(request(7, 1));
  });
  auto r = q_.pop(5s);
  pusher.join();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->client, 7u);
}

TEST_F(Queue, ForgetAnswers499AndRemoves) {
  q_.push(request(1, 1));
  q_.push(request(1, 2));  // one drop for client 1
  q_.push(request(2, 1));
  q_.forget(1);
  ASSERT_EQ(log_->size(), 2u);
  EXPECT_EQ((*log_)[1].client, 1u);
  EXPECT_EQ((*log_)[1].id, 2u);
  EXPECT_EQ((*log_)[1].status, 499);
  EXPECT_EQ(q_.pending(), 1u);
  EXPECT_EQ(q_.dropped(1), 0u);  // forgotten
  EXPECT_EQ(q_.dropped(), 1u);   // the total stays
  auto r = q_.pop(0ms);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->client, 2u);
  EXPECT_FALSE(q_.pop(0ms));
  q_.forget(42);  // unknown: nothing happens
  EXPECT_EQ(log_->size(), 2u);
}

TEST_F(Queue, CloseWakesAWaitingPop) {
  auto t0 = std::chrono::steady_clock::now();
  std::thread closer([&] {
    std::this_thread::sleep_for(20ms);
    q_.close();
  });
  EXPECT_FALSE(q_.pop(10s));  // woken by close(), not the timeout
  closer.join();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
}

TEST_F(Queue, CloseAnswersPendingAndRefusesNew) {
  q_.push(request(1, 1));
  q_.push(request(2, 1));
  q_.close();
  q_.push(request(3, 1));
  EXPECT_EQ(q_.pending(), 0u);
  EXPECT_FALSE(q_.pop(0ms));
  ASSERT_EQ(log_->size(), 3u);
  for (const auto& a : *log_) {
    EXPECT_EQ(a.status, 503);
    EXPECT_EQ(a.error, "the service is shutting down");
  }
  EXPECT_EQ(log_->back().client, 3u);
}

TEST_F(Queue, ReplyMayCallBackIntoTheQueue) {
  // Replies run outside the lock: a superseded request's callback can push again.
  ServiceRequest first = request(1, 1);
  first.reply = [this](ServiceReply) { EXPECT_EQ(q_.pending(), 1u); };
  q_.push(std::move(first));
  q_.push(request(1, 2));
  EXPECT_EQ(q_.dropped(), 1u);
}

}  // namespace
}  // namespace sortlast
