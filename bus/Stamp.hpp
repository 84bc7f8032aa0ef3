// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "msg/Common.h"

namespace flatsat::bus {

/// Where a stepped sample belongs in simulated time.
struct StepContext {
  std::uint64_t step = 0;       ///< [-] k
  std::int64_t sim_time_ns = 0; ///< [ns] t_k since the scenario epoch
  std::int64_t period_ns = 0;   ///< [ns] base step period
};

/// Copies text into a NUL-padded fixed char array, truncating.
template <std::size_t N>
void setText(std::array<char, N>& field, std::string_view text) {
  field.fill('\0');
  std::copy_n(text.begin(), std::min(text.size(), N - 1), field.begin());
}

template <std::size_t N>
std::string text(const std::array<char, N>& field) {
  return std::string(field.data(), std::find(field.begin(), field.end(), '\0'));
}

/// Stamps a sample's header, every field of it, in place: a header built
/// apart and moved in cost a construction and an assignment, both out of line
/// in the generated code, per sample (callgrind).
inline void stamp(msg::SampleHeader& header, const StepContext& ctx, std::string_view source) {
  header.step(ctx.step);
  header.sim_time_ns(ctx.sim_time_ns);
  header.sample_time_ns(ctx.sim_time_ns);
  setText(header.source(), source);
}

}  // namespace flatsat::bus
