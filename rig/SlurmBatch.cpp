// SPDX-License-Identifier: Apache-2.0
#include "rig/SlurmBatch.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <utility>

namespace flatsat::rig {

namespace fs = std::filesystem;

std::vector<std::vector<int>> splitIntoTasks(const std::vector<int>& runs, int per_task) {
  std::vector<std::vector<int>> tasks;
  const auto k = static_cast<std::size_t>(std::max(1, per_task));
  for (std::size_t i = 0; i < runs.size(); i += k) {
    tasks.emplace_back(runs.begin() + static_cast<std::ptrdiff_t>(i),
                       runs.begin() + static_cast<std::ptrdiff_t>(std::min(runs.size(), i + k)));
  }
  return tasks;
}

bool validTimeLimit(const std::string& limit) {
  // sbatch(1), --time: "minutes", "minutes:seconds", "hours:minutes:seconds",
  // "days-hours", "days-hours:minutes" and "days-hours:minutes:seconds".
  static const std::regex forms(R"(\d+|\d+:\d+|\d+:\d+:\d+|\d+-\d+|\d+-\d+:\d+|\d+-\d+:\d+:\d+|UNLIMITED|INFINITE)");
  return std::regex_match(limit, forms);
}

std::string submissionScript(const Campaign& c, int submission) {
  return (fs::path(c.dir) / "slurm" / ("submission-" + std::to_string(submission) + ".sh")).string();
}
std::string submissionRecord(const Campaign& c, int submission) {
  return (fs::path(c.dir) / "slurm" / ("submission-" + std::to_string(submission) + ".json")).string();
}
std::string taskOutput(const Campaign& c, int submission, int task) {
  return (fs::path(c.dir) / "slurm" / ("submission-" + std::to_string(submission)) /
          ("task-" + std::to_string(task) + ".out"))
      .string();
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

std::string jobName(const std::string& scenario_name) {
  std::string name = "flatsat-mc-";
  for (const char ch : scenario_name) {
    name += std::isalnum(static_cast<unsigned char>(ch)) != 0 || ch == '-' || ch == '_' ? ch : '_';
  }
  return name;
}

std::string batchScript(const Campaign& c, int submission, std::size_t tasks, const SlurmJobOptions& o) {
  const std::string outputs = (fs::path(c.dir) / "slurm" / ("submission-" + std::to_string(submission))).string();
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# flatsat mc: campaign " << jobName(c.name) << " in " << c.dir << ", submission " << submission << ":\n"
    << "# " << tasks << " array tasks of at most " << o.per_task << " runs each (their runs: "
    << fs::path(submissionRecord(c, submission)).filename().string() << ").\n"
    << "# Written by flatsat " << c.version << "; every node needs it at " << c.executable << "\n"
    << "# and this directory at the same path. Resubmit by hand with: sbatch " << submissionScript(c, submission)
    << "\n"
    << "#SBATCH --job-name=" << jobName(c.name) << "\n"
    << "#SBATCH --array=0-" << (tasks == 0 ? 0 : tasks - 1) << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=1\n"
    << "#SBATCH --chdir=" << c.dir << "\n"
    << "#SBATCH --output=" << outputs << "/task-%a.out\n";
  if (!o.partition.empty()) s << "#SBATCH --partition=" << o.partition << "\n";
  if (!o.time_limit.empty()) s << "#SBATCH --time=" << o.time_limit << "\n";
  s << "exec " << shellQuote(c.executable) << " mc-task " << shellQuote(c.dir) << " --submission " << submission
    << " --task \"$SLURM_ARRAY_TASK_ID\"\n";
  return s.str();
}

ArrayProgress parseSqueue(const std::string& text) {
  ArrayProgress p;
  std::istringstream lines(text);
  std::string id, state;
  while (lines >> id >> state) {
    if (state == "PENDING" || state == "REQUEUED" || state == "REQUEUE_HOLD" || state == "REQUEUE_FED") {
      ++p.pending;
    } else {
      ++p.running;
    }
  }
  return p;
}

std::string taskEndReason(const std::string& output) {
  // slurmstepd (src/slurmd/slurmstepd/req.c): "*** JOB 12 ON node1 CANCELLED AT
  // 2026-11-28T22:17:40 ***", or "... DUE TO TIME LIMIT ***", "DUE TO PREEMPTION",
  // "DUE TO NODE FAILURE, SEE SLURMCTLD LOG FOR DETAILS", "DUE TO JOB REQUEUE".
  static const std::regex stepd(R"(\*\*\* (JOB|STEP) [0-9_.]+ ON (\S+) CANCELLED AT (\S+)( DUE TO ([A-Z ]+?))?(,[^*]*)?( BY [^*]+)? \*\*\*)");
  std::string reason;
  for (auto it = std::sregex_iterator(output.begin(), output.end(), stepd); it != std::sregex_iterator(); ++it) {
    const auto& hit = *it;
    std::string why = hit[5].matched ? hit[5].str() : "CANCELLED";
    for (auto& ch : why) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    reason = (hit[5].matched ? "ended due to " + why : "cancelled") + " on " + hit[2].str() + " at " + hit[3].str();
  }
  if (!reason.empty()) return reason;
  // slurmstepd: "Detected 1 oom-kill event(s) in StepId=12.batch..."
  if (output.find("oom-kill event") != std::string::npos) return "killed for running out of memory (oom-kill)";
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("error: ", 0) == 0 || line.find(": command not found") != std::string::npos ||
        line.find("No such file or directory") != std::string::npos) {
      reason = line;
    }
  }
  return reason;
}

std::string sharedFileSystemName(long f_type) {
  static const std::pair<unsigned long, const char*> shared[] = {
      {0x6969, "NFS"},         {0x517B, "SMB"},        {0xFF534D42, "CIFS"},   {0xFE534D42, "SMB2"},
      {0x00C36400, "CephFS"},  {0x0BD00BD0, "Lustre"}, {0x47504653, "GPFS"},   {0x19830326, "BeeGFS"},
      {0x01161970, "GFS2"},    {0x7461636F, "OCFS2"},  {0x5346414F, "AFS"},    {0x6B414653, "AFS"},
      {0x01021997, "9p"},      {0xAAD7AAEA, "PanFS"},  {0x20030528, "OrangeFS"}, {0x65735546, "FUSE"}};
  for (const auto& [magic, name] : shared) {
    if (static_cast<unsigned long>(f_type) == magic) return name;
  }
  return "";
}

std::string sharedDirectoryProblem(const std::string& dir, long f_type, const std::vector<std::string>& remote) {
  if (remote.empty() || !sharedFileSystemName(f_type).empty()) return "";
  std::string nodes;
  for (std::size_t i = 0; i < remote.size() && i < 4; ++i) nodes += (i ? ", " : "") + remote[i];
  if (remote.size() > 4) nodes += " and " + std::to_string(remote.size() - 4) + " more";
  char type[16];
  std::snprintf(type, sizeof type, "0x%lx", static_cast<unsigned long>(f_type));
  return "--out " + dir + " is on a local filesystem (type " + type + ") but the partition's nodes " + nodes +
         " are other hosts: their tasks would not see it; put --out on a filesystem the nodes share "
         "(NFS, Lustre, GPFS, BeeGFS, CephFS...)";
}

}  // namespace flatsat::rig
