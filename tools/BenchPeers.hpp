// SPDX-License-Identifier: Apache-2.0
#pragma once
// What `flatsat bench`'s measurements share: their domain and their peer processes.
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace flatsat::tools {

/// How long a peer waits for the bench before it gives up (an orphan exits).
inline constexpr auto kPeerTimeout = std::chrono::seconds(120);

/// The bench's domains D and D+1, from its pid as tests/support/TestDomain.hpp
/// derives a test's, so parallel benches and tests do not see each other:
/// D is even in 10..228, D+1 stays under the port formula's cap (232).
inline std::uint32_t benchDomain() { return 10 + static_cast<std::uint32_t>(::getpid()) % 110 * 2; }

/// Peer processes: this very flatsat binary with a hidden subcommand. Any
/// not joined when this goes away (the bench failed) is stopped and reaped.
class Peers {
 public:
  Peers() = default;
  Peers(const Peers&) = delete;
  Peers& operator=(const Peers&) = delete;
  ~Peers() {
    for (const pid_t pid : pids_) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, nullptr, 0);
    }
  }
  void start(std::vector<std::string> args) {
    args.insert(args.begin(), "flatsat");
    std::vector<char*> argv;
    for (auto& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ);
    if (rc != 0) throw std::runtime_error("could not start flatsat " + args[1] + ": " + std::strerror(rc));
    pids_.push_back(pid);
  }
  /// Waits for every peer to exit; throws when one failed.
  void join() {
    std::string failed;
    while (!pids_.empty()) {
      int status = 0;
      const pid_t pid = pids_.back();
      ::waitpid(pid, &status, 0);
      pids_.pop_back();
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) failed.append(" ").append(std::to_string(pid));
    }
    if (!failed.empty()) throw std::runtime_error("bench peer process(es) failed:" + failed);
  }

 private:
  std::vector<pid_t> pids_;
};

}  // namespace flatsat::tools
