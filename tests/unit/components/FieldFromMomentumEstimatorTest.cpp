// SPDX-License-Identifier: Apache-2.0
// Seed S0 (DE3606636 / US4746085): field and roll angle from the stored momentum
// alone, checked against momentum histories integrated from the seed's own
// equations of motion with a large constant disturbance present.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <map>

#include <Eigen/LU>

#include "components/estimator/FieldFromMomentumEstimator.hpp"
#include "components/estimator/FieldFromMomentum.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::estimator;

namespace {

constexpr std::int64_t kStepNs = 100'000'000;  // 0.1 s samples

/// The seed's plant: dH/dt = Ms + M × B(t) − ω × H in a body frame turning at ω
/// about x; the inertial field b_N seen from the body, B(t) = Rx(α0 + ωt)ᵀ b_N.
struct RollingBody {
  double w_x = 2.0e-4;                                   // [rad/s] roll rate
  double alpha0 = 0.3;                                   // [rad]
  Eigen::Vector3d b_SE_T{1.5e-5, -2.2e-5, 1.2e-5};       // [T] field, Sun-ecliptic frame
  Eigen::Vector3d disturbance_B_Nm{2e-3, -8e-3, 6e-3};   // [N m] ~2x the pulse torque
  Eigen::Vector3d h_B_Nms{0.5, 1.5, -2.0};               // [Nms]
  double t_s = 0.0;

  double alpha(double t) const { return alpha0 + w_x * t; }
  Eigen::Vector3d field(double t) const { return s0BodyField(b_SE_T, alpha(t)); }
  Eigen::Vector3d rate() const { return {w_x, 0.0, 0.0}; }
  Eigen::Vector3d dh(double t, const Eigen::Vector3d& h, const Eigen::Vector3d& m) const {
    return disturbance_B_Nm + m.cross(field(t)) - rate().cross(h);
  }
  /// RK4 over one 0.1 s sample in 10 substeps, dipole held.
  void advance(const Eigen::Vector3d& m) {
    const double dt = 0.01;
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d k1 = dh(t_s, h_B_Nms, m);
      const Eigen::Vector3d k2 = dh(t_s + dt / 2, h_B_Nms + dt / 2 * k1, m);
      const Eigen::Vector3d k3 = dh(t_s + dt / 2, h_B_Nms + dt / 2 * k2, m);
      const Eigen::Vector3d k4 = dh(t_s + dt, h_B_Nms + dt * k3, m);
      h_B_Nms += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      t_s += dt;
    }
  }
};

/// Mean of the body field over [a, b] (what a pulse over [a, b] measures).
Eigen::Vector3d meanField(const RollingBody& body, double a, double b) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const int n = 1000;
  for (int i = 0; i < n; ++i) sum += body.field(a + (i + 0.5) * (b - a) / n);
  return sum / n;
}

/// Runs one window through the plant and returns the solver fed every sample.
FieldFromMomentum runWindow(RollingBody& body, const DipoleWindow& w, double average_s,
                              const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& measure) {
  FieldFromMomentum solver(average_s);
  for (std::int64_t t = 0; t <= w.t2_ns; t += kStepNs) {
    solver.add({t, measure(body.h_B_Nms), body.rate()}, 1e9);
    const bool on = t >= w.t1_ns && t < w.pulse_end_ns;
    body.advance(on ? w.m_B_Am2 : Eigen::Vector3d::Zero());
  }
  return solver;
}

