// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat orbit --tle FILE [--from MIN] [--to MIN] [--step MIN] [--no-checksum]`:
/// propagates every element set of FILE with SGP4 (sim::Sgp4) and prints, like Vallado's
/// verification driver, a line "<catalogue number> xx" per set and then rows
/// "tsince x y z xdot ydot zdot" (minutes since the set's epoch; TEME km and km/s;
/// tcppver.out's number formats) at from, from + step, … and finally to.
/// The command runs from its callback while the app parses and leaves its exit status in
/// exit_code: 0 done, 1 a set stopped with an SGP4 error (reported on stderr; the other
/// sets are still printed), 2 bad input (unreadable file, malformed TLE, bad times).
/// exit_code must outlive the parse; the caller returns it when the command was parsed.
CLI::App* addOrbitCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
