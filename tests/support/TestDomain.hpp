// SPDX-License-Identifier: Apache-2.0
#pragma once
// Every test that opens DDS takes its own domain, derived from its pid, so
// parallel tests never see each other (Fast DDS blackbox tests do the same).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace flatsat::test {

/// 10..229, distinct for concurrently running test processes in practice.
inline std::uint32_t testDomain() { return 10 + static_cast<std::uint32_t>(::getpid()) % 220; }

/// Exports FLATSAT_DOMAIN so child processes join the same test domain.
inline std::uint32_t exportTestDomain() {
  const auto domain = testDomain();
  ::setenv("FLATSAT_DOMAIN", std::to_string(domain).c_str(), 1);
  return domain;
}

}  // namespace flatsat::test
