// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <chrono>

#include "bus/TickLateness.hpp"

using flatsat::bus::TickLateness;
using std::chrono::microseconds;

TEST_CASE("TickLateness gives nearest-rank quantiles of the grant lateness to the microsecond",
          "[bus][tick_lateness]") {
  TickLateness late;
  CHECK(late.quantileUs(0.99) == 0.0);
  // 0.5, 1.5, ..., 99.5 µs: the k-th smallest lies in bin k - 1, whose upper edge is k µs.
  for (int i = 0; i < 100; ++i) late.add(std::chrono::nanoseconds(500 + 1000 * i));
  CHECK(late.quantileUs(0.50) == 50.0);
  CHECK(late.quantileUs(0.99) == 99.0);
  CHECK(late.maxUs() == Approx(99.5));
  CHECK(late.quantileUs(1.0) == Approx(99.5));  // the top bin's edge is past the largest: the largest
  // Early (negative) counts as on time; past the last bin the largest stays exact.
  late.add(microseconds(-20));
  late.add(microseconds(80'000));
  CHECK(late.maxUs() == Approx(80'000.0));
  CHECK(late.quantileUs(1.0) == Approx(80'000.0));
}
