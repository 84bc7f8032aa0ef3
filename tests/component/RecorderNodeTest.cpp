// SPDX-License-Identifier: Apache-2.0
// The recorder node against a scripted time master that plays the dynamics
// server and a gyro: every stepped sample and grant of the run is in the
// recording when the node is done, byte for byte as written, one per step
// (or one per `record_every_steps`), and the meta its reader gave it in its meta table.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>

#include "bus/Convert.hpp"
#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/TimeMaster.hpp"
#include "components/recorder/RecorderNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 30;

/// The gyro's rate at step k: distinct at every step, so a sample stored at the wrong step shows.
Eigen::Vector3d rateAt(std::uint64_t k) { return 1e-3 * Eigen::Vector3d(1.0, 2.0, 3.0) * static_cast<double>(k); }

class ScriptedPeers final : public bus::TimeMaster {
 public:
  ScriptedPeers(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}) {}

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, "dynamics_server");
    bus::put(truth.q_inertial_body(), Eigen::Quaterniond::Identity());
    truth_.write(truth);
    msg::GyroReading gyro;
    bus::stamp(gyro.header(), ctx, "gyro");
    bus::put(gyro.w_body_rad_s(), rateAt(ctx.step));
    gyro.valid(true);
    gyro_.write(gyro);
  }
  void advance(const bus::StepContext&) override {}
  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::WriterOf<bus::topics::kGyro>& gyro_ = addOutput(bus::topics::kGyro);
};

/// Runs the script and a recorder storing every `every` steps into `path`.
void recordRun(const std::string& path, std::uint32_t every) {
  const bus::Schedule node_view = {{"dynamics_server", 1}, {"recorder", 1}, {"gyro", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"recorder", 1}};
  test::NodeTestBuses buses("recorder");
  ScriptedPeers script(buses.script, {"dynamics_server", master_view});
  recorder::RecorderParams params;
  params.path = path;
  params.record_every_steps = every;
  params.meta = {{bus::meta::kSchedule, "dynamics_server=1,recorder=1,gyro=1"}};
  auto node = std::make_unique<recorder::RecorderNode>(buses.node, test::fedByScript({"recorder", node_view}), params);
  test::runTogether(script, *node);
  node.reset();  // closes the recording
}

}  // namespace

TEST_CASE("recorder node stores every stepped sample and grant, byte for byte, one per step",
          "[recorder][component][dds]") {
  const auto dir = std::filesystem::temp_directory_path() / ("flatsat-recorder-node-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "every.sqlite").string();
  recordRun(path, 1);

  const bus::Recording recording(path, bus::Recording::Access::kRead);
  const std::string gyro(bus::topics::kGyro.name);
  CHECK(recording.count(std::string(bus::topics::kTruth.name)) == kSteps);
  CHECK(recording.count(std::string(bus::topics::kStepGrant.name)) == kSteps);
  REQUIRE(recording.count(gyro) == kSteps);
  std::uint64_t expected = 0;
  recording.forEach(gyro, [&](std::uint64_t step, const std::string& source, const std::vector<std::uint8_t>& bytes) {
    CAPTURE(step);
    CHECK(step == expected++);
    CHECK(source == "gyro");
    const auto stored = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kGyro)>>(bytes);
    CHECK(stored.header().step() == step);
    CHECK(bus::vec3(stored.w_body_rad_s()) == rateAt(step));
    CHECK(stored.valid());
  });
  CHECK(recording.meta(bus::meta::kSchedule) == "dynamics_server=1,recorder=1,gyro=1");
  std::filesystem::remove_all(dir);
}

TEST_CASE("recorder node decimated stores the steps that are multiples of record_every_steps only",
          "[recorder][component][dds]") {
  const auto dir = std::filesystem::temp_directory_path() / ("flatsat-recorder-every-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "every4.sqlite").string();
  recordRun(path, 4);
  const bus::Recording recording(path, bus::Recording::Access::kRead);
  const std::uint64_t kept = (kSteps + 3) / 4;  // steps 0, 4, ..., 28
  CHECK(recording.count(std::string(bus::topics::kGyro.name)) == kept);
  CHECK(recording.count(std::string(bus::topics::kStepGrant.name)) == kept);
  recording.forEach(std::string(bus::topics::kGyro.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>&) { CHECK(step % 4 == 0); });
  std::filesystem::remove_all(dir);
}
