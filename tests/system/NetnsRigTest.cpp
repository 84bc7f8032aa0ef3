// SPDX-License-Identifier: Apache-2.0
// The rig across hosts (deploy/netns/run.sh): components in separate network
// namespaces, the bus on UDP between them, gives the one-host recording
// bit for bit, with one component started outside the launcher too, and no
// RTPS datagram reaches the host's own interfaces.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kRunSh = std::string(FLATSAT_SCENARIO_DIR) + "/../netns/run.sh";
using test::kDefault;
const std::string kShort = "--set duration_orbits=null --set duration_s=60";
const std::string& kRtps = test::kRtpsFilter;

/// True when this process may make network namespaces (root, not a
/// restricted container); says why not otherwise.
bool netnsPermitted() {
  const std::string probe = "fs-probe-" + std::to_string(::getpid());
  const auto result = test::runCommand("ip netns add " + probe + " && ip netns exec " + probe +
                                       " true; rc=$?; ip netns del " + probe + "; exit $rc");
  if (result.exit_code != 0) {
    WARN("SKIPPED: 'ip netns add' or 'ip netns exec' is not permitted here (" << result.output
                                                           << "); the namespace rig needs root");
  }
  return result.exit_code == 0;
}

std::string rigEnvironment(const std::string& id) {
  return "FLATSAT_BIN_DIR=" + std::string(FLATSAT_BIN_DIR) + " FLATSAT_RIG_ID=" + id + " ";
}

}  // namespace

TEST_CASE("the namespace rig records what the one-host rig records", "[system][network][netns]") {
  if (!netnsPermitted()) return;
  REQUIRE(test::runCommand("command -v tcpdump").exit_code == 0);
  const auto one_host = test::runScenario(kDefault, test::freshDir("netns-onehost"), kShort).summary;
  const std::string id = std::string("t").append(std::to_string(::getpid()));  // not "t" + …: GCC 12 -Wrestrict false positive

  {  // across namespaces over UDP, nothing on the host's interfaces
    const std::string out = test::freshDir("netns-rig");
    const std::string host_pcap = out + "-host.pcap", rig_pcap = out + "-rig.pcap";
    const std::string script = out + ".sh";
    std::ofstream(script) << "tcpdump -i any -n -p -U -w " << host_pcap << " '" << kRtps
                          << " and not (src net 127.0.0.0/8 and dst net 127.0.0.0/8)'"
                          << " 2>/dev/null & dump=$!\nsleep 1\n"
                          << rigEnvironment(id) << "FLATSAT_RIG_CAPTURE=" << rig_pcap << " "
                          << kRunSh << " " << kDefault << " " << out << " -q " << kShort
                          << "\nrc=$?\nsleep 1\nkill -INT $dump; wait $dump\necho rc=$rc\n";
    const auto result = test::runCommand("bash " + script);
    INFO(result.output);
    REQUIRE(result.output.find("rc=0") != std::string::npos);
    const auto rig = test::readSummary(out);
    CHECK(test::summaryKeys(rig) == test::summaryKeys(one_host));
    CHECK(rig["recording_sha256"] == one_host["recording_sha256"]);
    CHECK(rig["steps"] == one_host["steps"]);
    // The bus really crossed the bridge, between the rig's own addresses only,
    // and never showed on the host's interfaces. The sensors' samples reach
    // the estimator's data ports (odd: 7400 + 250 d + 11 + 2 p, RTPS 2.2
    // §9.6.1.1) as datagrams from .2 to .3, at least one per step.
    const int base = 7400 + 250 * static_cast<int>(test::testDomain());
    const std::string sensors_to_estimator =
        kRtps + " and src host 10.213.7.2 and dst host 10.213.7.3 and udp dst portrange " +
        std::to_string(base + 11) + "-" + std::to_string(base + 11 + 2 * 47) + " and udp[2:2] & 1 = 1";
    CHECK(test::capturedPackets(rig_pcap, sensors_to_estimator) >= one_host["steps"].get<int>());
    CHECK(test::capturedPackets(rig_pcap, kRtps + " and not (src net 10.213.7.0/24 and dst net 10.213.7.0/24)") == 0);
    CHECK(test::capturedPackets(host_pcap, "") == 0);
    CHECK(test::runCommand("ip netns list | grep -c fs-" + id + "-").output == "0\n");
    fs::remove_all(out);
    for (const auto& f : {host_pcap, rig_pcap, script}) fs::remove(f);
  }

  {  // one component external, started by hand in the rig's spare namespace
    const std::string out = test::freshDir("netns-external");
    const std::string script = out + ".sh";
    // The launcher writes OUTDIR/scenario.yaml, then makes OUTDIR/logs and
    // waits for the gyro; the gyro reads that resolved scenario.
    std::ofstream(script)
        << rigEnvironment(id) << kRunSh << " " << kDefault << " " << out << " -q " << kShort
        << " --set components.gyro.external=true & rig=$!\n"
        << "for i in $(seq 300); do [ -e /var/run/netns/fs-" << id << "-ext ] && [ -d " << out
        << "/logs ] && break; sleep 0.1; done\n"
        << "ip netns exec fs-" << id << "-ext env FLATSAT_PEERS=10.213.7.1,10.213.7.2,10.213.7.3,"
        << "10.213.7.4 " << FLATSAT_BIN_DIR << "/flatsat-gyro --scenario " << out
        << "/scenario.yaml --name gyro --out " << out << " --log warn & gyro=$!\n"
        << "wait $rig; echo rc=$?\nwait $gyro; echo gyro_rc=$?\n";
    const auto result = test::runCommand("bash " + script);
    INFO(result.output);
    REQUIRE(result.output.find("rc=0") != std::string::npos);
    CHECK(result.output.find("gyro_rc=0") != std::string::npos);
    const auto rig = test::readSummary(out);
    CHECK(rig["roles"]["gyro"] == "external");
    REQUIRE(rig["external_joined_s"].contains("gyro"));
    CHECK(rig["external_joined_s"]["gyro"].get<double>() > 0.0);
    CHECK(rig["recording_sha256"] == one_host["recording_sha256"]);
    fs::remove_all(out);
    fs::remove(script);
  }
}

