// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace flatsat::bus {

/// What a component must know after a restart: its state
/// (the estimator's estimate and covariance, the sequencer's correction count;
/// null for a component that keeps none) and the newest step it began to
/// publish, whose grant it must never step again.
struct Checkpoint {
  std::uint64_t step = 0;     ///< [-] the step whose end `state` holds
  nlohmann::json state;
  std::uint64_t claimed = 0;  ///< [-] >= step: outputs of steps up to it may be on the bus
};

/// Kept as `{"component", "step", "state", "claimed"}` in the run directory
/// (`checkpoints/<name>.json`). Written whole to a temporary file and renamed
/// over the old one, so a process killed at any moment leaves the previous
/// checkpoint or the new one, never half of one.
void writeCheckpoint(const std::string& file, const std::string& component, const Checkpoint& checkpoint);

/// The checkpoint in `file`, nothing when there is none. Throws
/// std::runtime_error naming the file and the reason when it cannot be read
/// or belongs to another component.
std::optional<Checkpoint> readCheckpoint(const std::string& file, const std::string& component);

}  // namespace flatsat::bus
