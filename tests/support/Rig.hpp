// SPDX-License-Identifier: Apache-2.0
#pragma once
// Whole-rig runs for the system tests: `flatsat run SCENARIO` on the test's own
// domain, judged on its summary.json. Needs FLATSAT_BIN_DIR and Catch2.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace flatsat::test {

inline const std::string kFlatsat = std::string(FLATSAT_BIN_DIR) + "/flatsat";
/// A hostile or broken participant (tests/support/hostile_participant.cpp).
inline const std::string kHostile = std::string(FLATSAT_BIN_DIR) + "/hostile_participant";
/// The default scenario, the one `flatsat run` runs without one named.
inline const std::string kDefault = std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml";

/// An empty temporary directory path unique to this test process and tag.
inline std::string freshDir(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("flatsat-test-" + tag + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

struct RigRun {
  CommandResult command;
  nlohmann::json summary;
};

/// The command line of a quiet run of `scenario` into `out`, no figures, with extra flags.
inline std::string runLine(const std::string& scenario, const std::string& out, const std::string& extra = "") {
  return kFlatsat + " run " + scenario + " -q --no-plots --out " + out + " " + extra;
}

/// Runs the scenario to its end into `out` with extra flags; requires success,
/// reads the summary and removes the run directory (kept when the run failed,
/// or when `keep`).
inline RigRun runScenario(const std::string& scenario, const std::string& out,
                          const std::string& extra = "", bool keep = false) {
  exportTestDomain();
  RigRun run;
  run.command = runCommand(runLine(scenario, out, extra));
  INFO(run.command.output);
  REQUIRE(run.command.exit_code == 0);
  std::ifstream(std::filesystem::path(out) / "summary.json") >> run.summary;
  if (!keep) std::filesystem::remove_all(out);
  return run;
}

/// A run directory's summary.json.
inline nlohmann::json readSummary(const std::string& out) {
  nlohmann::json summary;
  std::ifstream(std::filesystem::path(out) / "summary.json") >> summary;
  return summary;
}

/// The top-level keys of a summary.
inline std::set<std::string> summaryKeys(const nlohmann::json& summary) {
  std::set<std::string> names;
  for (const auto& [key, value] : summary.items()) names.insert(key);
  return names;
}

/// Datagrams in a capture file that match a tcpdump filter ("" for all).
inline int capturedPackets(const std::string& pcap, const std::string& filter) {
  const auto r = runCommand("tcpdump -r " + pcap + " -n " + (filter.empty() ? "" : "'" + filter + "'") +
                            " 2>/dev/null | wc -l");
  return std::stoi(r.output);
}

/// One topic of `flatsat export --json` into `dir`: a JSON object per line.
inline std::vector<nlohmann::json> exportedRows(const std::filesystem::path& dir, const std::string& topic) {
  std::vector<nlohmann::json> rows;
  std::ifstream in(dir / (topic + ".jsonl"));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) rows.push_back(nlohmann::json::parse(line));
  }
  return rows;
}

/// RTPS datagrams start with the magic "RTPS" right after the UDP header.
inline const std::string kRtpsFilter = "udp and udp[8:4] = 0x52545053";

/// kRtpsFilter for the test's own domains, d and d + 1 (testDomain()): every port an RTPS
/// participant of domain d sends to or from, multicast and unicast, lies in
/// 7400 + 250 d + [0, 250) (RTPS 2.2 §9.6.1.1). A capture on every interface then does
/// not count the rig of another test running beside it on its own Docker or namespace network.
inline std::string rtpsFilterOfTestDomain() {
  const std::uint32_t first = 7400 + 250 * testDomain();
  // A domain owns 250 ports (RTPS 9.6.1.1: PB 7400, DG 250); the next one is another test's.
  return kRtpsFilter + " and portrange " + std::to_string(first) + "-" + std::to_string(first + 249);
}

}  // namespace flatsat::test
