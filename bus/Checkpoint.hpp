// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace flatsat::bus {

/// A component's state that must survive a restart (issue "Restart": the
/// estimator's estimate and covariance, the sequencer's correction count),
/// kept as `{"component", "step", "state"}` in the run directory
/// (`checkpoints/<name>.json`). Written whole to a temporary file and renamed
/// over the old one, so a process killed at any moment leaves the previous
/// checkpoint or the new one, never half of one.
void writeCheckpoint(const std::string& file, const std::string& component, std::uint64_t step,
                     const nlohmann::json& state);

struct Checkpoint {
  std::uint64_t step = 0;  ///< [-] the step whose end it holds
  nlohmann::json state;
};

/// The checkpoint in `file`, nothing when there is none. Throws
/// std::runtime_error naming the file and the reason when it cannot be read
/// or belongs to another component.
std::optional<Checkpoint> readCheckpoint(const std::string& file, const std::string& component);

}  // namespace flatsat::bus
