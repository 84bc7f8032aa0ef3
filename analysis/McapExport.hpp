// SPDX-License-Identifier: Apache-2.0
#pragma once
// A recording as an MCAP file that Foxglove, Lichtblick and the MCAP tools
// open: `flatsat export REC --mcap OUT`, and `flatsat info` of such a file.
#include <cstdint>
#include <string>

#include "analysis/RecordingInfo.hpp"

namespace flatsat::analysis {

/// The channels an exported file adds for viewing, beside one per recorded topic.
inline constexpr const char* kMcapTruthFrames = "flatsat/tf/truth";        // foxglove.FrameTransform inertial -> body
inline constexpr const char* kMcapEstimateFrames = "flatsat/tf/estimate";  // inertial -> body_estimate
inline constexpr const char* kMcapLog = "flatsat/log";                     // foxglove.Log: faults, health changes

struct McapExportCounts {
  std::uint64_t messages = 0;  ///< every message written, derived ones included
  std::uint64_t channels = 0;
};

/// Writes recording `path` as MCAP `out`. Each recorded topic is a channel of
/// its IDL type (schema encoding `omgidl`, the IDL text self-contained) whose
/// messages are the recorded CDR bytes as they are (encapsulation header
/// first; message encoding `cdr`), in step order. Log and publish times are
/// the simulated time since the scenario's epoch [ns]; a health sample, which
/// counts its steps done, is placed at the rig's step it reached. The metadata record
/// "flatsat" holds the scenario, mode, recording_sha256, steps, wall duration
/// and the epoch (from the run directory's scenario.yaml). The derived
/// channels above are JSON with Foxglove's published schemas.
/// @throws std::runtime_error naming the file and the reason.
McapExportCounts exportMcap(const std::string& path, const std::string& out, const std::string& library);

/// What an exported MCAP file holds, read from its summary and its "flatsat"
/// metadata, in the terms of a recording's info (the derived channels as topics).
RecordingInfo describeMcap(const std::string& path);

/// Whether `path` begins with MCAP's magic.
bool isMcap(const std::string& path);

}  // namespace flatsat::analysis
