// SPDX-License-Identifier: Apache-2.0
// Each sensor fault changes the measurement exactly as specified, only while
// it is active in simulated time.
#include <catch2/catch.hpp>

#include <cmath>

#include "components/common/SensorFaults.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::SensorFault;
using flatsat::SensorFaultKind;
using flatsat::SensorFaults;
using Vec = Eigen::Vector3d;

namespace {
SensorFault fault(SensorFaultKind kind, int channel, double magnitude, double start_s,
                  double duration_s) {
  return {kind, channel, magnitude, static_cast<std::int64_t>(start_s * kSecond),
          static_cast<std::int64_t>(duration_s * kSecond)};
}
Vec measure(SensorFaults<3>& faults, Vec y, double t_s, bool* valid = nullptr) {
  const auto result = faults.apply(y, static_cast<std::int64_t>(t_s * kSecond));
  if (valid != nullptr) *valid = result.valid;
  return y;
}
}  // namespace

TEST_CASE("bias acts on its channel during its window only", "[common][components][faults]") {
  SensorFaults<3> faults(1);
  faults.add(fault(SensorFaultKind::kBias, 1, 2e-6, 10.0, 5.0));
  const Vec y(1e-5, 2e-5, 3e-5);
  CHECK(measure(faults, y, 9.9) == y);
  const Vec biased = y + Vec(0.0, 2e-6, 0.0);
  CHECK(measure(faults, y, 10.0) == biased);
  CHECK(measure(faults, y, 14.9) == biased);
  CHECK(measure(faults, y, 15.0) == y);  // [start, start + duration)
}

TEST_CASE("stuck holds the value of the first faulted sample, then releases", "[common][components][faults]") {
  SensorFaults<3> faults(1);
  faults.add(fault(SensorFaultKind::kStuck, -1, 0.0, 1.0, 2.0));
  CHECK(measure(faults, Vec(1, 2, 3), 0.5) == Vec(1, 2, 3));
  CHECK(measure(faults, Vec(4, 5, 6), 1.0) == Vec(4, 5, 6));
  CHECK(measure(faults, Vec(7, 8, 9), 2.0) == Vec(4, 5, 6));
  CHECK(measure(faults, Vec(7, 8, 9), 3.0) == Vec(7, 8, 9));
}

TEST_CASE("a stuck channel hides a bias on it, other channels keep theirs", "[common][components][faults]") {
  SensorFaults<3> faults(1);
  faults.add(fault(SensorFaultKind::kBias, -1, 1.0, 0.0, 0.0));
  faults.add(fault(SensorFaultKind::kStuck, 0, 0.0, 0.0, 0.0));
  CHECK(measure(faults, Vec(10, 20, 30), 0.0) == Vec(10, 21, 31));
  CHECK(measure(faults, Vec(50, 60, 70), 1.0) == Vec(10, 61, 71));
}

TEST_CASE("spike adds its magnitude to exactly one sample", "[common][components][faults]") {
  SensorFaults<3> faults(1);
  faults.add(fault(SensorFaultKind::kSpike, 2, 100.0, 1.0, 0.0));
  CHECK(measure(faults, Vec::Zero(), 0.9) == Vec::Zero());
  CHECK(measure(faults, Vec::Zero(), 1.05) == Vec(0, 0, 100));
  CHECK(measure(faults, Vec::Zero(), 1.1) == Vec::Zero());
}

TEST_CASE("dropout invalidates the sample, saturation clips", "[common][components][faults]") {
  SensorFaults<3> faults(1);
  faults.add(fault(SensorFaultKind::kDropout, -1, 0.0, 1.0, 1.0));
  faults.add(fault(SensorFaultKind::kSaturation, -1, 5.0, 0.0, 0.0));
  bool valid = false;
  CHECK(measure(faults, Vec(-9, 3, 9), 0.0, &valid) == Vec(-5, 3, 5));
  CHECK(valid);
  measure(faults, Vec(1, 2, 3), 1.5, &valid);
  CHECK_FALSE(valid);
  measure(faults, Vec(1, 2, 3), 2.0, &valid);
  CHECK(valid);
}

TEST_CASE("noise fault adds white noise of the set standard deviation", "[common][components][faults]") {
  SensorFaults<3> faults(42);
  faults.add(fault(SensorFaultKind::kNoise, 0, 0.5, 0.0, 0.0));
  const int n = 100000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec y = measure(faults, Vec(1.0, 2.0, 3.0), i * 0.1);
    REQUIRE(y[1] == 2.0);
    sum += y[0] - 1.0;
    sum2 += (y[0] - 1.0) * (y[0] - 1.0);
  }
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  CHECK(std::abs(mean) < 5 * 0.5 / std::sqrt(n));
  CHECK(sigma == Approx(0.5).epsilon(0.03));  // within 3 % over 1e5 samples
}

TEST_CASE("fault parameters are validated", "[common][components][faults]") {
  CHECK(fault(SensorFaultKind::kBias, 0, 1.0, 0.0, 0.0).validate(3).empty());
  CHECK(fault(SensorFaultKind::kBias, 3, 1.0, 0.0, 0.0).validate(3).size() == 1);
  CHECK(fault(SensorFaultKind::kNoise, 0, -1.0, 0.0, 0.0).validate(3).size() == 1);
  CHECK(fault(SensorFaultKind::kBias, 0, NAN, -1.0, -2.0).validate(3).size() == 3);
  SensorFaultKind kind;
  CHECK(flatsat::parseSensorFaultKind("dropout", kind));
  CHECK(kind == SensorFaultKind::kDropout);
  CHECK_FALSE(flatsat::parseSensorFaultKind("melt", kind));
}
