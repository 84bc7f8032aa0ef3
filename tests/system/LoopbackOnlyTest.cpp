// SPDX-License-Identifier: Apache-2.0
// The default participant profile keeps DDS on the machine: a packet
// capture on every interface during a run sees no RTPS datagram of the run's
// domain that is not loopback-to-loopback, and no multicast at all, while a
// capture on loopback alone sees the rig's RTPS traffic (the capture ran).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

TEST_CASE("no RTPS datagram leaves loopback during a run", "[system][network]") {
  REQUIRE(::geteuid() == 0);  // packet capture needs root (CI and rig.sh run as root)
  REQUIRE(test::runCommand("command -v tcpdump").exit_code == 0);
  test::exportTestDomain();
  const std::string tag = std::to_string(::getpid());
  const std::string pcap = (fs::temp_directory_path() / ("flatsat-loopback-" + tag + ".pcap")).string();
  const std::string out = (fs::temp_directory_path() / ("flatsat-loopback-" + tag)).string();
  fs::remove_all(out);
  // Only this test's domains: a Docker or network-namespace rig of another test running
  // beside this one talks RTPS on its own network, on its own domain.
  const std::string filter =
      test::rtpsFilterOfTestDomain() + " and not (src net 127.0.0.0/8 and dst net 127.0.0.0/8)";
  // The control: the same capture on loopback alone sees the rig's own RTPS
  // traffic (discovery goes over UDP even with shared memory), so a capture
  // that never ran cannot pass for a clean one.
  const std::string loopback_pcap = pcap + ".lo";
  const std::string script = out + ".sh";
  std::ofstream(script) << "tcpdump -i any -n -p -U -w " << pcap << " '" << filter
                        << "' 2>/dev/null & dump=$!\n"
                        << "tcpdump -i lo -n -p -U -w " << loopback_pcap << " '" << test::kRtpsFilter
                        << "' 2>/dev/null & dump_lo=$!\nsleep 1\n"
                        << FLATSAT_BIN_DIR << "/flatsat run " << FLATSAT_SCENARIO_DIR
                        << "/default.yaml -q --out " << out
                        << " --set duration_orbits=null --set duration_s=60\nrc=$?\nsleep 1\n"
                        << "kill -INT $dump $dump_lo; wait $dump $dump_lo\necho rc=$rc\n";
  const auto result = test::runCommand("bash " + script);
  INFO(result.output);
  CHECK(result.output.find("rc=0") != std::string::npos);
  REQUIRE(fs::exists(pcap));
  REQUIRE(fs::exists(loopback_pcap));
  CHECK(test::capturedPackets(pcap, "") == 0);
  CHECK(test::capturedPackets(loopback_pcap, "") > 0);
  fs::remove(loopback_pcap);
  fs::remove(pcap);
  fs::remove(script);
}
