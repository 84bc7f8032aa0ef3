// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "rig/Campaign.hpp"

namespace flatsat::rig {

/// What a campaign asks of Slurm for one submission (a job array).
struct SlurmJobOptions {
  int per_task = 1;        ///< runs each array task runs, one after the other; >= 1
  std::string partition;   ///< empty: the cluster's default partition
  std::string time_limit;  ///< sbatch --time; empty: the partition's default
};

/// The runs split into array tasks of at most `per_task` runs, in order.
std::vector<std::vector<int>> splitIntoTasks(const std::vector<int>& runs, int per_task);

/// Whether `limit` is one of sbatch's --time forms: M, M:S, H:M:S, D-H,
/// D-H:M, D-H:M:S, or UNLIMITED/INFINITE.
bool validTimeLimit(const std::string& limit);

/// DIR/slurm/submission-<n>.sh, .json and the folder of its tasks' output.
std::string submissionScript(const Campaign& campaign, int submission);
std::string submissionRecord(const Campaign& campaign, int submission);
std::string taskOutput(const Campaign& campaign, int submission, int task);

/// The job's name: "flatsat-mc-" and the scenario's name with anything but
/// letters, digits, '-' and '_' made '_' (it goes on an #SBATCH line).
std::string jobName(const std::string& scenario_name);

/// The batch script of a submission of `tasks` array tasks: one sbatch
/// --array job whose task i runs `flatsat mc-task DIR --submission n --task i`
/// (the runs of task i are in the submission's record). Readable, and
/// resubmittable by hand with `sbatch` alone.
std::string batchScript(const Campaign& campaign, int submission, std::size_t tasks, const SlurmJobOptions& options);

/// Array tasks by state in `squeue -h -r -o "%i %T"` output.
struct ArrayProgress {
  int pending = 0;
  int running = 0;  ///< RUNNING, COMPLETING, CONFIGURING, SUSPENDED...
};
ArrayProgress parseSqueue(const std::string& squeue_output);

/// Why an array task ended without its runs, from its Slurm output file: the
/// line slurmstepd writes when it is cancelled, times out, loses its node or
/// is preempted, else the task's own last error line; "" when neither.
std::string taskEndReason(const std::string& task_output);

/// The name of a shared (network or cluster) filesystem for statfs's f_type,
/// "" for a local one (ext4, xfs, tmpfs...).
std::string sharedFileSystemName(long f_type);

/// Why DIR cannot hold a campaign for these nodes, "" when it can: every node
/// is this host, or DIR is on a shared filesystem.
std::string sharedDirectoryProblem(const std::string& dir, long f_type, const std::vector<std::string>& remote_nodes);

/// `s` quoted for bash.
std::string shellQuote(const std::string& s);

}  // namespace flatsat::rig
