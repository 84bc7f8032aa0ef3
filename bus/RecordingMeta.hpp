// SPDX-License-Identifier: Apache-2.0
#pragma once
// What a rig's recorder writes about its rig into the recording's meta
// table, so that `flatsat replay` can stand in for part of that rig: who is
// scheduled at which divider, how time advanced, and the liveliness lease a
// paced component expects from its producers.
#include <charconv>
#include <stdexcept>
#include <string>

#include "bus/Node.hpp"

namespace flatsat::bus::meta {

inline constexpr const char* kScenario = "scenario";            // scenario name
inline constexpr const char* kSchedule = "schedule";            // "name=divider,..."
inline constexpr const char* kMode = "mode";                    // lockstep | paced
inline constexpr const char* kLeaseMs = "liveliness_lease_ms";  // [ms]
/// [-] only the stepped samples and grants of every Nth step are in (absent: every step)
inline constexpr const char* kRecordEverySteps = "record_every_steps";
/// [-] `flatsat run --resume`: steps up to this one are in the recording
/// already; the recorder checks the resumed rig's samples of those steps
/// against them instead of storing them again.
inline constexpr const char* kResumeAfterStep = "resume_after_step";
/// [-] written by a resumed recorder as it stops: samples of the steps up to
/// kResumeAfterStep that differed from (or were missing in) the recording.
inline constexpr const char* kResumeMismatches = "resume_mismatches";
/// The recording's digest (bus/RecordingDigest.hpp) as its writer computed it
/// while storing the samples (Recording::keepDigest); absent after a crash, a
/// resume or samples stored out of order, when a reader computes it again.
inline constexpr const char* kDigest = "recording_sha256";
/// The summary's figures of the samples (analysis/RunFigures.hpp, JSON) as
/// the recorder accumulated them while storing; absent when the digest is.
inline constexpr const char* kFigures = "summary_figures";
/// "1": the writer of a new recording left its (topic, source, step) index
/// to the first reader that needs it (bus::Recording::needIndex).
inline constexpr const char* kIndexDeferred = "index_deferred";

inline std::string formatSchedule(const Schedule& schedule) {
  std::string out;
  for (const auto& [name, divider] : schedule) {
    if (!out.empty()) out += ',';
    out += name + "=" + std::to_string(divider);
  }
  return out;
}

/// Throws std::runtime_error naming `where` for a malformed entry.
inline Schedule parseSchedule(const std::string& text, const std::string& where) {
  Schedule schedule;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string entry = text.substr(begin, end - begin);
    const std::size_t eq = entry.find('=');
    std::uint32_t divider = 0;
    if (eq == std::string::npos || eq == 0 ||
        std::from_chars(entry.data() + eq + 1, entry.data() + entry.size(), divider).ec !=
            std::errc() ||
        divider == 0) {
      throw std::runtime_error(where + ": schedule entry '" + entry +
                               "' is not name=divider (divider >= 1)");
    }
    schedule[entry.substr(0, eq)] = divider;
    begin = end + 1;
  }
  return schedule;
}

}  // namespace flatsat::bus::meta
