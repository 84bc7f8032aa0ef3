// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>

namespace flatsat::tools {

/// The plain graph of `flatsat bench`: the rig's shape written on Fast DDS directly,
/// without the bus layer's step protocol (no grants, no StepDone, no health, no
/// checks): a master → 4 sensors → estimator → 2 controllers → master, 8 processes, each
/// node writing one small sample per step when its inputs of that step are in. Reliable,
/// volatile, keep-last 8, data sharing automatic, on the rig's loopback network. What the
/// middleware allows for this graph; the rig's steps/s over it is
/// lockstep_fraction_of_plain (docs/performance.md).
///
/// Measures one run of `steps` steps (steps/s over all but the first 50, which include
/// discovery); NaN when it failed, its error on stderr.
double measurePlainGraphStepsPerSecond(bool quick);

/// The hidden peer `flatsat bench-plain ROLE --domain D --steps N`: one node of the graph.
int runPlainNode(const std::string& role, std::uint32_t domain, std::uint64_t steps);

/// The roles runPlainNode() takes.
bool isPlainRole(const std::string& role);

}  // namespace flatsat::tools
