// SPDX-License-Identifier: Apache-2.0
#pragma once
// What an operator command must be before a tool puts it on the bus, whoever
// composed it: `flatsat cmd` from its arguments, `flatsat foxglove` from a
// client's bytes. The component that applies it checks it again (it trusts
// nothing on the bus) and says in its acknowledgement what it did.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>

#include "bus/BusFaults.hpp"
#include "bus/Stamp.hpp"
#include "msg/Commands.h"
#include "msg/Faults.h"
#include "msg/Modes.h"

namespace flatsat::tools {

namespace command_checks {

/// "" when the text field is NUL-terminated, printable and, if `required`, not empty.
template <std::size_t N>
std::string textProblem(const std::array<char, N>& field, const char* name, bool required) {
  const auto end = std::find(field.begin(), field.end(), '\0');
  if (end == field.end()) return std::string(name) + " is not NUL-terminated within its " + std::to_string(N) + " chars";
  if (!std::all_of(field.begin(), end, [](char c) { return std::isprint(static_cast<unsigned char>(c)) != 0; })) {
    return std::string(name) + " holds characters that are not printable";
  }
  if (required && end == field.begin()) return std::string(name) + " is empty";
  return "";
}

}  // namespace command_checks

/// Why the command must not be sent; "" when it may.
inline std::string commandProblem(const msg::ModeCmd& c) {
  const auto mode = static_cast<int>(c.mode());
  if (mode < static_cast<int>(msg::MAGNETIC_UNLOAD) || mode > static_cast<int>(msg::MAGNETIC_SPIN_CAPTURE)) {
    return "mode " + std::to_string(mode) + " is none of unload (0), detumble (1), spin_capture (2)";
  }
  return "";
}

inline std::string commandProblem(const msg::FaultCmd& c) {
  using command_checks::textProblem;
  for (const auto& problem : {textProblem(c.target(), "target", true), textProblem(c.kind(), "kind", true),
                              textProblem(c.topic(), "topic", false)}) {
    if (!problem.empty()) return problem;
  }
  if (bus::text(c.target()) == bus::kBusFaultTarget && bus::text(c.topic()).empty()) return "a bus fault names its topic";
  if (c.channel() < -1) return "channel " + std::to_string(c.channel()) + " is below -1 (all)";
  if (!std::isfinite(c.magnitude())) return "magnitude is not finite";
  if (c.start_ns() < 0) return "start_ns is negative";
  if (c.duration_ns() < 0) return "duration_ns is negative";
  return "";
}

inline std::string commandProblem(const msg::ParamCmd& c) {
  using command_checks::textProblem;
  for (const auto& problem : {textProblem(c.target(), "target", true), textProblem(c.key(), "key", true)}) {
    if (!problem.empty()) return problem;
  }
  if (!std::isfinite(c.value())) return "value is not finite";
  return "";
}

}  // namespace flatsat::tools
