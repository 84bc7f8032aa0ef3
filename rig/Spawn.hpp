// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <sys/types.h>

#include <string>
#include <vector>

namespace flatsat::rig {

/// Starts args[0] (looked up on PATH when it has no slash) with stdout and
/// stderr into `log`; throws std::runtime_error naming it when it cannot.
pid_t spawnLogged(const std::vector<std::string>& args, const std::string& log);

/// A waitpid status in words: "exit code N", "killed by signal N".
std::string describeExit(int status);

}  // namespace flatsat::rig
