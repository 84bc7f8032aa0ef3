// SPDX-License-Identifier: Apache-2.0
// The least-privilege grants of deploy/security/make-certs.sh (`flatsat
// security-grants`, from the topic registry): every component identity may
// write the topics it produces and no other component's, and read only what
// its node reads; the operator only
// commands; `replay` feeds recorded topics; and every component's code can
// still make each of its endpoints under its own grant.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "bus/Endpoints.hpp"
#include "bus/NodeMain.hpp"
#include "bus/Security.hpp"
#include "bus/Topics.hpp"
#include "components/Registry.hpp"
#include "tests/support/SecuredBus.hpp"
#include "tests/support/TestDomain.hpp"
#include "vehicle/VehicleReader.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

/// Makes (and deletes) a writer on the registry topic `name`; throws what
/// bus::Writer throws when the grant refuses it.
void writerOn(bus::Bus& bus, const std::string& name) {
  bool found = false;
  bus::forEachTopic([&](const auto& def) {
    if (def.name != name) return;
    found = true;
    bus::Writer<std::remove_cvref_t<decltype(def)>> writer(bus, def);
  });
  if (!found) throw std::logic_error(name + ": not a registry topic");
}

bool mayWrite(bus::Bus& bus, const std::string& name) {
  try {
    writerOn(bus, name);
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

/// The component that stands behind `identity`'s stepped topics: itself, or
/// for a hardware bridge `<producer>_bridge` that producer.
std::string producerFor(const std::string& identity) {
  const std::string suffix = "_bridge";
  return identity.ends_with(suffix) ? identity.substr(0, identity.size() - suffix.size()) : identity;
}

}  // namespace

TEST_CASE("each identity's grant lets it write its own topics and refuses every other producer's",
          "[component][dds][security]") {
  const test::Certificates certs;  // every identity
  const std::uint32_t domain = test::testDomain();
  const std::string truth(bus::topics::kTruth.name);

  for (const auto& kind : componentKinds()) {
    INFO("identity " << kind.name);
    bus::Bus bus(test::secured(certs, domain, kind.name));
    // Its own topic: the first stepped one the registry names it (or, a bridge, its producer)
    // the producer of; else its health.
    std::string own(bus::topics::kHealth.name);
    bus::forEachTopic([&](const auto& def) {
      if (own == bus::topics::kHealth.name && def.qos == bus::QosKind::kStepped && def.producer == producerFor(kind.name)) {
        own = def.name;
      }
    });
    CHECK_NOTHROW(writerOn(bus, own));
    // One foreign topic, by the local access check (DDS-Security 1.1 §8.4.2.9.7): the writer is never made.
    const std::string foreign = kind.name == bus::topics::kTruth.producer ? std::string(bus::topics::kDipoleCmd.name) : truth;
    CHECK_THROWS_WITH(writerOn(bus, foreign), Catch::Contains("could not create a writer on " + foreign));
    // And all the others: another producer's topics, the grants and the commands.
    bus::forEachTopic([&](const auto& def) {
      const bool others = !def.producer.empty() && def.producer != producerFor(kind.name);
      const bool command = def.name == bus::topics::kFaultCmd.name || def.name == bus::topics::kUnloadingModeCmd.name ||
                           def.name == bus::topics::kParamCmd.name;
      if (others || command) {
        INFO("topic " << def.name);
        CHECK_FALSE(mayWrite(bus, std::string(def.name)));
      }
    });
  }

  {  // a component reads only what its node reads: the gyro takes the truth, never the commands
    bus::Bus gyro(test::secured(certs, domain, "gyro"));
    CHECK_NOTHROW(bus::ReaderOf<bus::topics::kTruth>(gyro, bus::topics::kTruth, [](const msg::TruthState&) {}));
    CHECK_THROWS(bus::ReaderOf<bus::topics::kDipoleCmd>(gyro, bus::topics::kDipoleCmd, [](const msg::DipoleCmd&) {}));
  }

  {  // the operator commands and does not write the rig's data
    bus::Bus operator_bus(test::secured(certs, domain, bus::kOperatorIdentity));
    CHECK_THROWS_WITH(writerOn(operator_bus, truth), Catch::Contains("could not create a writer on " + truth));
    CHECK_FALSE(mayWrite(operator_bus, std::string(bus::topics::kStepGrant.name)));
    CHECK_FALSE(mayWrite(operator_bus, std::string(bus::topics::kDipoleCmd.name)));
    CHECK_FALSE(mayWrite(operator_bus, std::string(bus::topics::kCommandAck.name)));
    CHECK(mayWrite(operator_bus, std::string(bus::topics::kFaultCmd.name)));
    CHECK(mayWrite(operator_bus, std::string(bus::topics::kUnloadingModeCmd.name)));
    CHECK(mayWrite(operator_bus, std::string(bus::topics::kParamCmd.name)));
    CHECK(mayWrite(operator_bus, std::string(bus::topics::kFaultEvent.name)));  // the launcher's "restarted"
  }

  {  // `flatsat replay` feeds recorded stepped topics and grants, and does not command
    bus::Bus replay_bus(test::secured(certs, domain, "replay"));
    CHECK(mayWrite(replay_bus, truth));
    CHECK(mayWrite(replay_bus, std::string(bus::topics::kGyro.name)));
    CHECK(mayWrite(replay_bus, std::string(bus::topics::kStepGrant.name)));
    CHECK_FALSE(mayWrite(replay_bus, std::string(bus::topics::kFaultCmd.name)));
    CHECK_FALSE(mayWrite(replay_bus, std::string(bus::topics::kStepDone.name)));
  }
}

TEST_CASE("every component's code makes its endpoints under its own grant", "[component][dds][security]") {
  const test::Certificates certs;
  const std::uint32_t domain = test::testDomain();
  const fs::path out = fs::temp_directory_path() / ("flatsat-grants-nodes-" + std::to_string(::getpid()));
  fs::create_directories(out);
  std::vector<bus::Scenario> scenarios;
  for (const auto& entry : fs::directory_iterator(FLATSAT_SCENARIO_DIR)) {
    if (entry.path().extension() == ".yaml") scenarios.push_back(bus::loadScenario(entry.path().string()));
  }
  for (const auto& kind : componentKinds()) {
    if (!kind.make) continue;  // a bridge or device stand-in: it needs its serial device
    // Each scenario that lists it: what a node reads depends on its parameters.
    // One participant for them all: a process that makes a hundred secured
    // participants in a row leaves the ones after unable to match.
    bus::Bus bus(test::secured(certs, domain, kind.name));
    for (const auto& scenario : scenarios) {
      if (!scenario.hasComponent(kind.name)) continue;
      INFO(kind.name << " of " << scenario.file);
      std::optional<bus::Bus::WatchersHeld> held(std::in_place, bus);
      CHECK_NOTHROW(kind.make(bus, bus::nodeOptions(scenario, kind.name), scenario, vehicle::vehicleOf(scenario),
                              {scenario.file, kind.name, out.string()}));
      held.reset();
    }
  }
  fs::remove_all(out);
}
