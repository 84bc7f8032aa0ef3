// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace flatsat::bus {

/// One row of a recording (bus/Recording.hpp) as it is stored or read in
/// storage order; its views last as long as the call it is handed to.
struct StoredSample {
  std::string_view topic;
  std::uint64_t step = 0;
  std::string_view source;
  std::int64_t sim_time_ns = 0;
  const std::uint8_t* payload = nullptr;
  std::size_t size = 0;
};

}  // namespace flatsat::bus
