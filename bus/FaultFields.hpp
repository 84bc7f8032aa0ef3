// SPDX-License-Identifier: Apache-2.0
#pragma once
// The fields every injected fault has (kind, channel, magnitude, start_s,
// duration_s), from a scenario's `faults:` list or from a FaultCmd. What a
// kind means and which values are valid is the fault table's own: `parse`
// turns the kind's text into the Fault's kind (false: unknown), `validate`
// returns the fault's problems as "field: reason".
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "bus/Params.hpp"
#include "bus/Stamp.hpp"
#include "msg/Faults.h"

namespace flatsat::bus {

/// `faults:` of a component's section; `kinds` lists the valid kinds for the
/// message, `unit` is the magnitude's.
template <class Fault, class Parse, class Validate>
std::vector<Fault> readFaults(ParamReader& reader, std::string_view unit, const std::string& kinds,
                              std::size_t max_faults, Parse&& parse, Validate&& validate) {
  std::vector<Fault> faults;
  for (auto& entry : reader.list("faults")) {
    Fault fault;
    std::string kind;
    entry.read("kind", kind);
    if (!parse(kind, fault.kind)) entry.problem("kind", "'" + kind + "' is not one of " + kinds);
    entry.read("channel", fault.channel);
    entry.read("magnitude", fault.magnitude, unit);
    double start_s = 0.0, duration_s = 0.0;
    entry.read("start_s", start_s, "s");
    entry.read("duration_s", duration_s, "s");
    fault.start_ns = std::llround(start_s * 1e9);
    fault.duration_ns = std::llround(duration_s * 1e9);
    entry.problems(validate(fault));
    entry.finish();
    faults.push_back(fault);
  }
  if (faults.size() > max_faults) reader.problem("faults", "at most " + std::to_string(max_faults) + " faults");
  return faults;
}

/// A fault command's fields into `fault`; every problem (empty: valid).
template <class Fault, class Parse, class Validate>
std::vector<std::string> faultFromCommand(const msg::FaultCmd& command, Fault& fault, const std::string& kinds,
                                          Parse&& parse, Validate&& validate) {
  std::vector<std::string> problems;
  const std::string kind = text(command.kind());
  if (!parse(kind, fault.kind)) problems.push_back("kind: '" + kind + "' is not one of " + kinds);
  fault.channel = command.channel();
  fault.magnitude = command.magnitude();
  fault.start_ns = command.start_ns();
  fault.duration_ns = command.duration_ns();
  for (auto& p : validate(fault)) problems.push_back(std::move(p));
  return problems;
}

}  // namespace flatsat::bus
