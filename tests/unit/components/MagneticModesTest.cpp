// SPDX-License-Identifier: Apache-2.0
// The coils' owner: mode switching by command and the detumble handover.
#include <algorithm>
#include <stdexcept>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/unloading_controller/MagneticModes.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::unloading_controller;

namespace {

/// The field of a constant inertial B seen from a body turned by angle [rad] about z.
Eigen::Vector3d fieldSeen(double angle) {
  return Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(30e-6, 0.0, 10e-6);
}
Eigen::Vector3d fieldSeen(double w, double t) { return fieldSeen(w * t); }

MagneticModesParams detumbleThenSpin() {
  MagneticModesParams p;
  p.initial_mode = MagneticMode::kDetumble;
  p.after_detumble = MagneticMode::kSpinCapture;
  p.handover_rate_rad_s = 0.01;
  p.handover_hold_s = 5.0;
  return p;
}

}  // namespace

TEST_CASE("mode names parse and nothing else does", "[unloading_controller][bdot]") {
  CHECK(magneticModeFromName("unload") == MagneticMode::kUnload);
  CHECK(magneticModeFromName("detumble") == MagneticMode::kDetumble);
  CHECK(magneticModeFromName("spin_capture") == MagneticMode::kSpinCapture);
  CHECK_FALSE(magneticModeFromName("spin"));
}

TEST_CASE("detumble hands over only after the rate stayed below the threshold for the hold", "[unloading_controller][bdot]") {
  MagneticModes modes(detumbleThenSpin());
  // |P|/|B| = |ω × b̂| = 0.95 ω for this field and ω along z.
  std::int64_t k = 0;
  double angle = 0.0;
  for (; k < 20; ++k, angle += 0.05) {  // fast: no handover however long
    const auto out = modes.step({Eigen::Vector4d::Zero(), fieldSeen(angle), true}, k * kSecond);
    CHECK_FALSE(out.handover);
    CHECK_FALSE(out.rate_below_handover);
  }
  // Slow from here: the first difference still spans the fast step, then the
  // 5 s hold runs from the first slow sample (k = 21).
  bool handed_over = false;
  std::int64_t handover_at = 0;
  for (; k < 40 && !handed_over; ++k, angle += 0.002) {
    const auto out = modes.step({Eigen::Vector4d::Zero(), fieldSeen(angle), true}, k * kSecond);
    CHECK(out.mode == MagneticMode::kDetumble);
    handed_over = out.handover;
    handover_at = k;
  }
  REQUIRE(handed_over);
  CHECK(handover_at == 21 + 5);
  CHECK(modes.mode() == MagneticMode::kSpinCapture);
  // The spin law starts afresh: no Ḃ from detumble's samples.
  CHECK_FALSE(modes.step({Eigen::Vector4d::Zero(), fieldSeen(0.002, 40), true}, 41 * kSecond).active);
}

TEST_CASE("without after_detumble the law stays in detumble", "[unloading_controller][bdot]") {
  auto p = detumbleThenSpin();
  p.after_detumble.reset();
  MagneticModes modes(p);
  for (std::int64_t k = 0; k < 30; ++k) {
    CHECK_FALSE(modes.step({Eigen::Vector4d::Zero(), fieldSeen(0.001, k), true}, k * kSecond).handover);
  }
  CHECK(modes.mode() == MagneticMode::kDetumble);
}

TEST_CASE("a mode command switches the law and reports the unloading thresholds", "[unloading_controller][bdot]") {
  MagneticModesParams p;
  p.unload.wheels.count = 3;
  p.unload.wheels.inertia_kg_m2 = Eigen::Vector4d(1e-4, 1e-4, 1e-4, 0.0);
  p.unload.h_start_Nms = 0.02;
  p.unload.h_stop_Nms = 0.01;
  p.unload.max_dipole_Am2.setConstant(1e3);
  MagneticModes modes(p);
  const Eigen::Vector4d speeds(300.0, 0.0, 0.0, 0.0);  // 0.03 Nms on x
  auto out = modes.step({speeds, Eigen::Vector3d(0, 30e-6, 0), true}, 0);
  CHECK(out.mode == MagneticMode::kUnload);
  CHECK(out.h_above_start);
  CHECK_FALSE(out.h_below_stop);
  CHECK(out.active);
  modes.command(MagneticMode::kDetumble);
  out = modes.step({speeds, Eigen::Vector3d(0, 30e-6, 0), true}, kSecond);
  CHECK(out.mode == MagneticMode::kDetumble);
  CHECK_FALSE(out.active);  // first sample of the new law
  out = modes.step({speeds, Eigen::Vector3d(0, 31e-6, 0), true}, 2 * kSecond);
  CHECK(out.active);
  CHECK(out.m_B_Am2.y() < 0.0);  // −m0 sgn(Ḃ_y)
}

TEST_CASE("mode parameters are validated with their scenario keys", "[unloading_controller][bdot]") {
  MagneticModesParams p;
  p.after_detumble = MagneticMode::kDetumble;
  p.detumble.gain_Am2_s_per_T = -1.0;
  p.spin.orbit_rate_rad_s = 0.0;
  const auto errors = p.validate();
  const auto has = [&](const std::string& prefix) {
    return std::any_of(errors.begin(), errors.end(), [&](const std::string& e) { return e.rfind(prefix, 0) == 0; });
  };
  CHECK(has("after_detumble: "));
  CHECK(has("detumble.gain_Am2_s_per_T: "));
  CHECK(has("spin_capture.orbit_rate_rad_s: "));
  CHECK_THROWS_AS(MagneticModes(p), std::invalid_argument);
}
