// SPDX-License-Identifier: Apache-2.0
#pragma once
// A sensor topic's contract (the sensor conformance test), checked the same
// way whoever produces the samples, an emulator or a hardware bridge: header
// fields, monotonic time, rate, and, for every valid sample, finite values in
// the topic's units and physical range, within the sensor's error budget of
// the truth of the same step (a value in the wrong unit is off by orders of
// magnitude). Works on `flatsat export --json` rows.
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace flatsat::test {

struct SensorContract {
  std::string field;             ///< measurement field, named as the truth's field it measures
  double tolerance = 0.0;        ///< [field unit] per component, |measured - true| when valid
  double min_norm = 0.0;         ///< [field unit] physical range of |measured| when valid
  double max_norm = 0.0;
  /// q and −q are the same attitude: compared with whichever sign is nearer the truth
  bool quaternion = false;
};

/// What a sample stream must show: who sends it and how often.
struct SensorStream {
  std::string source;    ///< header.source of every sample
  double step_s = 0.1;   ///< [s] the rig's step
  double rate_hz = 10.0; ///< [Hz] expected sample rate
  /// [-] relative rate tolerance: 10 % in lockstep; a paced rig, which waits
  /// for nobody, loses samples when a busy 2-core machine delays a process
  double rate_tolerance = 0.1;
};

/// Every breach of the contract by `samples` (one producer's, in step order);
/// `truth` is the truth by step. Empty: conformant.
inline std::vector<std::string> contractBreaches(const std::vector<nlohmann::json>& samples,
                                                 const std::map<std::uint64_t, nlohmann::json>& truth,
                                                 const SensorContract& contract, const SensorStream& stream) {
  std::vector<std::string> breaches;
  const auto breach = [&](const nlohmann::json& s, const std::string& what) {
    if (breaches.size() < 20) breaches.push_back("step " + s["header"]["step"].dump() + ": " + what);
  };
  if (samples.size() < 2) return {"fewer than 2 samples from " + stream.source};
  const auto period_ns = static_cast<std::int64_t>(std::llround(stream.step_s * 1e9));
  std::int64_t last_sample_ns = -1;
  for (const auto& s : samples) {
    const auto& h = s["header"];
    const auto step = h["step"].get<std::uint64_t>();
    const auto sim_ns = h["sim_time_ns"].get<std::int64_t>();
    const auto sample_ns = h["sample_time_ns"].get<std::int64_t>();
    if (h["source"] != stream.source) breach(s, "source " + h["source"].dump());
    if (sim_ns != static_cast<std::int64_t>(step) * period_ns) breach(s, "sim_time_ns is not step × step");
    if (sample_ns > sim_ns || sample_ns < sim_ns - period_ns) breach(s, "sample_time_ns outside its step");
    if (sample_ns < last_sample_ns) breach(s, "sample_time_ns went back");
    last_sample_ns = sample_ns;
    if (!s["valid"].get<bool>()) continue;
    const auto it = truth.find(step);
    if (it == truth.end()) {
      breach(s, "no truth at this step");
      continue;
    }
    double norm2 = 0.0;
    const auto& measured = s[contract.field];
    const auto& true_value = it->second[contract.field];
    double sign = 1.0;
    if (contract.quaternion) {
      double dot = 0.0;
      for (std::size_t i = 0; i < measured.size(); ++i) dot += measured[i].get<double>() * true_value[i].get<double>();
      sign = dot < 0.0 ? -1.0 : 1.0;
    }
    for (std::size_t i = 0; i < measured.size(); ++i) {
      const double m = measured[i].get<double>(), t = sign * true_value[i].get<double>();
      if (!std::isfinite(m)) breach(s, contract.field + " not finite");
      if (std::abs(m - t) > contract.tolerance) {
        breach(s, contract.field + "[" + std::to_string(i) + "] = " + std::to_string(m) + ", truth " +
                      std::to_string(t));
      }
      norm2 += m * m;
    }
    if (std::sqrt(norm2) < contract.min_norm || std::sqrt(norm2) > contract.max_norm) {
      breach(s, "|" + contract.field + "| = " + std::to_string(std::sqrt(norm2)) + " outside its range");
    }
  }
  const auto first = samples.front()["header"]["step"].get<std::uint64_t>();
  const auto last = samples.back()["header"]["step"].get<std::uint64_t>();
  const double rate_hz = static_cast<double>(samples.size() - 1) / (static_cast<double>(last - first) * stream.step_s);
  if (std::abs(rate_hz / stream.rate_hz - 1.0) > stream.rate_tolerance) {
    breaches.push_back(stream.source + ": " + std::to_string(rate_hz) + " samples/s, expected " +
                       std::to_string(stream.rate_hz));
  }
  return breaches;
}

/// The contracts of the rig's sensor topics, for the default spacecraft's
/// sensors (tolerances: several sigma of noise plus the largest bias set).
inline const std::map<std::string, SensorContract>& sensorContracts() {
  static const std::map<std::string, SensorContract> contracts = {
      // Earth's field in low orbit is 15..70 µT; noise 50 nT, bias up to 100 nT.
      {"magnetometer", {"b_body_T", 1e-6, 15e-6, 70e-6}},
      // A unit vector; noise 0.01 deg (1.7e-4).
      {"sun_sensor", {"sun_body_unit", 1e-3, 0.999, 1.001}},
      // A pointed spacecraft; noise 9e-6 rad/s per 0.1 s sample, bias 2.4e-6 rad/s.
      {"gyro", {"w_body_rad_s", 1e-4, 0.0, 0.2}},
      // Noise 0.01 rad/s, quantum 0.005 rad/s; wheels below 6000 rpm.
      {"wheel_tach", {"wheel_speed_rad_s", 0.1, 0.0, 2.0 * 629.0}},
      // A unit quaternion; noise 4 arcsec across the boresight, 30 arcsec about it (a
      // quaternion component moves by half the angle: 7e-5 at 30 arcsec).
      {"star_tracker", {"q_inertial_body", 5e-4, 1.0 - 1e-9, 1.0 + 1e-9, true}},
  };
  return contracts;
}

}  // namespace flatsat::test
