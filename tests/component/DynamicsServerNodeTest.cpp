// SPDX-License-Identifier: Apache-2.0
// The dynamics server node (the time master) against a scripted attitude
// controller that commands constant wheel motor torques. With no external
// torque and no momentum at the start, the total momentum stays zero, so the
// gyrostat's equation (sim/RigidBodyWheels.hpp) reduces to J'ω̇ = −A τ_m and the
// body rate published at step k is exactly ω(t_k) = −J'⁻¹ A τ_m t_k: the command
// stamped k held over [t_k, t_k+1), from step 0 on, and the truth stamped t_k.
#include <catch2/catch.hpp>


#include "bus/Component.hpp"
#include "bus/Convert.hpp"
#include "components/dynamics_server/DynamicsServerNode.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 20;
const Eigen::Vector3d kMotorTorque_Nm(0.01, -0.02, 0.005);

class ScriptedController final : public bus::Component {
 public:
  ScriptedController(bus::Bus& bus, bus::NodeOptions options) : Component(bus, std::move(options)) {}
  std::map<std::uint64_t, msg::TruthState> truth;

 private:
  void step(const bus::StepContext& ctx) override {
    truth[ctx.step] = truth_.at(ctx.step);
    msg::WheelTorqueCmd command;
    bus::stamp(command.header(), ctx, "attitude_controller");
    bus::put(command.torque_Nm(), Eigen::Vector4d(kMotorTorque_Nm.x(), kMotorTorque_Nm.y(), kMotorTorque_Nm.z(), 0.0));
    command_.write(command);
  }
  bus::InputOf<bus::topics::kTruth>& truth_ = addInput(bus::topics::kTruth);
  bus::WriterOf<bus::topics::kWheelTorqueCmd>& command_ = addOutput(bus::topics::kWheelTorqueCmd);
};

}  // namespace

TEST_CASE("dynamics server node holds each wheel command over its step and conserves the momentum",
          "[dynamics_server][component][dds]") {
  dynamics_server::DynamicsServerParams params;
  sim::DynamicsParams& p = params.dynamics;
  p.body.J_B_kg_m2 = Eigen::Vector3d(10.0, 12.0, 14.0).asDiagonal();
  p.body.wheel_count = 3;
  p.body.wheel_axes_B.leftCols<3>() = Eigen::Matrix3d::Identity();
  p.body.wheel_inertia_kg_m2 = Eigen::Vector4d(0.01, 0.01, 0.01, 0.0);
  p.body.wheel_max_torque_Nm = Eigen::Vector4d(1.0, 1.0, 1.0, 0.0);
  p.body.wheel_max_momentum_Nms = Eigen::Vector4d(10.0, 10.0, 10.0, 0.0);
  p.gravity_gradient = false;  // no external torque: the field meets no dipole, no air, no panels
  params.step_period_ns = 100'000'000;
  params.final_step = kSteps - 1;

  const bus::Schedule view = {{"dynamics_server", 1}, {"attitude_controller", 1}};
  // The script is the attitude controller's own participant: the server takes its producer's samples.
  test::NodeTestBuses buses("dynamics_server", "attitude_controller");
  dynamics_server::DynamicsServerNode server(buses.node, {"dynamics_server", view}, params);
  ScriptedController controller(buses.script, {"attitude_controller", view});
  test::runTogether(server, controller);

  REQUIRE(controller.truth.size() == kSteps);
  // J' = J − I_w Σ a aᵀ: the body's inertia without the rotors' spin.
  const Eigen::Matrix3d J_spinless = p.body.J_B_kg_m2 - 0.01 * Eigen::Matrix3d::Identity();
  for (const auto& [k, truth] : controller.truth) {
    CAPTURE(k);
    const double t_s = 0.1 * static_cast<double>(k);
    CHECK(truth.header().step() == k);
    CHECK(truth.header().sim_time_ns() == static_cast<std::int64_t>(k) * params.step_period_ns);
    CHECK(bus::vec3(truth.h_total_inertial_Nms()).norm() < 1e-12);
    const Eigen::Vector3d expected = -J_spinless.inverse() * kMotorTorque_Nm * t_s;
    CHECK((bus::vec3(truth.w_body_rad_s()) - expected).norm() < 1e-12);
  }
}
