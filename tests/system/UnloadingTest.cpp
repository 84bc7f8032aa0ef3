// SPDX-License-Identifier: Apache-2.0
// The unloading pin: 10 orbits of the ROSAT-like rig under gravity-gradient,
// drag and solar-pressure torques, the cross-product law with hysteresis
// (deploy/scenarios/unloading_10orbits.yaml), against the same run with it off,
// and with the field from the onboard model and the attitude estimate.
#include <catch2/catch.hpp>

#include "tests/support/Rig.hpp"

using namespace flatsat;

TEST_CASE("cross-product unloading holds the wheels inside its start threshold over 10 orbits",
          "[unloading_controller][system][slow][unloading]") {
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/unloading_10orbits.yaml";
  // Composed (ComposedTest: the same recording as the multi-process rig): ten orbits in seconds.
  const auto on = test::runScenario(scenario, test::freshDir("u10-on"), "--composed").summary;
  const auto off = test::runScenario(scenario, test::freshDir("u10-off"),
                                     "--composed --set components.unloading_controller.enabled=false")
                       .summary;
  INFO(on.dump(2));
  INFO(off.dump(2));
  CHECK(on["sim_seconds"].get<double>() >= 10 * 5700);
  // h_start_Nms in the scenario: stored momentum never more than 10 % above it.
  constexpr double kStart_Nms = 3.0;
  CHECK(on["wheel_momentum_Nms_max"].get<double>() <= 1.1 * kStart_Nms);
  CHECK(on["wheel_saturation_events"].get<int>() == 0);
  CHECK(on["pointing_error_deg_max"].get<double>() < 0.5);
  // The third field source: the onboard IGRF turned into body axes by the
  // attitude estimate, no magnetometer reading used: the same bound holds.
  const auto model = test::runScenario(scenario, test::freshDir("u10-model"),
                                       "--composed --set components.unloading_controller.field_source=model_attitude")
                         .summary;
  INFO(model.dump(2));
  CHECK(model["wheel_momentum_Nms_max"].get<double>() <= 1.1 * kStart_Nms);
  CHECK(model["wheel_saturation_events"].get<int>() == 0);
  // Off, the disturbances pile up in the wheels until they saturate.
  CHECK(off["wheel_saturation_events"].get<int>() > 0);
  CHECK(off["wheel_momentum_Nms_max"].get<double>() > 5 * on["wheel_momentum_Nms_max"].get<double>());
}
