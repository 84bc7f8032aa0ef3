// SPDX-License-Identifier: Apache-2.0
// The unloading controller node against scripted peers over real DDS: a
// scripted time master that also plays the wheel tachometer and the
// magnetometer, with known samples each step; the dipole the node sends
// must be the cross-product law (algorithms.md, "The unloading law")
// computed here independently, stamped with the step it answers.
#include <catch2/catch.hpp>

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>
#include <thread>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/TestDomain.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 40;
constexpr double kGain = 0.01;      // [1/s]
constexpr double kMaxDipole = 50.0; // [A m^2]
constexpr double kWheelInertia = 0.1;

Eigen::Vector4d speedsAt(std::uint64_t k) { return {100.0 + k, -50.0, 20.0 + 0.5 * k, 0.0}; }
Eigen::Vector3d fieldAt(std::uint64_t k) {
  return Eigen::Vector3d(2e-5 * std::cos(0.1 * k), 1e-5, -3e-5 * std::sin(0.1 * k));
}

/// A parameter change the script sends with the inputs of a step.
struct ParamChange {
  std::uint64_t step;
  std::uint64_t id;
  std::string key;
  double value;
};

class ScriptedPeers final : public bus::TimeMaster {
 public:
  ScriptedPeers(bus::Bus& bus, bus::NodeOptions options, std::optional<std::uint64_t> detumble_at = {},
                std::vector<ParamChange> changes = {})
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}),
        detumble_at_(detumble_at),
        changes_(std::move(changes)) {}
  std::map<std::uint64_t, msg::DipoleCmd> received;
  std::vector<msg::CommandAck> acks;  // as they came (a Fast DDS thread), read after run()

 private:
  void publishStep(const bus::StepContext& ctx) override {
    for (const auto& change : changes_) {
      if (change.step != ctx.step) continue;
      msg::ParamCmd command;
      bus::stamp(command.header(), ctx, "operator");
      command.command_id(change.id);
      bus::setText(command.target(), "unloading_controller");
      bus::setText(command.key(), change.key);
      command.value(change.value);
      param_.write(command);
    }
    if (detumble_at_ == ctx.step) {
      msg::ModeCmd command;
      bus::stamp(command.header(), ctx, "operator");
      command.mode(msg::MAGNETIC_DETUMBLE);
      mode_.write(command);
    }
    msg::WheelTachReading tach;
    bus::stamp(tach.header(), ctx, "wheel_tach");
    bus::put(tach.wheel_speed_rad_s(), speedsAt(ctx.step));
    tach.valid(true);
    tach_.write(tach);
    msg::MagnetometerReading field;
    bus::stamp(field.header(), ctx, "magnetometer");
    bus::put(field.b_body_T(), fieldAt(ctx.step));
    field.valid(true);
    field_.write(field);
  }
  void advance(const bus::StepContext& ctx) override {
    received[ctx.step] = dipole_.at(ctx.step);
  }
  bus::WriterOf<bus::topics::kWheelTach>& tach_ = addOutput(bus::topics::kWheelTach);
  bus::WriterOf<bus::topics::kMagnetometer>& field_ = addOutput(bus::topics::kMagnetometer);
  bus::InputOf<bus::topics::kDipoleCmd>& dipole_ = addInput(bus::topics::kDipoleCmd);
  bus::WriterOf<bus::topics::kUnloadingModeCmd>& mode_ = addOutput(bus::topics::kUnloadingModeCmd);
  bus::WriterOf<bus::topics::kParamCmd>& param_ = addOutput(bus::topics::kParamCmd);
  std::mutex acks_mutex_;
  bus::ReaderOf<bus::topics::kCommandAck> ack_reader_{bus_, bus::topics::kCommandAck, [this](const msg::CommandAck& a) {
                                                        std::lock_guard lock(acks_mutex_);
                                                        acks.push_back(a);
                                                      }};
  std::optional<std::uint64_t> detumble_at_;
  std::vector<ParamChange> changes_;
};

/// The unloading law with gain kGain on three wheels along x, y, z of kWheelInertia.
unloading_controller::MagneticModesParams crossProduct(double max_dipole_Am2) {
  unloading_controller::MagneticModesParams params;
  params.unload.gain_per_s = kGain;
  params.unload.max_dipole_Am2 = Eigen::Vector3d::Constant(max_dipole_Am2);
  params.unload.wheels.count = 3;
  params.unload.wheels.axes_B = Eigen::Matrix<double, 3, 4>::Identity();
  params.unload.wheels.inertia_kg_m2 = Eigen::Vector4d(kWheelInertia, kWheelInertia, kWheelInertia, 0);
  return params;
}

}  // namespace