/// Seed S0's unequal windows (Δt1 = 20 s, Δt2 = 30 s, so Q21 = 1.5 and Q31 = 2.5) on
/// `body`, the momentum as `read` gives it (H [Nms], t [s]): the seed's closed form
/// (algorithms.md S0, written out independently of the solver) and the general solution,
/// each against the mean field over the pulse. The seed's rectangle rule for ∫ω×H costs it
/// accuracy of order ω·Δt·|ΔH|/(M·Δt): both within 1 %, the general form within 0.1 %.
void checkSeedClosedForm(RollingBody& body, const std::function<Eigen::Vector3d(const Eigen::Vector3d&, double)>& read) {
  const double t0 = 10.0, t1 = 30.0, t2 = 60.0, mx = 80.0;
  DipoleWindow w{ns(t0), ns(t1), ns(t2), ns(t2), {mx, 0.0, 0.0}};
  std::map<std::int64_t, Eigen::Vector3d> h;
  FieldFromMomentum solver(0.0);
  for (std::int64_t t = 0; t <= w.t2_ns; t += kStepNs) {
    h[t] = read(body.h_B_Nms, static_cast<double>(t) * 1e-9);
    solver.add({t, h[t], body.rate()}, 1e9);
    body.advance(t >= w.t1_ns && t < w.pulse_end_ns ? w.m_B_Am2 : Eigen::Vector3d::Zero());
  }
  const double Q2 = 1.0 / (mx * (t2 - t1)), Q21 = (t2 - t1) / (t1 - t0), Q31 = (t2 - t0) / (t1 - t0);
  const double om = body.w_x, dt2 = t2 - t1;
  const auto& H0 = h.at(ns(t0));
  const auto& H1 = h.at(ns(t1));
  const auto& H2 = h.at(ns(t2));
  const double by = Q2 * (H2.z() - Q31 * H1.z() + Q21 * H0.z() + om * dt2 * (H1.y() - H0.y()));
  const double bz = Q2 * (-H2.y() + Q31 * H1.y() - Q21 * H0.y() + om * dt2 * (H1.z() - H0.z()));
  const auto solution = solver.solve(w);
  REQUIRE(solution);
  const Eigen::Vector3d truth = meanField(body, t1, t2);
  INFO("seed " << by << " " << bz << "  general " << solution->b_perp_B_T.transpose() << "  truth "
               << truth.transpose());
  CHECK(std::hypot(by - truth.y(), bz - truth.z()) < 1e-2 * truth.norm());
  CHECK((solution->b_perp_B_T.tail<2>() - truth.tail<2>()).norm() < 1e-3 * truth.norm());
}

}  // namespace

TEST_CASE("S0: the field perpendicular to the dipole follows from the momentum alone",
          "[estimator][s0]") {
  RollingBody body;
  DipoleWindow w{ns(5.0), ns(35.0), ns(65.0), ns(65.0), {100.0, 0.0, 0.0}};
  const auto solver = runWindow(body, w, 0.0, [](const Eigen::Vector3d& h) { return h; });
  const auto solution = solver.solve(w);
  REQUIRE(solution);
  const Eigen::Vector3d truth = meanField(body, 35.0, 65.0);
  INFO("estimate " << solution->b_perp_B_T.transpose() << " truth " << truth.transpose());
  // By and Bz to 0.1 % of |B| with a disturbance twice the pulse's torque: it cancels.
  CHECK(std::abs(solution->b_perp_B_T.x()) < 1e-12);
  CHECK((solution->b_perp_B_T.tail<2>() - truth.tail<2>()).norm() < 1e-3 * truth.norm());
  CHECK((solution->disturbance_B_Nm - body.disturbance_B_Nm).norm() <
        1e-3 * body.disturbance_B_Nm.norm());
  CHECK(std::abs(solution->along_dipole_Nm) < 1e-6);
  CHECK(solution->t_ref_ns == ns(50.0));
}

TEST_CASE("S0: the seed's closed form (Q2, Q21, Q31) agrees with the general solution",
          "[estimator][s0]") {
  RollingBody body;
  checkSeedClosedForm(body, [](const Eigen::Vector3d& h, double) { return h; });
}

