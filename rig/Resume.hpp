// SPDX-License-Identifier: Apache-2.0
#pragma once
// `flatsat run SCENARIO --resume DIR`: a lockstep run killed part-way goes on
// from the last complete step of its recording. The rig is deterministic, so
// the resumed processes compute steps 0..K again from the scenario (in
// lockstep, or composed: far faster than the first time) and the recorder
// checks every sample of those steps against the recording instead of
// storing it; from K + 1 on it records as usual. The final recording is the
// one an uninterrupted run would have written, and a rig that did not
// reproduce its recorded steps is reported, not silently continued.
#include <cstdint>
#include <optional>
#include <string>

#include "bus/Scenario.hpp"

namespace flatsat::rig {

/// Readies DIR/recording.sqlite of a killed run of `scenario` (DIR's own
/// scenario.yaml): finds K, the last step every stepped topic of the rig
/// holds, erases the samples stamped after it and marks the recording for
/// the recorder (bus::meta::kResumeAfterStep). Nothing when no step is
/// complete. Throws std::runtime_error naming the file and the reason
/// (not lockstep, operator commands in it, no recording).
std::optional<std::uint64_t> prepareResume(const bus::Scenario& scenario, const std::string& recording);

/// Samples of steps 0..K the resumed rig computed differently (written by the recorder as it stopped).
std::uint64_t resumeMismatches(const std::string& recording);

}  // namespace flatsat::rig
