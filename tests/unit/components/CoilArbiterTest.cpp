// SPDX-License-Identifier: Apache-2.0
// One owner for the coils: requested windows run whole and never overlap each
// other or the unloading law.
#include <vector>

#include <catch2/catch.hpp>

#include "components/unloading_controller/CoilArbiter.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::unloading_controller;

TEST_CASE("coil arbiter: a window runs whole, the law resumes after it", "[unloading_controller][coils]") {
  CoilArbiter arbiter(Eigen::Vector3d::Constant(150.0));
  const Eigen::Vector3d law(1.0, 2.0, 3.0);
  CoilRequest r{7, {100.0, 0.0, 0.0}, 10.0, 5.0, 10.0};
  for (std::int64_t t = 0; t < 40; ++t) {
    // The request stays asserted the whole time, as the estimator publishes it.
    const auto out = arbiter.step(r, law, (100 + t) * kSecond);
    const std::int64_t since = t;
    if (since < 10) {
      CHECK(out.window_active);
      CHECK(out.m_B_Am2.isZero());
      CHECK(out.report.phase == CoilPhase::kQuiet);
    } else if (since < 15) {
      CHECK(out.m_B_Am2 == r.m_B_Am2);
      CHECK(out.report.phase == CoilPhase::kPulse);
    } else if (since < 25) {
      CHECK(out.m_B_Am2.isZero());
      CHECK(out.report.phase == CoilPhase::kQuietAfter);
    } else {
      CHECK_FALSE(out.window_active);
      CHECK(out.m_B_Am2 == law);  // the same id is not served twice
      CHECK(out.report.phase == CoilPhase::kDone);
      CHECK(out.report.request_id == 7);
      CHECK(out.report.t0_ns == 100 * kSecond);
      CHECK(out.report.t1_ns == 110 * kSecond);
      CHECK(out.report.pulse_end_ns == 115 * kSecond);
      CHECK(out.report.t2_ns == 125 * kSecond);
    }
  }
}

TEST_CASE("coil arbiter: overlapping requests wait, two users never drive a coil at once",
          "[unloading_controller][coils]") {
  CoilArbiter arbiter(Eigen::Vector3d::Constant(150.0));
  const Eigen::Vector3d law(5.0, 5.0, 5.0);
  CoilRequest first{1, {100.0, 0.0, 0.0}, 3.0, 3.0, 3.0};
  CoilRequest second{2, {-100.0, 0.0, 0.0}, 3.0, 3.0, 3.0};
  int pulses_first = 0, pulses_second = 0;
  std::int64_t second_started = -1;
  for (std::int64_t t = 0; t < 30; ++t) {
    // The second request arrives while the first window runs.
    const auto& request = t < 4 ? first : second;
    const auto out = arbiter.step(request, law, t * kSecond);
    const bool law_on = out.m_B_Am2 == law;
    const bool first_on = out.m_B_Am2 == first.m_B_Am2;
    const bool second_on = out.m_B_Am2 == second.m_B_Am2;
    CHECK(int(law_on) + int(first_on) + int(second_on) <= 1);
    CHECK(law_on != out.window_active);
    pulses_first += first_on;
    pulses_second += second_on;
    if (out.report.request_id == 2 && second_started < 0) second_started = t;
  }
  CHECK(pulses_first == 3);
  CHECK(pulses_second == 3);
  CHECK(second_started == 9);  // right after the first window's end
}

TEST_CASE("coil arbiter: a dipole beyond a coil's limit is refused, not clipped", "[unloading_controller][coils]") {
  CoilArbiter arbiter(Eigen::Vector3d::Constant(150.0));
  const auto out = arbiter.step(CoilRequest{3, {200.0, 0.0, 0.0}, 1.0, 1.0, 1.0},
                                Eigen::Vector3d::Ones(), 0);
  CHECK(out.report.phase == CoilPhase::kRefused);
  CHECK(out.report.request_id == 3);
  CHECK_FALSE(out.window_active);
  CHECK(out.m_B_Am2 == Eigen::Vector3d::Ones());
  CHECK_THROWS_AS(CoilArbiter(Eigen::Vector3d(1.0, 0.0, 1.0)), std::invalid_argument);
}

TEST_CASE("coil arbiter: an unloading pulse in progress is held as the window's pulse", "[unloading_controller][coils]") {
  CoilArbiter arbiter(Eigen::Vector3d::Constant(150.0));
  // Seed S0 asks for +100 A m² on x, or the law's own dipole when it gives >= 40 along x.
  const CoilRequest request{4, {100.0, 0.0, 0.0}, 2.0, 3.0, 2.0, 40.0};
  std::vector<Eigen::Vector3d> pulse;
  for (std::int64_t t = 0; t < 7; ++t) {
    // The law keeps changing (it follows H and B); the pulse holds its value at t1 = 2 s.
    const Eigen::Vector3d law(-60.0 - static_cast<double>(t), 20.0, 5.0);
    const auto out = arbiter.step(request, law, t * kSecond);
    CHECK(out.window_active);
    if (out.report.phase == CoilPhase::kPulse) pulse.push_back(out.m_B_Am2);
    if (out.report.phase != CoilPhase::kPulse) CHECK(out.m_B_Am2.isZero(0.0));
  }
  REQUIRE(pulse.size() == 3);
  for (const auto& m : pulse) CHECK(m == Eigen::Vector3d(-62.0, 20.0, 5.0));
  const auto done = arbiter.step(std::nullopt, Eigen::Vector3d::Zero(), 7 * kSecond);
  CHECK(done.report.phase == CoilPhase::kDone);
  CHECK(done.report.law_pulse);
  CHECK(done.report.m_B_Am2 == Eigen::Vector3d(-62.0, 20.0, 5.0));  // what the estimator divides by

  // Too little along x, or mostly across it: the requested pulse instead.
  for (const Eigen::Vector3d& law : {Eigen::Vector3d(30.0, 0.0, 0.0), Eigen::Vector3d(50.0, 120.0, 0.0)}) {
    CoilArbiter other(Eigen::Vector3d::Constant(150.0));
    for (std::int64_t t = 0; t < 8; ++t) other.step(request, law, t * kSecond);
    const auto report = other.step(std::nullopt, law, 8 * kSecond).report;
    CHECK_FALSE(report.law_pulse);
    CHECK(report.m_B_Am2 == request.m_B_Am2);
  }
}
