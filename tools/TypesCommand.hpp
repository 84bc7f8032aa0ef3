// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat types [TYPE]`, like `ros2 interface show`: the registry's topic
/// types with their topics, or one type's OMG IDL text (the schema the MCAP
/// export and the Foxglove bridge send). Needs no rig.
CLI::App* addTypesCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
