// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <sys/resource.h>
#include <sys/types.h>

#include <string>
#include <vector>

namespace flatsat::rig {

/// Starts args[0] (looked up on PATH when it has no slash) with stdout and
/// stderr into `log`; throws std::runtime_error naming it when it cannot.
pid_t spawnLogged(const std::vector<std::string>& args, const std::string& log);

/// What a program printed, and how it ended.
struct Captured {
  int exit_code = -1;  ///< 128 + signal when killed; 127 when it could not start
  std::string out;
  std::string err;
};
/// Runs args[0] (looked up on PATH) to its end, capturing stdout and stderr.
Captured runCaptured(const std::vector<std::string>& args);

/// Whether `program` is an executable on PATH.
bool onPath(const std::string& program);

/// [s] User plus system CPU time of a getrusage() or wait4() report.
double cpuSeconds(const rusage& usage);

/// A waitpid status in words: "exit code N", "killed by signal N".
std::string describeExit(int status);

}  // namespace flatsat::rig