TEST_CASE("S0: any dipole direction gives the field perpendicular to it", "[estimator][s0]") {
  RollingBody body;
  DipoleWindow w{ns(2.0), ns(22.0), ns(42.0), ns(50.0), {60.0, -40.0, 30.0}};
  const auto solver = runWindow(body, w, 0.5, [](const Eigen::Vector3d& h) { return h; });
  const auto solution = solver.solve(w);
  REQUIRE(solution);
  const Eigen::Vector3d m = w.m_B_Am2.normalized();
  const Eigen::Vector3d truth = meanField(body, 22.0, 42.0);
  const Eigen::Vector3d truth_perp = truth - truth.dot(m) * m;
  CHECK((solution->b_perp_B_T - truth_perp).norm() < 2e-3 * truth.norm());
  CHECK(std::abs(solution->b_perp_B_T.dot(m)) < 1e-15);
}

TEST_CASE("S0: a quiet interval after the pulse removes a disturbance that changes linearly",
          "[estimator][s0]") {
  // Gravity gradient on a large spacecraft turns at twice the orbit rate: over a
  // minute it changes by a good part of the pulse's torque. Ramp: 5e-5 N m/s.
  const auto error = [](std::int64_t after_ns) {
    RollingBody body;
    body.w_x = 0.0;
    const Eigen::Vector3d ramp(1e-5, 5e-5, -4e-5);
    DipoleWindow w{ns(1.0), ns(31.0), ns(61.0), ns(61.0) + after_ns, {100.0, 0.0, 0.0}};
    FieldFromMomentum solver(1.0);
    const Eigen::Vector3d d0 = body.disturbance_B_Nm;
    for (std::int64_t t = 0; t <= w.t2_ns; t += kStepNs) {
      solver.add({t, body.h_B_Nms, body.rate()}, 1e9);
      // The ramp, held over each 0.1 s sample at its mid-time value.
      body.disturbance_B_Nm = d0 + ramp * (static_cast<double>(t) * 1e-9 + 0.05);
      body.advance(t >= w.t1_ns && t < w.pulse_end_ns ? w.m_B_Am2 : Eigen::Vector3d::Zero());
    }
    const auto solution = solver.solve(w);
    REQUIRE(solution);
    const Eigen::Vector3d truth = meanField(body, 31.0, 61.0);
    return (solution->b_perp_B_T.tail<2>() - truth.tail<2>()).norm() / truth.norm();
  };
  const double seed_form = error(0);
  const double with_quiet_after = error(ns(30.0));
  INFO("seed form " << seed_form << ", quiet after " << with_quiet_after);
  // Seed form: the ramp adds ramp·τ² to the pulse's impulse m·|B|·τ: ~ 6e-5·30/(100·2.9e-5) = 60 %.
  CHECK(seed_form > 0.3);
  CHECK(with_quiet_after < 1e-3);
}

TEST_CASE("S0: a window not held in the buffer or with no dipole gives nothing", "[estimator][s0]") {
  RollingBody body;
  DipoleWindow w{ns(5.0), ns(15.0), ns(25.0), ns(25.0), {100.0, 0.0, 0.0}};
  const auto solver = runWindow(body, w, 0.0, [](const Eigen::Vector3d& h) { return h; });
  DipoleWindow later = w;
  later.t2_ns = ns(40.0);
  CHECK_FALSE(solver.solve(later));
  DipoleWindow zero = w;
  zero.m_B_Am2.setZero();
  CHECK_FALSE(solver.solve(zero));
  DipoleWindow reversed = w;
  reversed.t1_ns = reversed.t0_ns;
  CHECK_FALSE(solver.solve(reversed));
}

TEST_CASE("S0: the roll angle round-trips through the body field", "[estimator][s0]") {
  const Eigen::Vector3d b_SE(1.1e-5, -2.5e-5, 1.7e-5);
  for (double alpha = -3.1; alpha < 3.14; alpha += 0.05) {
    const Eigen::Vector3d b_B = s0BodyField(b_SE, alpha);
    CHECK(b_B.norm() == Approx(b_SE.norm()).epsilon(1e-14));
    CHECK(b_B.x() == b_SE.x());
    CHECK(s0RollAngle(b_B.y(), b_B.z(), b_SE.y(), b_SE.z()) == Approx(alpha).margin(1e-12));
  }
  CHECK(std::isnan(s0RollAngle(1e-5, 1e-5, 0.0, 0.0)));
}

