// SPDX-License-Identifier: Apache-2.0
// Seed S2 in closed loop at 400 km (algorithms.md S2; deploy/scenarios/s2_aero.yaml):
// the coils and the flaps together give the torque the unloading law asks for, the flaps no
// more of it than its component along B (up to B's tilt out of their roll-yaw plane), and the
// flaps drag less than when they take roll and yaw alone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kScenario = std::string(FLATSAT_SCENARIO_DIR) + "/s2_aero.yaml";
const std::string kEquatorial = std::string(FLATSAT_SCENARIO_DIR) + "/s2_equatorial.yaml";

double norm3(const nlohmann::json& a) { return std::hypot(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); }

struct Met {
  std::vector<double> relative_error;  // |M × B + τ_flaps − delivered·C| / |C| per step with a demand
  int replaced = 0;                    // flap commands that used the replacement table
  double max_angle_plate4 = 0.0;       // [rad]
  std::array<double, 3> flap_torque_abs_sum{};  // [N m] Σ|τ_flaps| per body axis (plant), steps with a demand
};

/// Every step with a demand C (flatsat/flap_cmd at k): the plant's magnetic and flap torques
/// held over [k, k+1] (truth at k + 1) against the share of C the split delivered.
Met torquesMet(const std::string& out) {
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t flap_cmd")
              .exit_code == 0);
  std::map<std::uint64_t, nlohmann::json> truth;
  for (auto& row : test::exportedRows(fs::path(out) / "export", "truth")) truth[row["header"]["step"]] = row;
  Met met;
  for (const auto& cmd : test::exportedRows(fs::path(out) / "export", "flap_cmd")) {
    const std::uint64_t k = cmd["header"]["step"];
    met.replaced += cmd["replaced"].get<bool>() ? 1 : 0;
    met.max_angle_plate4 = std::max(met.max_angle_plate4, std::abs(cmd["theta_rad"][3].get<double>()));
    const auto& C = cmd["c_demand_body_Nm"];
    if (norm3(C) == 0.0 || !truth.count(k + 1)) continue;
    const auto& t = truth[k + 1];
    const double share = cmd["delivered"].get<double>();
    double error_sq = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double given = t["tau_magnetic_body_Nm"][i].get<double>() + t["tau_flaps_body_Nm"][i].get<double>();
      error_sq += std::pow(given - share * C[i].get<double>(), 2);
      met.flap_torque_abs_sum[static_cast<std::size_t>(i)] += std::abs(t["tau_flaps_body_Nm"][i].get<double>());
    }
    met.relative_error.push_back(std::sqrt(error_sq) / norm3(C));
  }
  std::sort(met.relative_error.begin(), met.relative_error.end());
  return met;
}

double quantile(const std::vector<double>& sorted, double q) {
  return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
}

}  // namespace

TEST_CASE("S2 at 400 km: coils and flaps meet the demanded torque, the flaps with its component along B",
          "[unloading_controller][system][s2]") {
  // Composed: ComposedTest shows s2_aero records the same over DDS, every component its own process.
  const std::string out = test::freshDir("s2-aero");
  const auto run = test::runScenario(kScenario, out, "--composed", true);
  const auto& s = run.summary;
  INFO(s.dump(2));
  const Met met = torquesMet(out);
  INFO("steps with a demand " << met.relative_error.size() << ", relative error median "
                              << quantile(met.relative_error, 0.5) << ", p99 " << quantile(met.relative_error, 0.99));
  REQUIRE(met.relative_error.size() > 15000);  // 3 orbits at 1 Hz, the law asks for C = −k H throughout
  // The plant's panel model (specular plates, the true wind) against the onboard closed form
  // K (c_ax, 0, c_az) and the onboard field through the attitude estimate.
  CHECK(quantile(met.relative_error, 0.5) < 0.005);
  CHECK(quantile(met.relative_error, 0.99) < 0.01);
  CHECK(s["torque_delivered_mean"].get<double>() > 0.99);
  // No more flap torque than the least any roll-yaw pair completing C needs; that least is
  // |C·B̂| up to B's few degrees out of the orbit plane.
  CHECK(s["aero_torque_ratio"].get<double>() <= 1.01 * s["aero_torque_ratio_least"].get<double>());
  CHECK(s["aero_torque_ratio_least"].get<double>() < 1.05);
  CHECK(s["drag_ratio"].get<double>() < 0.9);
  CHECK(s["wheel_saturation_events"].get<int>() == 0);
  CHECK(s["wheel_momentum_Nms_max"].get<double>() < 0.1);
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.05);  // the seed's orbital frame held by the wheels
  fs::remove_all(out);
}

