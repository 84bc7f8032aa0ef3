// SPDX-License-Identifier: Apache-2.0
#pragma once
// Sensor faults injected into an emulator's measurement, timed in simulated
// time (architecture, "Faults"). Pure: Eigen + std.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/GaussianNoise.hpp"

namespace flatsat {

enum class SensorFaultKind {
  kStuck,       ///< the channel holds the value it had when the fault began
  kBias,        ///< + magnitude
  kNoise,       ///< + white noise of 1σ = magnitude
  kSpike,       ///< + magnitude on the first sample at or after the start only
  kDropout,     ///< no valid sample (published with valid = false)
  kSaturation,  ///< clipped to ±magnitude
};

/// Parses "stuck", "bias", "noise", "spike", "dropout", "saturation".
bool parseSensorFaultKind(const std::string& text, SensorFaultKind& kind);
const char* toString(SensorFaultKind kind);

struct SensorFault {
  SensorFaultKind kind = SensorFaultKind::kBias;
  int channel = -1;              // [-] measurement component (axis, wheel), -1 = all
  double magnitude = 0.0;        // [measurement unit] bias, spike, noise 1σ or clip level
  std::int64_t start_ns = 0;     // [ns] simulated time it begins, >= 0
  std::int64_t duration_ns = 0;  // [ns] how long it lasts; 0 = for the rest of the run

  bool activeAt(std::int64_t t_ns) const {
    return t_ns >= start_ns && (duration_ns == 0 || t_ns < start_ns + duration_ns);
  }
  /// Every violation as "field: reason" for a measurement of `channels` components.
  std::vector<std::string> validate(int channels) const;
};

/// The faults of one sensor; apply() runs them over each new measurement.
template <int N>
class SensorFaults {
 public:
  static constexpr int kMaxFaults = 16;
  using Vector = Eigen::Matrix<double, N, 1>;

  explicit SensorFaults(std::uint64_t seed) : noise_(seed) {}

  /// False (and nothing changes) when kMaxFaults are already held.
  bool add(const SensorFault& fault) {
    if (count_ == kMaxFaults) return false;
    faults_[static_cast<std::size_t>(count_++)] = {fault, false, Vector::Zero(), false};
    return true;
  }
  int count() const { return count_; }
  const SensorFault& fault(int i) const { return faults_[static_cast<std::size_t>(i)].fault; }

  struct Result {
    bool valid = true;           // false: a dropout is active
    std::uint32_t active = 0;    // bit i: fault i acted on this sample
  };

  /// Applies every fault active at t_ns to y, in the order bias, noise,
  /// spike, saturation, stuck (a stuck channel shows no other effect).
  Result apply(Vector& y, std::int64_t t_ns) {
    Result result;
    const Vector raw = y;
    for (int i = 0; i < count_; ++i) {
      Entry& e = faults_[static_cast<std::size_t>(i)];
      const bool active = e.fault.activeAt(t_ns);
      if (!active) {
        e.latched = false;
        continue;
      }
      const Vector mask = channelMask(e.fault.channel);
      switch (e.fault.kind) {
        case SensorFaultKind::kBias: y += e.fault.magnitude * mask; break;
        case SensorFaultKind::kNoise:
          y += noise_.template vector<N>(e.fault.magnitude).cwiseProduct(mask);
          break;
        case SensorFaultKind::kSpike:
          if (e.spiked) continue;
          y += e.fault.magnitude * mask;
          e.spiked = true;
          break;
        case SensorFaultKind::kDropout: result.valid = false; break;
        case SensorFaultKind::kSaturation:
          for (int c = 0; c < N; ++c) {
            if (mask[c] != 0.0) y[c] = std::clamp(y[c], -e.fault.magnitude, e.fault.magnitude);
          }
          break;
        case SensorFaultKind::kStuck:
          if (!e.latched) {
            e.held = raw;
            e.latched = true;
          }
          break;
      }
      result.active |= 1u << i;
    }
    for (int i = 0; i < count_; ++i) {
      const Entry& e = faults_[static_cast<std::size_t>(i)];
      if (e.fault.kind != SensorFaultKind::kStuck || !e.latched) continue;
      const Vector mask = channelMask(e.fault.channel);
      y = (mask.array() != 0.0).select(e.held, y);
    }
    return result;
  }

 private:
  struct Entry {
    SensorFault fault;
    bool latched = false;  // stuck: value held
    Vector held = Vector::Zero();
    bool spiked = false;   // spike: already delivered
  };
  static Vector channelMask(int channel) {
    if (channel < 0) return Vector::Ones();
    Vector mask = Vector::Zero();
    mask[channel] = 1.0;
    return mask;
  }

  std::array<Entry, kMaxFaults> faults_{};
  int count_ = 0;
  GaussianNoise noise_;
};

}  // namespace flatsat
