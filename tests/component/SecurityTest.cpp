// SPDX-License-Identifier: Apache-2.0
// DDS Security as deploy/security/make-certs.sh sets it up (bus/Security.hpp):
// the operator commands a component; a participant without a certificate
// neither sees nor injects commands; a component's grant does not let it
// command; and a grant the participant signed itself (the Fast DDS 2.9.1
// one-CA trap) is refused because grants must chain to the permissions CA.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "bus/Endpoints.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "tests/support/SecuredBus.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/Within.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

msg::FaultCmd faultCommand(std::uint64_t id) {
  msg::FaultCmd command;
  command.command_id(id);
  bus::setText(command.target(), "gyro");
  bus::setText(command.kind(), "bias");
  return command;
}

}  // namespace

TEST_CASE("with DDS Security only the operator commands, strangers and forged grants are shut out",
          "[component][dds][security]") {
  const test::Certificates certs("gyro operator");
  const std::uint32_t domain = test::testDomain();

  bus::Bus gyro(test::secured(certs, domain, "gyro"));
  std::atomic<int> received{0};
  std::atomic<std::uint64_t> last_id{0};
  bus::ReaderOf<bus::topics::kFaultCmd> commands(gyro, bus::topics::kFaultCmd,
                                                 [&](const msg::FaultCmd& c) {
                                                   last_id = c.command_id();
                                                   ++received;
                                                 });

  SECTION("a participant without a certificate neither sees nor injects commands") {
    bus::Bus operator_bus(test::secured(certs, domain, "operator"));
    bus::WriterOf<bus::topics::kFaultCmd> genuine(operator_bus, bus::topics::kFaultCmd);
    // Two open participants: one listens, one injects.
    bus::Bus listener({.domain_id = domain, .participant_name = "eavesdropper"});
    std::atomic<int> overheard{0}, heard_from_injector{0};
    bus::ReaderOf<bus::topics::kFaultCmd> eavesdropper(
        listener, bus::topics::kFaultCmd,
        [&](const msg::FaultCmd& c) { ++(c.command_id() == 666 ? heard_from_injector : overheard); });
    bus::Bus injector({.domain_id = domain, .participant_name = "injector"});
    bus::WriterOf<bus::topics::kFaultCmd> forged(injector, bus::topics::kFaultCmd);

    // The operator's command arrives: the channel works.
    REQUIRE(test::within(20, [&] { return genuine.matchedReaders() == 1; }));
    genuine.write(faultCommand(1));
    REQUIRE(test::within(10, [&] { return received.load() == 1; }));
    CHECK(last_id == 1);
    // The rogue stays unmatched both ways however long it tries; its writes go nowhere.
    for (int i = 0; i < 30; ++i) {
      forged.write(faultCommand(666));
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    CHECK(forged.matchedReaders() == 1);  // only the other stranger,
    CHECK(heard_from_injector > 0);       // which hears the injector
    CHECK(overheard == 0);                // but never the operator
    CHECK(eavesdropper.matchedWriters() == 1);
    CHECK(received == 1);
    CHECK(last_id == 1);
  }

  SECTION("a component's grant does not allow commanding") {
    // The local access check refuses the writer (DDS-Security 1.1 §8.4.2.9.7
    // check_create_datawriter), so the bus cannot make it.
    CHECK_THROWS_WITH((bus::WriterOf<bus::topics::kFaultCmd>(gyro, bus::topics::kFaultCmd)),
                      Catch::Contains("flatsat/fault_cmd"));
    // Its own topics it may publish.
    CHECK_NOTHROW(bus::WriterOf<bus::topics::kGyro>(gyro, bus::topics::kGyro));
  }

  SECTION("a grant signed by its own participant, not the permissions CA, is refused") {
    // The gyro's identity is genuine, its grant (the operator's rules) is signed with its own key.
    const fs::path forged = certs.dir / "forged";
    fs::create_directories(forged / "gyro");
    for (const char* file : {"identity_ca.pem", "permissions_ca.pem", "governance.p7s"}) {
      fs::copy_file(certs.dir / file, forged / file);
    }
    for (const char* file : {"cert.pem", "key.pem"}) {
      fs::copy_file(certs.dir / "gyro" / file, forged / "gyro" / file);
    }
    std::string grant;
    {
      std::ifstream in(certs.dir / "operator" / "permissions.xml");
      grant.assign(std::istreambuf_iterator<char>(in), {});
    }
    grant.replace(grant.find("CN=operator"), std::string("CN=operator").size(), "CN=gyro");
    std::ofstream(forged / "gyro" / "permissions.xml") << grant;
    const auto signing = test::runCommand(
        "openssl smime -sign -text -in " + (forged / "gyro" / "permissions.xml").string() +
        " -out " + (forged / "gyro" / "permissions.p7s").string() + " -signer " +
        (forged / "gyro" / "cert.pem").string() + " -inkey " +
        (forged / "gyro" / "key.pem").string() + " 2>&1");
    INFO(signing.output);
    REQUIRE(signing.exit_code == 0);
    auto options = test::secured(certs, domain, "gyro");
    options.security_dir = forged.string();
    CHECK_THROWS_WITH(bus::Bus(options),
                      Catch::Contains("did not verify"));
  }
}
