// SPDX-License-Identifier: Apache-2.0
// Every file of the fuzz corpus (seeds and the inputs fuzzing found) through
// the same entry point as the fuzzer, in the normal build: found crashes stay
// fixed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/FuzzTargets.hpp"

TEST_CASE("the fuzz corpus replays without a crash", "[fuzz][corpus]") {
  namespace fs = std::filesystem;
  for (const auto& target : flatsat::fuzz::targets()) {
    const fs::path dir = fs::path(FLATSAT_FUZZ_CORPUS) / target.name;
    INFO(dir);
    REQUIRE(fs::is_directory(dir));
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::ifstream in(entry.path(), std::ios::binary);
      const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
      INFO(entry.path());
      CHECK_NOTHROW(target.entry(bytes.data(), bytes.size()));
      ++files;
    }
    CHECK(files > 0);
  }
}
