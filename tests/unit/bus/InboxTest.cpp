// SPDX-License-Identifier: Apache-2.0
// A step thread's inbox (bus/Inbox.hpp): what other threads push is taken
// whole, in order, once, however the pushes and the takes interleave.
#include <cstddef>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "bus/Inbox.hpp"

using flatsat::bus::Inbox;

TEST_CASE("Inbox: an empty one gives nothing, a take empties it", "[bus]") {
  Inbox<int> inbox;
  CHECK(inbox.takeAll().empty());
  inbox.push(1);
  inbox.push(2);
  CHECK(inbox.takeAll() == std::vector<int>{1, 2});
  CHECK(inbox.takeAll().empty());
  inbox.push(3);
  CHECK(inbox.takeAll() == std::vector<int>{3});
}

TEST_CASE("Inbox: every item pushed from other threads is taken exactly once, each thread's in order", "[bus]") {
  constexpr int kThreads = 4;
  constexpr int kItems = 20000;
  Inbox<int> inbox;
  std::vector<std::jthread> pushers;
  for (int t = 0; t < kThreads; ++t) {
    pushers.emplace_back([&inbox, t] {
      for (int i = 0; i < kItems; ++i) inbox.push(t * kItems + i);
    });
  }
  std::vector<int> next(kThreads, 0);  // each thread's next expected item
  std::size_t taken = 0;
  while (taken < static_cast<std::size_t>(kThreads * kItems)) {
    for (const int item : inbox.takeAll()) {
      const int t = item / kItems;
      REQUIRE(item % kItems == next[t]);
      ++next[t];
      ++taken;
    }
  }
  CHECK(inbox.takeAll().empty());
}
