// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

namespace flatsat {

/// The newest sample whose valid() is true: a consumer rides through a
/// sensor dropout on the last good reading (none before the first one).
template <class Sample>
class LastValid {
 public:
  const std::optional<Sample>& update(const Sample& sample) {
    if (sample.valid()) last_ = sample;
    return last_;
  }

 private:
  std::optional<Sample> last_;
};

}  // namespace flatsat
