// SPDX-License-Identifier: Apache-2.0
#pragma once
// `flatsat security-grants`: the least-privilege DDS Security grants of the
// rig's identities (architecture, "Security"), made from the topic registry
// (bus/Topics.hpp) and from what each component's code writes.
// deploy/security/make-certs.sh signs them.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Identity of `flatsat replay` under DDS Security: a time master that
/// publishes recorded samples of every stepped topic (not `operator`, which only commands).
inline constexpr const char* kReplayIdentity = "replay";

/// What one identity's grant allows, topics in registry order.
struct Grant {
  std::string identity;
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
};

/// Every identity of the rig: each component kind (components/Registry.cpp),
/// `operator` (bus::kOperatorIdentity) and `replay`.
std::vector<std::string> grantIdentities();

/// The grants of `identities` (empty: grantIdentities()). Throws
/// std::invalid_argument for an unknown identity, std::runtime_error when a
/// component's code writes a topic the registry gives another producer.
std::vector<Grant> securityGrants(const std::vector<std::string>& identities);

/// `flatsat security-grants [IDENTITY ...]`: per identity, a line
/// `IDENTITY publish TOPIC ...` and a line `IDENTITY subscribe TOPIC ...`.
CLI::App* addGrantsCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
