// SPDX-License-Identifier: Apache-2.0
// An input's samples by step (bus/StepSamples.hpp) against std::map, the
// container it stands in for, under the operations Input makes.
#include <cstdint>
#include <iterator>
#include <map>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "bus/StepSamples.hpp"

using flatsat::bus::StepSamples;

TEST_CASE("StepSamples answers as std::map does under inserts, lookups and drops of the oldest", "[bus]") {
  StepSamples<std::string> samples;
  std::map<std::uint64_t, std::string> reference;
  std::mt19937_64 random(7);
  std::uniform_int_distribution<std::uint64_t> step(0, 40);
  for (int n = 0; n < 20000; ++n) {
    const std::uint64_t k = step(random);
    switch (random() % 4) {
      case 0:
      case 1: {  // a sample arrives, perhaps out of order or again
        const std::string value = "sample " + std::to_string(n);
        samples.insert_or_assign(k, value);
        reference.insert_or_assign(k, value);
        break;
      }
      case 2: {  // dropBefore(k)
        samples.erase(samples.begin(), samples.lower_bound(k));
        reference.erase(reference.begin(), reference.lower_bound(k));
        break;
      }
      default: {  // at(k): the newest at or before k
        const auto it = samples.upper_bound(k);
        const auto ref = reference.upper_bound(k);
        REQUIRE((it == samples.begin()) == (ref == reference.begin()));
        if (ref != reference.begin()) CHECK(std::prev(it)->second == std::prev(ref)->second);
      }
    }
    REQUIRE(samples.count(k) == reference.count(k));
    REQUIRE(samples.empty() == reference.empty());
    if (!reference.empty()) REQUIRE(samples.begin()->first == reference.begin()->first);
    REQUIRE(std::distance(samples.begin(), samples.end()) == static_cast<std::ptrdiff_t>(reference.size()));
  }
}
