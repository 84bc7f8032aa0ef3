// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

namespace flatsat {

/// Rides a consumer through a sensor dropout on the last good reading.
template <class Sample>
class LastValid {
 public:
  /// The newest sample whose valid() is true, or `sample` itself before the
  /// first valid one. A copy: callers pass the temporary Input::at() returns.
  Sample update(const Sample& sample) {
    if (sample.valid()) last_ = sample;
    return last_ ? *last_ : sample;
  }

 private:
  std::optional<Sample> last_;
};

}  // namespace flatsat