TEST_CASE("unloading controller node answers every step with the cross-product law",
          "[unloading_controller][component][dds]") {
  const std::uint32_t domain = test::testDomain();
  const auto params = crossProduct(kMaxDipole);  // initial mode: unload

  const bus::Schedule node_view = {
      {"dynamics_server", 1}, {"unloading_controller", 1}, {"wheel_tach", 1}, {"magnetometer", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"unloading_controller", 1}};

  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "unloading_controller"});
  ScriptedPeers script(script_bus, {"dynamics_server", master_view});
  unloading_controller::UnloadingControllerNode node(node_bus, test::fedByScript({"unloading_controller", node_view}),
                                                     {params});
  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.received.size() == kSteps);
  for (const auto& [k, dipole] : script.received) {
    CAPTURE(k);
    CHECK(dipole.header().step() == k);
    CHECK(bus::text(dipole.header().source()) == "unloading_controller");
    const Eigen::Vector3d h = kWheelInertia * speedsAt(k).head<3>();  // axes are x, y, z
    const Eigen::Vector3d b = fieldAt(k);
    Eigen::Vector3d m = kGain * h.cross(b) / b.squaredNorm();
    const double scale = std::max(1.0, m.cwiseAbs().maxCoeff() / kMaxDipole);
    m /= scale;
    const Eigen::Vector3d got = bus::vec3(dipole.m_body_Am2());
    CHECK((got - m).norm() <= 1e-9 * m.norm());
    CHECK(dipole.saturated() == (scale > 1.0));
    // The torque the dipole makes opposes the stored momentum across B.
    const Eigen::Vector3d h_perp = h - b * b.dot(h) / b.squaredNorm();
    CHECK((got.cross(b) + kGain / scale * h_perp).norm() <= 1e-9 * h_perp.norm() * kGain);
  }
}

TEST_CASE("a mode command on flatsat/unloading_mode_cmd switches the node to B-dot", "[unloading_controller][component][dds][bdot]") {
  const std::uint32_t domain = test::testDomain();
  unloading_controller::MagneticModesParams params;  // initial mode: unload
  params.unload.max_dipole_Am2 = Eigen::Vector3d::Constant(kMaxDipole);
  params.detumble.max_dipole_Am2 = Eigen::Vector3d::Constant(kMaxDipole);
  const bus::Schedule node_view = {
      {"dynamics_server", 1}, {"unloading_controller", 1}, {"wheel_tach", 1}, {"magnetometer", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"unloading_controller", 1}};
  constexpr std::uint64_t kCommandStep = 10;

  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "unloading_controller"});
  ScriptedPeers script(script_bus, {"dynamics_server", master_view}, kCommandStep);
  unloading_controller::UnloadingControllerNode node(node_bus, test::fedByScript({"unloading_controller", node_view}), {params});
  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.received.size() == kSteps);
  std::optional<std::uint64_t> switched;
  for (const auto& [k, dipole] : script.received) {
    CAPTURE(k);
    if (k < kCommandStep) CHECK(dipole.mode() == msg::MAGNETIC_UNLOAD);  // sent with step 10's inputs
    if (!switched && dipole.mode() == msg::MAGNETIC_DETUMBLE) switched = k;
    if (switched) CHECK(dipole.mode() == msg::MAGNETIC_DETUMBLE);  // and it stays
    if (switched && k > *switched) {
      // B-dot, bang-bang: each coil at its limit against the field's change (off where B_i is constant).
      const Eigen::Vector3d b_dot = fieldAt(k) - fieldAt(k - 1);
      for (int i = 0; i < 3; ++i) {
        CHECK(dipole.m_body_Am2()[i] == (b_dot[i] == 0.0 ? 0.0 : -std::copysign(kMaxDipole, b_dot[i])));
      }
      CHECK(dipole.active());
    }
  }
  REQUIRE(switched);
  CHECK(*switched < kSteps - 5);
}

TEST_CASE("the unloading controller takes gain and threshold changes in flight, refuses bad ones",
          "[unloading_controller][component][dds][cmd]") {
  const std::uint32_t domain = test::testDomain();
  const auto params = crossProduct(1e6);  // never saturates: m ∝ k
  const bus::Schedule node_view = {
      {"dynamics_server", 1}, {"unloading_controller", 1}, {"wheel_tach", 1}, {"magnetometer", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"unloading_controller", 1}};
  // Doubled gain at step 10; a stop threshold above the start one at 12 (refused); an unknown key at 14.
  const std::vector<ParamChange> changes = {
      {10, 1, "gain_per_s", 2 * kGain}, {12, 2, "h_stop_Nms", 5.0}, {14, 3, "colour", 1.0}};

  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "unloading_controller"});
  ScriptedPeers script(script_bus, {"dynamics_server", master_view}, std::nullopt, changes);
  unloading_controller::UnloadingControllerNode node(node_bus, test::fedByScript({"unloading_controller", node_view}), {params});
  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.acks.size() == 3);
  std::map<std::uint64_t, msg::CommandAck> by_id;
  for (const auto& ack : script.acks) by_id[ack.command_id()] = ack;
  CHECK(by_id[1].accepted());
  CHECK_FALSE(by_id[2].accepted());
  CHECK(bus::text(by_id[2].reason()).find("h_start_Nms") != std::string::npos);
  CHECK_FALSE(by_id[3].accepted());
  CHECK(bus::text(by_id[3].reason()).find("colour: not settable") != std::string::npos);
  const std::uint64_t from = by_id[1].header().step();  // the step the new gain applies from
  REQUIRE(script.received.size() == kSteps);
  for (const auto& [k, dipole] : script.received) {
    CAPTURE(k, from);
    const Eigen::Vector3d h = kWheelInertia * speedsAt(k).head<3>();
    const Eigen::Vector3d b = fieldAt(k);
    const double gain = k >= from ? 2 * kGain : kGain;
    CHECK((bus::vec3(dipole.m_body_Am2()) - gain * h.cross(b) / b.squaredNorm()).norm() <=
          1e-9 * gain * h.cross(b).norm() / b.squaredNorm());
  }
}
