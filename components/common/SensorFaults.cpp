// SPDX-License-Identifier: Apache-2.0
#include "components/common/SensorFaults.hpp"

#include <cmath>
#include <limits>

namespace flatsat {

namespace {
struct KindName {
  SensorFaultKind kind;
  const char* name;
};
constexpr KindName kKinds[] = {
    {SensorFaultKind::kStuck, "stuck"},   {SensorFaultKind::kBias, "bias"},
    {SensorFaultKind::kNoise, "noise"},   {SensorFaultKind::kSpike, "spike"},
    {SensorFaultKind::kDropout, "dropout"}, {SensorFaultKind::kSaturation, "saturation"},
};
}  // namespace

bool parseSensorFaultKind(const std::string& text, SensorFaultKind& kind) {
  for (const auto& k : kKinds) {
    if (text == k.name) {
      kind = k.kind;
      return true;
    }
  }
  return false;
}

const char* toString(SensorFaultKind kind) {
  for (const auto& k : kKinds) {
    if (k.kind == kind) return k.name;
  }
  return "unknown";
}

std::vector<std::string> SensorFault::validate(int channels) const {
  std::vector<std::string> problems;
  if (channel < -1 || channel >= channels) {
    problems.push_back("channel: must be -1 (all) or 0.." + std::to_string(channels - 1));
  }
  if (!std::isfinite(magnitude)) problems.push_back("magnitude: must be finite");
  if ((kind == SensorFaultKind::kNoise || kind == SensorFaultKind::kSaturation) && magnitude < 0) {
    problems.push_back("magnitude: must be >= 0 for " + std::string(toString(kind)));
  }
  if (start_ns < 0) problems.push_back("start_s: must be >= 0");
  if (duration_ns < 0) problems.push_back("duration_s: must be >= 0 (0: until the end)");
  // activeAt() adds them: the end must be a representable time (found by tests/fuzz, fault_cmd).
  if (start_ns >= 0 && duration_ns > std::numeric_limits<std::int64_t>::max() - start_ns) {
    problems.push_back("duration_s: start + duration is beyond the representable time");
  }
  return problems;
}

}  // namespace flatsat