TEST_CASE("the namespace rig removes its namespaces when the run fails", "[system][network][netns]") {
  if (!netnsPermitted()) return;
  test::exportTestDomain();
  const std::string id = std::string("f").append(std::to_string(::getpid()));  // not "f" + …: GCC 12 -Wrestrict false positive
  const std::string out = test::freshDir("netns-fail");
  const auto result = test::runCommand(rigEnvironment(id) + kRunSh + " " + kDefault + " " + out +
                                       " -q --set step_s=-1");
  INFO(result.output);
  CHECK(result.exit_code == 2);
  CHECK(result.output.find("step_s") != std::string::npos);
  CHECK(test::runCommand("ip netns list | grep -c fs-" + id + "-").output == "0\n");
  fs::remove_all(out);
}

TEST_CASE("bad rig settings are refused, naming the setting", "[system][network]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("netns-settings");
  const std::string run = test::kFlatsat + " run " + kDefault + " -q --no-plots --out " + out + " ";
  const auto malformed = test::runCommand("FLATSAT_PEERS=10.213.7 " + run);
  CHECK(malformed.exit_code == 1);
  CHECK(malformed.output.find("FLATSAT_PEERS='10.213.7': '10.213.7' is not an IPv4 address") !=
        std::string::npos);
  // 192.0.2.0/24 is TEST-NET-1 (RFC 5737): never an address of this host.
  const auto foreign = test::runCommand("FLATSAT_PEERS=192.0.2.1 " + run);
  CHECK(foreign.exit_code == 1);
  CHECK(foreign.output.find("none of the peers is an address of this host") != std::string::npos);
  const auto prefix = test::runCommand(run + "--prefix 'no_such=ip netns exec x'");
  CHECK(prefix.exit_code == 2);
  CHECK(prefix.output.find("--prefix no_such=ip netns exec x: no component kind 'no_such'") !=
        std::string::npos);
  fs::remove_all(out);
}
