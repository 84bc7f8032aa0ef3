// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat web`: a live view of a running rig in the browser, served on
/// 127.0.0.1 only: the health table and live plots of the body rate and the
/// stored wheel momentum, refreshed twice a second from `/state` (JSON).
CLI::App* addWebCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
