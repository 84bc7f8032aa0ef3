// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat foxglove`: a running rig served to Foxglove (or Lichtblick) over
/// the Foxglove WebSocket protocol: every live registry topic a channel with
/// its OMG IDL schema and CDR bytes, health changes as status messages, and
/// the operator command topics open to clients that publish. It reads the
/// rig's recorder's live feed (bus/LiveFeed.hpp) where one runs on this host,
/// else the bus.
CLI::App* addFoxgloveCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