namespace {

struct CycleRun {
  std::vector<WindowRequest> requests;
  std::vector<Eigen::Vector3d> h_at_request;  // [Nms] stored momentum when each was asked
  std::vector<bool> valid_at_request;
  double alpha_error_max = 0.0, field_error_max = 0.0;
  FieldFromMomentumOutput last;
};

/// The estimator against the rolling body and a scripted coil owner that starts
/// each asked window at once and reports it done at its end.
CycleRun driveCycles(const FieldFromMomentumParams& p, RollingBody& body, double duration_s) {
  FieldFromMomentumEstimator estimator(p);
  std::optional<WindowRequest> running;
  DipoleWindow window;
  CycleRun run;
  bool valid = false;
  for (std::int64_t t = 0; t <= ns(duration_s); t += kStepNs) {
    FieldFromMomentumInput in;
    in.wheel_speed_rad_s.head<3>() = body.h_B_Nms;
    in.tach_valid = true;
    in.w_B_rad_s = body.rate();
    in.gyro_valid = true;
    in.sun_B_unit = Eigen::Vector3d::UnitX();
    in.sun_valid = t < ns(duration_s - 100.0);  // no new window once the Sun is lost
    in.R_SE_N = Eigen::Matrix3d::Identity();
    in.b_N_ref_T = body.b_SE_T;
    if (running && t == window.t2_ns) {
      in.completed = std::make_pair(running->id, window);
      running.reset();
    }
    run.last = estimator.step(in, t);
    if (run.last.valid) {
      const double t_s = static_cast<double>(t) * 1e-9;
      run.alpha_error_max = std::max(run.alpha_error_max, std::abs(run.last.alpha_rad - body.alpha(t_s)));
      run.field_error_max = std::max(run.field_error_max, (run.last.b_B_T - body.field(t_s)).norm() /
                                                              body.field(t_s).norm());
    }
    if (run.last.request && !running) {
      running = run.last.request;
      run.requests.push_back(*running);
      run.h_at_request.push_back(body.h_B_Nms);
      run.valid_at_request.push_back(valid);
      window.t0_ns = t;
      window.t1_ns = t + ns(running->quiet_s);
      window.pulse_end_ns = window.t1_ns + ns(running->pulse_s);
      window.t2_ns = window.pulse_end_ns + ns(running->quiet_after_s);
      window.m_B_Am2 = running->m_B_Am2;
    }
    valid = run.last.valid;
    const bool on = running && t >= window.t1_ns && t < window.pulse_end_ns;
    body.advance(on ? window.m_B_Am2 : Eigen::Vector3d::Zero());
  }
  return run;
}

FieldFromMomentumParams cycleParams() {
  FieldFromMomentumParams p;
  p.wheels.count = 3;
  p.wheels.inertia_kg_m2 = Eigen::Vector4d::Ones();  // speeds read as momenta
  p.quiet_s = 20.0;
  p.pulse_s = 20.0;
  p.quiet_after_s = 0.0;
  p.cycle_period_s = 120.0;
  p.dipole_Am2 = 100.0;
  p.average_s = 0.0;
  return p;
}

}  // namespace

TEST_CASE("S0 cycle: the estimator asks for windows and tracks the roll angle", "[estimator][s0]") {
  RollingBody body;
  const auto run = driveCycles(cycleParams(), body, 600.0);
  CHECK(run.last.valid);
  CHECK(run.last.cycles == 5);
  CHECK(run.last.failed_cycles == 0);
  // The field over a 20 s pulse turns by ω·10 s = 2e-3 rad from its mid-time value.
  CHECK(run.alpha_error_max < 2e-3);
  CHECK(run.field_error_max < 3e-3);
  REQUIRE(run.requests.size() == 5);
  CHECK(run.requests[0].m_B_Am2.x() == -run.requests[1].m_B_Am2.x());  // impulses cancel
}

