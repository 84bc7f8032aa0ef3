// SPDX-License-Identifier: Apache-2.0
// The recorder's live feed: its frames, and a server and client over a real
// abstract Unix socket (no DDS).
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include <catch2/catch.hpp>

#include "bus/LiveFeed.hpp"

namespace flatsat::bus {
namespace {

struct Seen {
  std::string kind_name;
  std::int64_t ns = 0;
  bool alive = false;
  std::string bytes;
};

std::vector<Seen> readAll(LiveFrameReader& reader) {
  std::vector<Seen> seen;
  reader.drain([&](const std::vector<LiveFrame>& frames) {
    for (const auto& f : frames) {
      seen.push_back({std::to_string(static_cast<int>(f.kind)) + ":" + std::string(f.name), f.sim_time_ns, f.alive,
                      std::string(reinterpret_cast<const char*>(f.data), f.size)});
    }
  });
  return seen;
}

std::string threeFrames() {
  std::string stream;
  const std::uint8_t cdr[] = {0, 1, 0, 0, 42, 7};
  appendLiveFrame(stream, LiveFrameKind::kHello, kLiveFeedVersion);
  appendLiveSample(stream, "flatsat/gyro", -5'000'000'000'123, cdr, sizeof cdr);
  appendLiveFrame(stream, LiveFrameKind::kLiveliness, "sun_sensor", false);
  return stream;
}

}  // namespace

TEST_CASE("live feed frames come back whole, in order, however the stream is cut", "[bus][live_feed]") {
  const std::string stream = threeFrames();
  for (std::size_t cut = 1; cut <= stream.size(); cut += 3) {
    LiveFrameReader reader;
    std::vector<Seen> seen;
    for (std::size_t at = 0; at < stream.size(); at += cut) {
      reader.append(stream.data() + at, std::min(cut, stream.size() - at));
      auto more = readAll(reader);
      seen.insert(seen.end(), more.begin(), more.end());
    }
    REQUIRE(seen.size() == 3);
    CHECK(seen[0].kind_name == "0:flatsat-live-1");
    CHECK(seen[1].kind_name == "1:flatsat/gyro");
    CHECK(seen[1].ns == -5'000'000'000'123);
    CHECK(seen[1].bytes == std::string("\0\1\0\0\x2a\7", 6));
    CHECK(seen[2].kind_name == "2:sun_sensor");
    CHECK_FALSE(seen[2].alive);
  }
}

TEST_CASE("a live feed stream that is not one is refused, naming what is wrong", "[bus][live_feed]") {
  auto refused = [](std::string stream) {
    LiveFrameReader reader;
    reader.append(stream.data(), stream.size());
    try {
      readAll(reader);
    } catch (const LiveFeedError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(refused(std::string("\x02\0\0\0\1\0", 6)).find("a frame of 2 bytes") != std::string::npos);
  CHECK(refused(std::string("\xff\xff\xff\x7f", 4)).find("bytes") != std::string::npos);
  CHECK(refused(std::string("\x03\0\0\0\x09\0\0", 7)).find("frame kind 9") != std::string::npos);
  CHECK(refused(std::string("\x03\0\0\0\1\5\0", 7)).find("name longer than its frame") != std::string::npos);
  CHECK(refused(std::string("\x04\0\0\0\1\0\0\1", 8)).find("without its time") != std::string::npos);
  CHECK(refused(std::string("\x05\0\0\0\2\0\0\1\1", 9)).find("liveliness frame of 2 bytes") != std::string::npos);
}

TEST_CASE("a live feed server sends what it gathers to a watcher, and its end", "[bus][live_feed]") {
  const std::string name = "flatsat-live-unit-test-" + std::to_string(::getpid());
  LiveFeedServer server(name);
  CHECK_THROWS_AS(LiveFeedServer(name), LiveFeedError);  // one recorder per name

  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::string> got;
  std::vector<std::size_t> batches;
  std::optional<std::pair<bool, std::string>> closed;
  auto client = LiveFeedClient::connect(
      name,
      [&](const std::vector<LiveFrame>& frames) {
        std::lock_guard lock(mutex);
        batches.push_back(frames.size());
        for (const auto& f : frames) got.push_back(std::string(f.name) + (f.kind == LiveFrameKind::kLiveliness ? (f.alive ? "+" : "-") : ""));
        changed.notify_all();
      },
      [&](bool ended, const std::string& why) {
        std::lock_guard lock(mutex);
        closed = {ended, why};
        changed.notify_all();
      });
  REQUIRE(client);
  for (int i = 0; i < 200 && !server.watched(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  REQUIRE(server.watched());

  const std::uint8_t cdr[] = {0, 1, 0, 0};
  server.sample("flatsat/truth", 100, cdr, sizeof cdr);
  server.sample("flatsat/gyro", 100, cdr, sizeof cdr);
  server.liveliness("gyro", false);
  server.flush();
  server.end();
  std::unique_lock lock(mutex);
  REQUIRE(changed.wait_for(lock, std::chrono::seconds(5), [&] { return closed.has_value(); }));
  CHECK(got == std::vector<std::string>{"flatsat/truth", "flatsat/gyro", "gyro-"});
  CHECK(batches.front() == 3);  // one flush, one batch
  CHECK(closed->first);
  CHECK(closed->second.find("ended its feed") != std::string::npos);
  CHECK(server.framesDropped() == 0);
}

TEST_CASE("a live feed that breaks off without its end is reported so", "[bus][live_feed]") {
  const std::string name = "flatsat-live-unit-test-broken-" + std::to_string(::getpid());
  std::mutex mutex;
  std::condition_variable changed;
  std::optional<std::pair<bool, std::string>> closed;
  auto server = std::make_unique<LiveFeedServer>(name);
  auto client = LiveFeedClient::connect(
      name, [](const std::vector<LiveFrame>&) {},
      [&](bool ended, const std::string& why) {
        std::lock_guard lock(mutex);
        closed = {ended, why};
        changed.notify_all();
      });
  REQUIRE(client);
  for (int i = 0; i < 200 && !server->watched(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  server.reset();  // a recorder that went without ending its feed
  std::unique_lock lock(mutex);
  REQUIRE(changed.wait_for(lock, std::chrono::seconds(5), [&] { return closed.has_value(); }));
  CHECK_FALSE(closed->first);
  CHECK(closed->second.find("without its end") != std::string::npos);
}

TEST_CASE("no live feed to connect to is no client, not an error", "[bus][live_feed]") {
  CHECK(LiveFeedClient::connect("flatsat-live-unit-test-nobody-" + std::to_string(::getpid()),
                                [](const std::vector<LiveFrame>&) {}, [](bool, const std::string&) {}) == nullptr);
}

}  // namespace flatsat::bus

namespace flatsat::bus {

TEST_CASE("a live feed watcher that does not keep up loses whole frames, and the stream stays readable",
          "[bus][live_feed]") {
  const std::string name = "flatsat-live-unit-test-slow-" + std::to_string(::getpid());
  LiveFeedServer server(name);
  std::mutex mutex;
  std::condition_variable changed;
  bool go_on = false;
  std::vector<std::size_t> sizes;
  std::optional<std::string> broke;
  auto client = LiveFeedClient::connect(
      name,
      [&](const std::vector<LiveFrame>& frames) {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return go_on; });  // a watcher stuck for a while
        for (const auto& f : frames) sizes.push_back(f.size);
      },
      [&](bool ended, const std::string& why) {
        std::lock_guard lock(mutex);
        if (!ended) broke = why;
      });
  REQUIRE(client);
  for (int i = 0; i < 200 && !server.watched(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const std::vector<std::uint8_t> big(1 << 20, 7);
  for (int i = 0; i < 24; ++i) {
    server.sample("flatsat/truth", i, big.data(), big.size());
    server.flush();
  }
  CHECK(server.framesDropped() > 0);
  {
    std::lock_guard lock(mutex);
    go_on = true;
  }
  changed.notify_all();
  for (int i = 0; i < 100; ++i) {  // the backlog goes out as the watcher reads
    server.flush();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::lock_guard lock(mutex);
  CHECK_FALSE(broke.has_value());
  CHECK(sizes.size() + server.framesDropped() == 24);
  for (const auto size : sizes) CHECK(size == big.size());
}

}  // namespace flatsat::bus
