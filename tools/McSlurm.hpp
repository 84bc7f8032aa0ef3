// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "analysis/McTable.hpp"
#include "rig/Campaign.hpp"
#include "rig/SlurmBatch.hpp"

namespace flatsat::tools {

/// One sbatch of a campaign: a job array whose task i runs tasks[i].
struct Submission {
  int number = 0;
  std::string job_id;
  std::vector<std::vector<int>> tasks;
};

/// What stops `runs` runs of a campaign in `dir` from being submitted with
/// `options` from this host, found before anything is submitted: Slurm's
/// commands missing from PATH, an unknown partition, a bad time limit, more
/// array tasks than the cluster's MaxArraySize, a directory the partition's
/// nodes cannot see. Empty when none.
std::vector<std::string> slurmProblems(const std::string& dir, std::size_t runs, const rig::SlurmJobOptions& options);

/// Writes the next submission's script and record and submits it with
/// sbatch; throws std::runtime_error with sbatch's own words when refused.
Submission submitRuns(const rig::Campaign& campaign, const std::vector<int>& runs,
                      const rig::SlurmJobOptions& options);

/// The campaign's submissions, oldest first (a local campaign has none).
std::vector<Submission> submissions(const rig::Campaign& campaign);

/// Whether squeue still lists tasks of the job queued or running; nothing
/// when the controller did not answer (the job may well be running).
std::optional<bool> jobActive(const std::string& job_id);

/// Follows the job until none of its tasks is queued or running, with a
/// progress line on stderr; false when interrupted (the job carries on) or
/// when the controller stayed unreachable.
bool followJob(const rig::Campaign& campaign, const Submission& submission);

/// Adds to each failed run the reason its array task gave (cancelled, time
/// limit, node failure, the task's own error), from the newest submission
/// that ran it.
void explainSlurmFailures(const rig::Campaign& campaign, std::vector<analysis::McRun>& runs);

/// `flatsat mc-task DIR --submission N --task I`: what array task I runs on
/// its node: its runs one after the other, each status recorded in DIR.
/// Exit status 0 when every run succeeded, 1 when one failed, 2 when the
/// campaign cannot be read or was written by another flatsat.
int runArrayTask(const std::string& dir, int submission, int task, const std::string& version);

}  // namespace flatsat::tools