TEST_CASE("S0 cycle: with the unloading sign, each pulse drains the stored momentum", "[estimator][s0]") {
  auto p = cycleParams();
  p.unloading_sign = true;
  RollingBody body;
  body.disturbance_B_Nm.setZero();
  body.w_x = 0.0;
  const auto run = driveCycles(p, body, 600.0);
  REQUIRE(run.requests.size() == 5);
  int unloading_pulses = 0;
  for (std::size_t i = 0; i < run.requests.size(); ++i) {
    if (!run.valid_at_request[i]) continue;
    // The cross-product law's x coil: sign of (H × B)_x; its torque m × B removes H⊥.
    const Eigen::Vector3d b = body.field(0.0);
    const double law_x = run.h_at_request[i].cross(b).x();
    CHECK(run.requests[i].m_B_Am2.x() * law_x > 0.0);
    ++unloading_pulses;
  }
  CHECK(unloading_pulses == 4);
  // An x dipole's torque lies along u = x × B: each pulse of 100 A m² for 20 s moves
  // H·u by 100·|x × B|·20 ≈ 0.05 Nms, the first (sign not yet known) either way, the
  // four others towards zero.
  const Eigen::Vector3d h0(0.5, 1.5, -2.0);
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX().cross(body.field(0.0));
  const double step = 100.0 * u.norm() * 20.0;
  INFO("H.u from " << h0.dot(u.normalized()) << " to " << body.h_B_Nms.dot(u.normalized()));
  CHECK(std::abs(body.h_B_Nms.dot(u.normalized())) <
        std::abs(h0.dot(u.normalized())) - 3 * step + 1e-3);
}

TEST_CASE("S0: the seed's closed form on ROSAT's four skewed wheels, their null-space motion included",
          "[estimator][s0]") {
  // ROSAT's layout (deploy/scenarios/default.yaml): two wheels in the x–z plane 20° off z,
  // two in the x–y plane 20° off y, 0.12 kg m² each. The body's momentum reaches the
  // closed form only as four tachometer speeds, made here by an independent pseudo-inverse
  // plus a null-space motion (a·n = 0: no body momentum) that grows through the window, as
  // momentum management moves it: what is checked is the read through the skewed axes and
  // inertias (WheelGeometry::momentum_B_Nms), and that the null-space motion leaves no
  // trace in the seed's form or the general one.
  WheelGeometry rosat;
  rosat.count = 4;
  const double s = 0.3420201433, c = 0.9396926208;
  rosat.axes_B << s, -s, s, -s,  //
      0.0, 0.0, c, c,            //
      c, c, 0.0, 0.0;
  rosat.inertia_kg_m2 = Eigen::Vector4d::Constant(0.12);
  const Eigen::Matrix<double, 3, 4> a = rosat.axes_B;
  const Eigen::Matrix<double, 4, 3> share = a.transpose() * (a * a.transpose()).inverse();
  const Eigen::Vector4d null_space = Eigen::FullPivLU<Eigen::Matrix<double, 3, 4>>(a).kernel().col(0).normalized();
  REQUIRE((a * null_space).norm() < 1e-12);
  const auto speeds = [&](const Eigen::Vector3d& h_B, double t_s) -> Eigen::Vector4d {
    return (share * h_B + null_space * (5.0 + 0.2 * t_s)) / 0.12;  // [rad/s]
  };

  RollingBody body;
  checkSeedClosedForm(body, [&](const Eigen::Vector3d& h_B, double t_s) {
    return rosat.momentum_B_Nms(speeds(h_B, t_s));  // as the four tachometers read it
  });
}
