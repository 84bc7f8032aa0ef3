// SPDX-License-Identifier: Apache-2.0
// ctest registers each Catch test case under its name (catch_discover_tests);
// a ';' there is CMake's list separator, so the case would be split into
// two ctest entries that match no case and pass without running anything.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

TEST_CASE("no test case name holds a semicolon (ctest would split it and run nothing)", "[tests]") {
  const std::regex name(R"re(TEST_CASE\(\s*"([^"]*)")re");
  int cases = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(FLATSAT_SOURCE_DIR "/tests")) {
    if (entry.path().extension() != ".cpp") continue;
    std::stringstream text;
    text << std::ifstream(entry.path()).rdbuf();
    const std::string source = text.str();
    for (std::sregex_iterator it(source.begin(), source.end(), name), end; it != end; ++it) {
      ++cases;
      INFO(entry.path().string() << ": " << (*it)[1]);
      CHECK((*it)[1].str().find(';') == std::string::npos);
    }
  }
  CHECK(cases > 300);
}

TEST_CASE("every unit test of a component is selected by its component's tag", "[tests]") {
  // One selector per component (tests/README.md): `unit_tests "[<folder under components/>]"`,
  // `[common]` for what several share.
  std::vector<std::string> tags = {"[common]"};
  for (const auto& entry : std::filesystem::directory_iterator(FLATSAT_SOURCE_DIR "/components")) {
    if (entry.is_directory() && entry.path().filename() != "common") {
      tags.push_back("[" + entry.path().filename().string() + "]");
    }
  }
  const std::regex test_case(R"re(TEST_CASE\(\s*(?:"(?:[^"\\]|\\.)*"\s*)+,\s*"([^"]*)")re");
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FLATSAT_SOURCE_DIR "/tests/unit/components")) {
    if (entry.path().extension() != ".cpp") continue;
    std::stringstream text;
    text << std::ifstream(entry.path()).rdbuf();
    const std::string source = text.str();
    for (std::sregex_iterator it(source.begin(), source.end(), test_case), end; it != end; ++it) {
      ++cases;
      const std::string case_tags = (*it)[1];
      INFO(entry.path().filename().string() << ": " << case_tags);
      CHECK(std::any_of(tags.begin(), tags.end(),
                        [&](const std::string& tag) { return case_tags.find(tag) != std::string::npos; }));
    }
  }
  CHECK(cases > 100);
}
