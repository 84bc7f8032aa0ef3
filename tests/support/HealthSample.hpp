// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>

#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace flatsat::test {

/// A health sample from `source` that has done `steps` steps.
inline msg::Health healthSample(const std::string& source, std::uint64_t steps) {
  msg::Health h;
  bus::setText(h.header().source(), source);
  h.steps_done(steps);
  return h;
}

}  // namespace flatsat::test
