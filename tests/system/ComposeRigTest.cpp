// SPDX-License-Identifier: Apache-2.0
// The rig in Docker containers (deploy/compose/run.sh): one container per
// component on an internal compose network gives the one-host recording bit
// for bit, with discovery through a Fast DDS discovery server while the
// network drops every multicast datagram, and with multicast discovery; the
// health checks read the health topic; nothing reaches the host's own
// interface. Skipped, saying why, where no Docker engine answers.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kRunSh = std::string(FLATSAT_SOURCE_DIR) + "/deploy/compose/run.sh";
using test::kDefault;
// The containers' start (discovery) and these steps last long enough for
// several health probes at 2 s. With 120 s, on a loaded machine (the suite
// at -j3), a gyro's first probe, which waits for discovery, was still
// waiting when the run ended 3.3 s later.
const std::string kLength = "--set duration_orbits=null --set duration_s=300";
const std::vector<std::string> kComponents = {
    "dynamics_server", "magnetometer", "sun_sensor", "gyro", "wheel_tach",
    "estimator", "attitude_controller", "unloading_controller", "recorder"};

bool dockerReady() {
  for (const char* tool : {"docker", "docker-compose", "nft", "tcpdump", "debootstrap"}) {
    if (test::runCommand(std::string("command -v ") + tool).exit_code != 0) {
      WARN("SKIPPED: " << tool << " is not installed; the compose rig needs it");
      return false;
    }
  }
  const auto info = test::runCommand("docker info --format '{{.ServerVersion}}'");
  if (info.exit_code != 0) {
    WARN("SKIPPED: no Docker engine answers (" << info.output << "); start one with 'dockerd &'");
    return false;
  }
  return true;
}

struct ComposeRun {
  test::CommandResult command;
  nlohmann::json summary;
  int bridge_rtps = 0;       // RTPS datagrams on the rig's bridge ports (each seen going in and out)
  int bridge_multicast = 0;  // of them, to an IPv4 multicast group
  int host_rtps = 0;         // RTPS datagrams on the host's own interface
};

/// The compose rig with captures on its bridge and on the host's interface.
ComposeRun runCompose(const std::string& tag, const std::string& environment) {
  const std::string id = tag + std::to_string(::getpid() % 100000);
  const std::string out = test::freshDir("compose-" + tag);
  const std::string bridge_pcap = out + "-bridge.pcap", host_pcap = out + "-host.pcap";
  const std::string script = out + ".sh";
  // The bridge appears once compose made the network: the capture waits for it.
  std::ofstream(script)
      << "host_if=$(ip route show default | awk '{print $5; exit}')\n"
      << "tcpdump -i ${host_if:-eth0} -n -p -U -w " << host_pcap << " '" << test::kRtpsFilter
      << "' 2>/dev/null & host_dump=$!\n"
      // A bridge device shows only what is addressed to it, not what it
      // forwards: the veth ports (all interfaces but loopback) show that; of
      // them, only this rig's domain (another test's rig may run beside it).
      << "tcpdump -i any -n -p -U -w " << bridge_pcap << " '" << test::rtpsFilterOfTestDomain()
      << " and not net 127.0.0.0/8' 2>/dev/null & bridge_dump=$!\nsleep 1\n"
      << "FLATSAT_DOMAIN=" << test::testDomain() << " FLATSAT_RIG_ID=" << id << " " << environment << " " << kRunSh
      << " " << kDefault << " " << out
      << " -q " << kLength << "\nrc=$?\nsleep 1\nkill -INT $host_dump $bridge_dump 2>/dev/null\n"
      << "wait $host_dump $bridge_dump\necho rc=$rc\n";
  ComposeRun run;
  run.command = test::runCommand("bash " + script);
  INFO(run.command.output);
  REQUIRE(run.command.output.find("rc=0") != std::string::npos);
  run.summary = test::readSummary(out);
  run.bridge_rtps = test::capturedPackets(bridge_pcap, "");
  run.bridge_multicast = test::capturedPackets(bridge_pcap, "dst net 224.0.0.0/4");
  run.host_rtps = test::capturedPackets(host_pcap, "");
  for (const auto& component : kComponents) {  // each health check passed at least once
    std::ifstream file(fs::path(out) / "logs" / (component + ".health.json"));
    nlohmann::json health;
    file >> health;
    INFO(component << " health: " << health.dump());
    bool passed = false;
    for (const auto& probe : health["Log"]) passed |= probe["ExitCode"] == 0;
    CHECK(passed);
  }
  fs::remove_all(out);
  for (const auto& f : {bridge_pcap, host_pcap, script}) fs::remove(f);
  return run;
}

}  // namespace

TEST_CASE("the compose rig records what the one-host rig records", "[system][network][docker]") {
  if (!dockerReady()) return;
  const auto one_host = test::runScenario(kDefault, test::freshDir("compose-onehost"), kLength).summary;
  const int steps = one_host["steps"].get<int>();

  {  // discovery server, multicast dropped on the network
    const auto rig = runCompose("s", "FLATSAT_COMPOSE_DISCOVERY=server FLATSAT_COMPOSE_NO_MULTICAST=1");
    CHECK(test::summaryKeys(rig.summary) == test::summaryKeys(one_host));
    CHECK(rig.summary["recording_sha256"] == one_host["recording_sha256"]);
    CHECK(rig.summary["steps"] == one_host["steps"]);
    CHECK(rig.summary["processes"] == kComponents.size());
    for (const auto& component : kComponents) CHECK(rig.summary["roles"][component] == "external");
    // Every sample crossed the network between containers (several per step),
    // and no participant even tried multicast.
    CHECK(rig.bridge_rtps > 5 * steps);
    CHECK(rig.bridge_multicast == 0);
    CHECK(rig.command.output.find("multicast dropped on fsrigs") != std::string::npos);
    CHECK(rig.command.output.find(": 0 UDP datagrams") != std::string::npos);
    CHECK(rig.host_rtps == 0);
  }
  {  // multicast discovery on the compose network
    const auto rig = runCompose("m", "FLATSAT_COMPOSE_DISCOVERY=multicast");
    CHECK(rig.summary["recording_sha256"] == one_host["recording_sha256"]);
    CHECK(rig.bridge_rtps > 5 * steps);
    CHECK(rig.bridge_multicast > 0);  // SPDP announcements to 239.255.0.1
    CHECK(rig.host_rtps == 0);
  }
  // Docker's own rule for the internal network is back as it was.
  CHECK(test::runCommand("iptables -S DOCKER-USER | grep -c fsrigm").output == "0\n");
}

TEST_CASE("the compose rig refuses a bad scenario and leaves nothing running", "[system][network][docker]") {
  if (!dockerReady()) return;
  const std::string id = "b" + std::to_string(::getpid() % 100000);
  const std::string out = test::freshDir("compose-bad");
  const auto result = test::runCommand("FLATSAT_RIG_ID=" + id + " " + kRunSh + " " + kDefault + " " + out +
                                       " -q --set step_s=-1");
  INFO(result.output);
  CHECK(result.exit_code == 2);
  CHECK(result.output.find("step_s") != std::string::npos);
  CHECK(test::runCommand("docker ps -a -q --filter name=flatsat" + id + "_ | wc -l").output == "0\n");
  CHECK(test::runCommand("docker network ls -q --filter name=flatsat" + id + "_ | wc -l").output == "0\n");
  fs::remove_all(out);
}
