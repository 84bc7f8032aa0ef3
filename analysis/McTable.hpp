// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace flatsat::analysis {

/// One Monte Carlo run as `flatsat mc` saw it end.
struct McRun {
  int index = 0;
  std::uint64_t seed = 0;
  int exit_code = -1;        ///< the run's exit status (128 + signal when killed); -1: it never ended
  std::string failure;       ///< why it has no result, in words; empty when it succeeded
  std::string log;           ///< its stdout and stderr (kept when it failed)
  nlohmann::ordered_json summary;  ///< its summary.json; null when it failed
};

/// Statistics of one summary key over the successful runs. std is the sample
/// standard deviation (n - 1; 0 for one run); p50 and p95 are nearest-rank
/// quantiles (the smallest value with at least that fraction at or below it).
struct McStats {
  std::size_t count = 0;
  double mean = 0, std = 0, min = 0, max = 0, p50 = 0, p95 = 0;
};

McStats mcStats(std::vector<double> values);

/// The numeric scalar keys of the successful runs' summaries, in the order
/// they first appear (booleans, strings, arrays and objects are left out).
std::vector<std::string> mcNumericKeys(const std::vector<McRun>& runs);

/// mc.csv: a header, then one row per run in index order: run, seed,
/// exit_code (empty when the run never ended), recording_sha256, then every
/// numeric key (empty when the run failed or did not report the key). Numbers keep their full precision.
std::string mcCsv(const std::vector<McRun>& runs, const std::vector<std::string>& keys);

/// mc_summary.json: the runs' counts, the failed runs (seed, exit code or
/// null, the reason, log)
/// and per numeric key the McStats over the successful runs.
nlohmann::ordered_json mcSummary(const std::string& scenario, const std::vector<McRun>& runs,
                                 const std::vector<std::string>& keys);

/// A short table of mc_summary.json's statistics for the terminal.
std::string mcTable(const nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