TEST_CASE("S2 at 400 km: the seed's closed-form angles (rules IV-IX) beside the exact ones, over the same run",
          "[unloading_controller][system][s2]") {
  // flap_torque_error_pct_rms: the flaps' share of the demand (eq. II) against the torque
  // the commanded angles give by the seed's own shapes. Exact: the Newton solution, to
  // rounding. The seed's closed forms solve the small-angle shapes (√(1 − sin²θ) → 1):
  // 2.21 % RMS measured (docs/magnetic_control.md), pinned at 1.5×.
  const auto exact = test::runScenario(kScenario, test::freshDir("s2-exact"), "--composed");
  const auto seed = test::runScenario(kScenario, test::freshDir("s2-seed"),
                                      "--composed --set components.unloading_controller.aero.flap_solver=seed");
  INFO(exact.summary.dump(2) << "\n" << seed.summary.dump(2));
  CHECK(exact.summary["flap_torque_error_pct_rms"].get<double>() < 1e-6);
  CHECK(seed.summary["flap_torque_error_pct_rms"].get<double>() > 2.21 / 1.5);
  CHECK(seed.summary["flap_torque_error_pct_rms"].get<double>() < 2.21 * 1.5);
  // The same unloading either way: the wheels hold what they held.
  CHECK(seed.summary["wheel_momentum_Nms_max"].get<double>() ==
        Approx(exact.summary["wheel_momentum_Nms_max"].get<double>()).epsilon(0.01));
}

TEST_CASE("S2 at 400 km with SPOT's field onboard (claim 5: harmonic 1, or 1, 3 and 5) against IGRF onboard",
          "[unloading_controller][system][s2]") {
  // The split runs on the onboard field through the attitude estimate; the plant is IGRF-14.
  // With SPOT's cheap model (Bx = −B0 cos u, Bz = −2 B0 sin u) the coils' dipole and the flaps'
  // share are computed for the wrong field, and the torque the plant gives misses the demand;
  // the unloading loop closes around it. Measured (docs/magnetic_control.md), pinned at 1.5×.
  struct Case {
    const char* name;
    const char* set;
    double median, p99, momentum_Nms;
  };
  // The seed's improved model (harmonics 1, 3 and 5) barely helps: along a real orbit the
  // field's longitude terms, which no function of u alone follows, dominate the error.
  for (const Case& c : {Case{"igrf14", "onboard.field_model=igrf14", 0.000908, 0.00335, 0.0498},
                        Case{"spot", "onboard.field_model=spot", 0.209, 0.526, 0.0498},
                        Case{"spot-odd", "onboard.field_model=spot --set onboard.spot_harmonics=odd", 0.216, 0.461, 0.0498}}) {
    const std::string out = test::freshDir(std::string("s2-onboard-") + c.name);
    const auto run = test::runScenario(kScenario, out, std::string("--composed --set ") + c.set, true);
    const Met met = torquesMet(out);
    WARN(c.name << " onboard: torque error median " << quantile(met.relative_error, 0.5) << ", p99 "
                << quantile(met.relative_error, 0.99) << "; wheel momentum max "
                << run.summary["wheel_momentum_Nms_max"].get<double>() << " N m s");
    CHECK(quantile(met.relative_error, 0.5) < 1.5 * c.median);
    CHECK(quantile(met.relative_error, 0.5) > c.median / 1.5);
    CHECK(quantile(met.relative_error, 0.99) < 1.5 * c.p99);
    CHECK(run.summary["wheel_momentum_Nms_max"].get<double>() < 1.5 * c.momentum_Nms);
    CHECK(run.summary["wheel_saturation_events"].get<int>() == 0);
    fs::remove_all(out);
  }
}

TEST_CASE("S2 at 400 km: less flap drag than flaps alone, and the wheels full without unloading",
          "[unloading_controller][system][s2]") {
  const auto seed = test::runScenario(kScenario, test::freshDir("s2-seed"), "--composed").summary;
  const auto alone =
      test::runScenario(kScenario, test::freshDir("s2-alone"),
                        "--composed --set components.unloading_controller.aero.split=flaps_only")
          .summary;
  const auto off = test::runScenario(kScenario, test::freshDir("s2-off"),
                                     "--composed --set components.unloading_controller.enabled=false")
                       .summary;
  INFO("seed split: " << seed.dump(2) << "\nflaps alone: " << alone.dump(2) << "\nunloading off: " << off.dump(2));
  // Measured on the plant in two closed loops, not inferred from the angles.
  CHECK(seed["flap_drag_N_mean"].get<double>() < 0.9 * alone["flap_drag_N_mean"].get<double>());
  CHECK(alone["aero_torque_ratio"].get<double>() > 1.2 * seed["aero_torque_ratio"].get<double>());
  CHECK(alone["torque_delivered_mean"].get<double>() > 0.99);
  CHECK(seed["wheel_momentum_Nms_end"].get<double>() < 0.2 * off["wheel_momentum_Nms_end"].get<double>());
}

