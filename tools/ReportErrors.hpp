// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <exception>
#include <iostream>

namespace flatsat::tools {

/// Runs a subcommand: its exit code, or 1 with "error: ..." on stderr when it throws.
template <class Run>
void runReportingErrors(int& exit_code, Run&& run) {
  try {
    exit_code = run();
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    exit_code = 1;
  }
}

}  // namespace flatsat::tools
