// SPDX-License-Identifier: Apache-2.0
// Which readers of a component's process are best-effort (bus/NodeMain.hpp
// processBusOptions, bus/Qos.hpp QosTuning::best_effort_readers): no DDS.
#include <catch2/catch.hpp>

#include "bus/NodeMain.hpp"
#include "bus/Qos.hpp"
#include "tests/support/ScopedEnv.hpp"

// In the library's namespace rather than `using` it: in a unity batch a
// using-directive would reach the test files after this one.
namespace flatsat::bus {
namespace {

namespace dds = eprosima::fastdds::dds;

bool readsBestEffort(const Scenario& scenario, const NodeArgs& args) {
  return processBusOptions(scenario, args, kEmulatorStrength).tuning.best_effort_readers;
}

}  // namespace

TEST_CASE("only a scheduled component of a lockstep rig on shared memory reads best-effort, and only its stepped and protocol topics",
          "[bus][qos]") {
  using test::ScopedEnv;
  const ScopedEnv no_peers("FLATSAT_PEERS", nullptr), no_servers("FLATSAT_DISCOVERY_SERVER", nullptr),
      no_network("FLATSAT_NETWORK", nullptr), shm("FLATSAT_SHARED_MEMORY", nullptr),
      no_security("FLATSAT_SECURE_DIR", nullptr);
  Scenario lockstep;
  lockstep.pacing = Pacing::kLockstep;
  lockstep.components = {{.name = "estimator"}, {.name = "recorder"}, {.name = "magnetometer_device"}};
  lockstep.components.back().scheduled = false;
  const NodeArgs recorder{.name = "recorder", .shared_memory_rig = true};
  CHECK(readsBestEffort(lockstep, recorder));
  // A producer of stepped topics trails the time master no farther than a sink (bus/StepReports.hpp).
  CHECK(readsBestEffort(lockstep, {.name = "estimator", .shared_memory_rig = true}));
  // Without the launcher's word a writer may be on another host.
  CHECK_FALSE(readsBestEffort(lockstep, {.name = "recorder"}));
  Scenario paced = lockstep;
  paced.pacing = Pacing::kPaced;  // no trail bounds how far the recorder lags
  CHECK_FALSE(readsBestEffort(paced, recorder));
  {
    const ScopedEnv off("FLATSAT_SHARED_MEMORY", "0");
    CHECK_FALSE(readsBestEffort(lockstep, recorder));
  }
  {
    // DDS Security turns data sharing off, whoever set the variable.
    const ScopedEnv secure("FLATSAT_SECURE_DIR", "/nonexistent");
    CHECK_FALSE(readsBestEffort(lockstep, recorder));
  }
  // A process the time master does not schedule (a device stand-in) has no trail to bound its lag.
  CHECK_FALSE(readsBestEffort(lockstep, {.name = "magnetometer_device", .shared_memory_rig = true}));

  QosTuning tuning;
  tuning.best_effort_readers = true;
  CHECK(readerQos(QosKind::kStepped, tuning).reliability().kind == dds::BEST_EFFORT_RELIABILITY_QOS);
  // Grants and StepDones lag no more than stepped samples (the time master keeps the
  // grants' pool until everyone stopped); health and commands are not bounded by the
  // trail: they stay reliable.
  CHECK(readerQos(QosKind::kProtocol, tuning).reliability().kind == dds::BEST_EFFORT_RELIABILITY_QOS);
  CHECK(readerQos(QosKind::kState, tuning).reliability().kind == dds::RELIABLE_RELIABILITY_QOS);
  CHECK(readerQos(QosKind::kCommand, tuning).reliability().kind == dds::RELIABLE_RELIABILITY_QOS);
  // Transient-local still: on matching, a data-sharing reader takes the writer's history from its pool.
  CHECK(readerQos(QosKind::kStepped, tuning).durability().kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS);
  CHECK(readerQos(QosKind::kStepped).reliability().kind == dds::RELIABLE_RELIABILITY_QOS);
}

TEST_CASE("a lockstep rig acknowledges over shared memory only when the launcher owns every process", "[bus][qos]") {
  using test::ScopedEnv;
  const ScopedEnv no_peers("FLATSAT_PEERS", nullptr), no_servers("FLATSAT_DISCOVERY_SERVER", nullptr),
      no_network("FLATSAT_NETWORK", nullptr);
  Scenario lockstep;
  lockstep.pacing = Pacing::kLockstep;
  lockstep.components = {{.name = "estimator"}, {.name = "wheel_tach"}};
  const NodeArgs estimator{.name = "estimator", .shared_memory_rig = true};
  CHECK(processBusOptions(lockstep, estimator, kEmulatorStrength).acks_over_shm);
  // An external process may be killed holding a shared-memory port's lock (NodeMain.cpp).
  lockstep.components.back().launched = false;
  const auto with_external = processBusOptions(lockstep, estimator, kEmulatorStrength);
  CHECK_FALSE(with_external.acks_over_shm);
  CHECK_FALSE(with_external.shared_memory);  // nor data over it: any shared lock can be held by the dead
  CHECK_FALSE(with_external.tuning.data_sharing);
  Scenario paced = lockstep;
  paced.pacing = Pacing::kPaced;
  CHECK_FALSE(processBusOptions(paced, estimator, kEmulatorStrength).shared_memory);  // paced takes the locks too
  paced.components.back().launched = true;
  CHECK(processBusOptions(paced, estimator, kEmulatorStrength).shared_memory);
  CHECK_FALSE(processBusOptions(paced, estimator, kEmulatorStrength).acks_over_shm);
}

TEST_CASE("components grant themselves their steps only in a lockstep rig the launcher started whole",
          "[bus][step_protocol]") {
  Scenario lockstep;
  lockstep.pacing = Pacing::kLockstep;
  lockstep.components = {{.name = "estimator"}};
  CHECK(nodeOptions(lockstep, NodeArgs{.name = "estimator", .shared_memory_rig = true}).implied_grants);
  // Started by anyone else (compose, `flatsat replay`): a grant a step, as a foreign component expects.
  CHECK_FALSE(nodeOptions(lockstep, NodeArgs{.name = "estimator"}).implied_grants);
  Scenario paced = lockstep;
  paced.pacing = Pacing::kPaced;  // the wall clock grants
  CHECK_FALSE(nodeOptions(paced, NodeArgs{.name = "estimator", .shared_memory_rig = true}).implied_grants);
}

}  // namespace flatsat::bus
