// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/McTable.hpp"

namespace flatsat::rig {

/// A Monte Carlo campaign's directory: the one place every run of it reads
/// from and writes to, whether the runs are this host's children or a
/// cluster's array tasks (it must then be shared with the nodes).
///   DIR/campaign.json         what to run (this struct)
///   DIR/scenario.yaml         the scenario with the campaign's --sets, resolved
///   DIR/run-<i>/              run i's own run directory
///   DIR/run-<i>/run_status.json  how run i ended, written by whoever ran it
///   DIR/run-<i>.log           run i's output (kept when it failed)
///   DIR/cost/<runner>.json    CPU each runner spent (for the overhead figure)
struct Campaign {
  std::string dir;         ///< absolute
  std::string scenario;    ///< the scenario file the campaign was made from
  std::string name;        ///< the scenario's name
  int runs = 0;            ///< run i has seed seed0 + i
  std::uint64_t seed0 = 0;
  std::string version;     ///< the flatsat that wrote it: runs by another are refused
  std::string executable;  ///< that flatsat, absolute; the nodes must have it at the same path
};

/// Writes DIR/campaign.json (atomically: a node never reads half of it).
void writeCampaign(const Campaign& campaign);
/// Reads DIR/campaign.json; throws std::runtime_error naming the file and the
/// key when it cannot.
Campaign readCampaign(const std::string& dir);

std::string runDirectory(const Campaign& campaign, int index);
std::string runLog(const Campaign& campaign, int index);
std::uint64_t runSeed(const Campaign& campaign, int index);

/// The command line of run `index`, the same wherever it runs: this
/// campaign's flatsat on its resolved scenario, composed, with the run's seed.
std::vector<std::string> runArguments(const Campaign& campaign, int index);

/// How one run ended, measured by the process that waited for it.
struct RunStatus {
  int exit_code = -1;  ///< 128 + signal when killed
  double wall_s = 0;
  double cpu_s = 0;    ///< user + system of the run's process
  std::string host;
  std::string unrecorded;  ///< why run_status.json could not be written (empty when it was)
};

/// Removes what an earlier attempt at run `index` left, so it starts afresh.
void clearRun(const Campaign& campaign, int index);

/// A run under way.
struct StartedRun {
  int index = 0;
  pid_t pid = -1;
  std::chrono::steady_clock::time_point started;
};
/// Starts run `index` with its output to runLog(); throws std::runtime_error.
StartedRun startRun(const Campaign& campaign, int index);
/// Waits for one of `running` to end, writes its run_status.json, takes it
/// out of `running` and returns it with how it ended; std::nullopt when a
/// signal interrupted the wait (or no child is left).
std::optional<std::pair<int, RunStatus>> waitForRun(const Campaign& campaign, std::vector<StartedRun>& running);

std::optional<RunStatus> readRunStatus(const Campaign& campaign, int index);

/// Run `index` as it stands: its exit status and summary when it ended, its
/// log kept when it failed, `failure` empty when it succeeded.
analysis::McRun gatherRun(const Campaign& campaign, int index);
/// The runs with no successful end recorded, in index order.
std::vector<int> unfinishedRuns(const Campaign& campaign);

/// Records the CPU a runner (this process and the children it waited for)
/// spent, as DIR/cost/<runner>.json.
void writeRunnerCost(const Campaign& campaign, const std::string& runner, double wall_s);
/// The campaign's cost so far: the runs' own CPU (their run_status.json), the
/// runners' (DIR/cost), the fraction the runners add and runs per CPU-second.
nlohmann::ordered_json campaignCost(const Campaign& campaign, const std::vector<analysis::McRun>& runs);

/// This host's name (what Slurm's tasks and statuses report).
std::string hostName();

}  // namespace flatsat::rig
