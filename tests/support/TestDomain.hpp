// SPDX-License-Identifier: Apache-2.0
#pragma once
// Every test that opens DDS takes its own domain, derived from its pid, so
// parallel tests never see each other (Fast DDS blackbox tests do the same).
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace flatsat::test {

/// An even domain in 10..228, distinct for concurrently running test
/// processes: the domain starts from the pid, and a process holds an
/// exclusive lock on its domain (released when it ends) so that another one
/// moves on to the next free domain. Two rigs on one domain would share a
/// bus and each other's samples. The odd domain after it is the test's too:
/// a run of two spacecraft puts its second rig there (tests/system/FleetTest).
inline std::uint32_t testDomain() {
  static const std::uint32_t domain = [] {
    const auto pid = static_cast<std::uint32_t>(::getpid());
    for (std::uint32_t i = 0; i < 110; ++i) {
      const std::uint32_t d = 10 + 2 * ((pid + i) % 110);
      const std::string lock = "/tmp/flatsat-test-domain-" + std::to_string(d) + ".lock";
      const int fd = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
      if (fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0) return d;  // fd stays open: held to the end
      if (fd >= 0) ::close(fd);
    }
    return 10 + 2 * (pid % 110);
  }();
  return domain;
}

/// Exports FLATSAT_DOMAIN so child processes join the same test domain.
inline std::uint32_t exportTestDomain() {
  const auto domain = testDomain();
  ::setenv("FLATSAT_DOMAIN", std::to_string(domain).c_str(), 1);
  return domain;
}

}  // namespace flatsat::test