TEST_CASE("S2 at 400 km: a failed flap is replaced and the torque still met", "[unloading_controller][system][s2]") {
  const std::string out = test::freshDir("s2-failed");
  const auto s =
      test::runScenario(kScenario, out, "--composed --set components.unloading_controller.aero.failed_flap=4", true)
          .summary;
  INFO(s.dump(2));
  const Met met = torquesMet(out);
  CHECK(met.max_angle_plate4 == 0.0);  // plate 4 stays edge-on
  CHECK(met.replaced > 1000);          // its jobs went to plate 2, or to the spread yaw pattern
  CHECK(quantile(met.relative_error, 0.99) < 0.01);
  CHECK(s["torque_delivered_mean"].get<double>() > 0.99);
  CHECK(s["wheel_momentum_Nms_max"].get<double>() < 0.1);
  fs::remove_all(out);
}

TEST_CASE("S2 on the equatorial orbit (claim 8): flaps on wings along yaw give roll and pitch, the axis the coils lack",
          "[unloading_controller][system][s2]") {
  // s2_equatorial.yaml: the field lies 18 deg from the pitch axis on average (28 at most), so the coils
  // cannot unload pitch; the flaps, on wings along z, give roll and pitch and no yaw.
  // Measured (docs/magnetic_control.md, "The equatorial orbit"), pinned at 1.5x.
  const std::string out = test::freshDir("s2-equatorial");
  const auto seed = test::runScenario(kEquatorial, out, "--composed", true).summary;
  const Met met = torquesMet(out);
  const auto coils = test::runScenario(kEquatorial, test::freshDir("s2-equatorial-coils"),
                                       "--composed --set components.unloading_controller.aero.split=drag_only")
                         .summary;
  const auto polar = test::runScenario(kEquatorial, test::freshDir("s2-equatorial-wings-y"),
                                       "--composed --set spacecraft.flaps.wings_along=y")
                         .summary;
  INFO("seed split: " << seed.dump(2) << "\ncoils alone: " << coils.dump(2) << "\nwings along y: " << polar.dump(2));
  const auto& sum = met.flap_torque_abs_sum;
  INFO("flap torque sums (roll, pitch, yaw) " << sum[0] << ", " << sum[1] << ", " << sum[2] << " N m; torque error median "
                                            << quantile(met.relative_error, 0.5) << ", p99 "
                                            << quantile(met.relative_error, 0.99));
  // The plates' centres of pressure are on the z axis: no arm about z, no yaw at all, on the
  // plant's panel model with the true wind. Most of their torque is pitch (8.2 x the roll).
  CHECK(sum[2] <= 1e-12 * (sum[0] + sum[1]));
  CHECK(sum[1] > 8.15 / 1.5 * sum[0]);
  // The plant's coils and flaps against the demand; the flaps' relative error grows where the
  // true wind's small tilt meets small plate angles (0.23 % median, 1.48 % p99 measured).
  CHECK(quantile(met.relative_error, 0.5) < 1.5 * 0.0023);
  CHECK(quantile(met.relative_error, 0.99) < 1.5 * 0.0148);
  CHECK(seed["torque_delivered_mean"].get<double>() > 0.99);
  CHECK(seed["aero_torque_ratio"].get<double>() <= 1.01 * seed["aero_torque_ratio_least"].get<double>());
  CHECK(seed["aero_torque_ratio_least"].get<double>() < 1.05);  // 1.035: B 18 deg off pitch, mostly in the roll-pitch plane
  CHECK(seed["flap_drag_N_mean"].get<double>() < 1.5 * 1.39e-5);
  CHECK(seed["flap_drag_N_mean"].get<double>() > 1.39e-5 / 1.5);
  CHECK(seed["wheel_momentum_Nms_max"].get<double>() < 1.5 * 0.0565);
  CHECK(seed["wheel_saturation_events"].get<int>() == 0);
  // The coils alone (flaps edge-on): the pitch wheel fills, 0.223 N m s after 3 orbits.
  CHECK(coils["wheel_momentum_Nms_end"].get<double>() > 0.223 / 1.5);
  CHECK(coils["wheel_momentum_Nms_end"].get<double>() < 1.5 * 0.223);
  CHECK(seed["wheel_momentum_Nms_end"].get<double>() < 0.2 * coils["wheel_momentum_Nms_end"].get<double>());
  // The polar arrangement here unloads as well, but B lies near the normal of its roll-yaw
  // plane: 3.8x the flap torque of |C.B^| and 2.8x claim 8's flap drag.
  CHECK(polar["aero_torque_ratio"].get<double>() > 3.82 / 1.5);
  CHECK(polar["aero_torque_ratio"].get<double>() < 1.5 * 3.82);
  CHECK(polar["flap_drag_N_mean"].get<double>() < 1.5 * 3.92e-5);
  CHECK(polar["flap_drag_N_mean"].get<double>() > 2.82 / 1.5 * seed["flap_drag_N_mean"].get<double>());
  fs::remove_all(out);
}
