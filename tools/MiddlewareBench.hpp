// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <vector>

namespace CLI {
class App;
}

namespace flatsat::tools {

/// Prints the middleware figures of `flatsat bench`, measured with
/// the rig's own bus (loopback profile: UDP on 127.0.0.1 + SHM), its registry
/// topics and QoS, between separate flatsat processes:
///   hop_us, hop_us_p99  one-way latency of a TruthState sample, RTT/2 of a
///                       ping-pong with an echo process (median, 99th percentile)
///   plain_graph_steps_per_s  the same shape on Fast DDS directly, no step protocol
///                       (PlainGraphBench.hpp): what the middleware allows
///   limit_steps_per_s   the bare lockstep graph of the rig's shape (time master →
///                       4 sensors → estimator → 2 controllers → master, no models,
///                       no recorder) as 8 processes
/// A figure that could not be measured prints as nan, its error on stderr.
/// Returns limit_steps_per_s (NaN when it failed); `all_measured`, when
/// given, says whether every figure was.
double printMiddlewareBench(bool quick, bool* all_measured = nullptr);
/// Its two parts: prints hop_us and hop_us_p99 (false: not measured) ...
bool printHopBench(bool quick);
/// ... and measures limit_steps_per_s once, printing nothing (NaN when it failed).
double measureLimitStepsPerSecond(bool quick);

/// The hidden subcommands the bench starts as its peer processes:
///   bench-echo --domain D   reads truth on D, writes each sample back on D+1
///   bench-node ROLE --domain D --steps N   one component of the bare graph
/// Both are hidden from --help; `exit_code` receives the command's result.
std::vector<CLI::App*> addBenchPeerCommands(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
