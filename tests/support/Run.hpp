// SPDX-License-Identifier: Apache-2.0
#pragma once
// Runs a command line and captures what it printed (stdout and stderr).
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace flatsat::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;
};

inline CommandResult runCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

/// Starts a command line in the background (its output to `log`) as a child
/// of this process; returns its pid for waitCommand().
inline pid_t startCommand(const std::string& command, const std::string& log) {
  const std::string line = "exec " + command + " >" + log + " 2>&1";
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot fork for " + command);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

/// Waits for a child started by startCommand(); its exit code (128 + signal).
inline int waitCommand(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace flatsat::test
