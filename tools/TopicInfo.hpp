// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat topics info TOPIC`, like `ros2 topic info -v`: a topic's type,
/// its QoS preset as the rig's writers and readers use it, and the producers
/// and consumers discovery finds on the domain.
void addTopicInfoCommand(CLI::App& topics, int& exit_code);

}  // namespace flatsat::tools
