// SPDX-License-Identifier: Apache-2.0
#pragma once
// DDS Security files for a test, made by deploy/security/make-certs.sh in a
// temporary directory of this process and removed with it. Needs
// FLATSAT_SOURCE_DIR (the repository root) and FLATSAT_BIN_DIR (where the
// flatsat tool that prints the grants is) from the test's CMakeLists.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/support/Run.hpp"

namespace flatsat::test {

struct Certificates {
  std::filesystem::path dir;
  /// `identities`: space-separated names; empty makes the script's default set.
  explicit Certificates(const std::string& identities = "")
      : dir(std::filesystem::temp_directory_path() /
            ("flatsat-certs-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir);
    const auto made = runCommand("FLATSAT_TOOL=" FLATSAT_BIN_DIR "/flatsat bash " FLATSAT_SOURCE_DIR "/deploy/security/make-certs.sh " +
                                 dir.string() + " " + identities + " 2>&1");
    INFO(made.output);
    REQUIRE(made.exit_code == 0);
  }
  ~Certificates() { std::filesystem::remove_all(dir); }
  Certificates(const Certificates&) = delete;
  Certificates& operator=(const Certificates&) = delete;
};

}  // namespace flatsat::test
