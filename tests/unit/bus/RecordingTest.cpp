// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>

#include "bus/Recording.hpp"

using flatsat::bus::Recording;

namespace {

std::vector<std::pair<std::uint64_t, std::string>> visit(const Recording& r, Recording::Order order) {
  std::vector<std::pair<std::uint64_t, std::string>> seen;
  r.forEach("t", [&](std::uint64_t step, const std::string& source, const std::vector<std::uint8_t>&) {
    seen.emplace_back(step, source);
  }, order);
  return seen;
}

}  // namespace

TEST_CASE("Recording visits a topic in step order or in arrival order", "[recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-order-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    // A hand-over as the recorder sees it: the bridge's first sample carries an
    // older step than the emulator's last one.
    Recording r(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step : {300, 301, 302, 303}) r.insert("t", step, "emulator", 0, {1});
    for (std::uint64_t step : {301, 303, 304}) r.insert("t", step, "bridge", 0, {2});
    r.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  using Seen = std::vector<std::pair<std::uint64_t, std::string>>;
  CHECK(visit(r, Recording::Order::kArrival) ==
        Seen{{300, "emulator"}, {301, "emulator"}, {302, "emulator"}, {303, "emulator"},
             {301, "bridge"}, {303, "bridge"}, {304, "bridge"}});
  CHECK(visit(r, Recording::Order::kStep) ==
        Seen{{300, "emulator"}, {301, "bridge"}, {301, "emulator"}, {302, "emulator"},
             {303, "bridge"}, {303, "emulator"}, {304, "bridge"}});
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("Recording finds a topic's last step and erases what came after a step", "[recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-erase-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    Recording r(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step = 0; step < 10; ++step) r.insert("a", step, "x", 0, {1});
    for (std::uint64_t step = 0; step < 10; step += 5) r.insert("b", step, "y", 0, {2});
    CHECK(r.lastStep("a") == 9u);
    CHECK(r.lastStep("b") == 5u);
    CHECK_FALSE(r.lastStep("c").has_value());
    r.eraseAfter(6);
    r.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  CHECK(r.count("a") == 7);  // steps 0..6
  CHECK(r.count("b") == 2);
  CHECK(r.lastStep("a") == 6u);
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}
