// SPDX-License-Identifier: Apache-2.0
// What `flatsat mc --slurm` writes for sbatch and reads back from Slurm,
// checked against sbatch(1)'s forms and slurmstepd's own words.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "rig/SlurmBatch.hpp"

using namespace flatsat::rig;

namespace {

Campaign slurmTestCampaign() {
  Campaign c;
  c.dir = "/shared/camp";
  c.name = "default";
  c.runs = 12;
  c.seed0 = 100;
  c.version = "0.1.0+gabc";
  c.executable = "/opt/flat sat/bin/flatsat";
  return c;
}

bool hasLine(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

}  // namespace

TEST_CASE("a campaign's runs are split into array tasks of at most K runs, in order", "[slurm]") {
  CHECK(splitIntoTasks({0, 1, 2, 3, 4, 5, 6}, 3) == std::vector<std::vector<int>>{{0, 1, 2}, {3, 4, 5}, {6}});
  CHECK(splitIntoTasks({4, 9}, 5) == std::vector<std::vector<int>>{{4, 9}});
  CHECK(splitIntoTasks({1, 2}, 1) == std::vector<std::vector<int>>{{1}, {2}});
  CHECK(splitIntoTasks({}, 5).empty());
}

TEST_CASE("a time limit is taken in exactly sbatch's --time forms", "[slurm]") {
  for (const char* ok : {"30", "30:00", "2:00:00", "1-0", "1-12:30", "2-00:00:00", "UNLIMITED", "INFINITE"}) {
    INFO(ok);
    CHECK(validTimeLimit(ok));
  }
  for (const char* bad : {"", "1h", "1:2:3:4", "-5", "1-", "1-2:3:4:5", "unlimited", "10 "}) {
    INFO(bad);
    CHECK_FALSE(validTimeLimit(bad));
  }
}

TEST_CASE("the batch script is one job array whose tasks run flatsat mc-task on the shared directory", "[slurm]") {
  const Campaign c = slurmTestCampaign();
  const std::string script = batchScript(c, 2, 3, {.per_task = 4, .partition = "batch", .time_limit = "1:00:00"});
  CHECK(script.rfind("#!/bin/bash\n", 0) == 0);
  CHECK(hasLine(script, "#SBATCH --array=0-2"));
  CHECK(hasLine(script, "#SBATCH --job-name=flatsat-mc-default"));
  CHECK(hasLine(script, "#SBATCH --chdir=/shared/camp"));
  CHECK(hasLine(script, "#SBATCH --output=/shared/camp/slurm/submission-2/task-%a.out"));
  CHECK(hasLine(script, "#SBATCH --partition=batch"));
  CHECK(hasLine(script, "#SBATCH --time=1:00:00"));
  CHECK(hasLine(script, "exec '/opt/flat sat/bin/flatsat' mc-task '/shared/camp' --submission 2 --task "
                        "\"$SLURM_ARRAY_TASK_ID\""));
  // sbatch stops reading #SBATCH at the first command: every directive comes before exec.
  CHECK(script.rfind("#SBATCH") < script.find("\nexec "));
  const std::string plain = batchScript(c, 1, 1, {});
  CHECK(hasLine(plain, "#SBATCH --array=0-0"));
  CHECK(plain.find("--partition") == std::string::npos);
  CHECK(plain.find("--time") == std::string::npos);
  CHECK(taskOutput(c, 1, 7) == "/shared/camp/slurm/submission-1/task-7.out");
  CHECK(shellQuote("it's") == "'it'\\''s'");
  // A scenario's name is free text; the job's name on an #SBATCH line is not.
  CHECK(jobName("sun pointing: 2%") == "flatsat-mc-sun_pointing__2_");
  CHECK(jobName("s1_settling-b") == "flatsat-mc-s1_settling-b");
}

TEST_CASE("squeue's array tasks are counted as pending or running", "[slurm]") {
  const auto p = parseSqueue("12_[4-7] PENDING\n12_0 RUNNING\n12_1 COMPLETING\n12_3 REQUEUED\n");
  CHECK(p.pending == 2);
  CHECK(p.running == 2);
  const auto none = parseSqueue("");
  CHECK(none.pending + none.running == 0);
}

TEST_CASE("why an array task ended is read from slurmstepd's line in its output", "[slurm]") {
  // The lines as slurmstepd writes them (src/slurmd/slurmstepd/req.c, 22.05).
  CHECK(taskEndReason("mc-task: submission 1 task 1 on vm: 3 runs\n"
                      "slurmstepd-localhost: error: *** JOB 10 ON localhost CANCELLED AT 2026-11-28T22:42:14 ***\n") ==
        "cancelled on localhost at 2026-11-28T22:42:14");
  CHECK(taskEndReason("slurmstepd: error: *** JOB 77 ON node3 CANCELLED AT 2026-01-02T03:04:05 DUE TO TIME LIMIT ***") ==
        "ended due to time limit on node3 at 2026-01-02T03:04:05");
  CHECK(taskEndReason("slurmstepd: error: *** JOB 78 ON n1 CANCELLED AT 2026-01-02T03:04:05 DUE TO NODE FAILURE, "
                      "SEE SLURMCTLD LOG FOR DETAILS ***") == "ended due to node failure on n1 at 2026-01-02T03:04:05");
  CHECK(taskEndReason("slurmstepd: error: *** JOB 79 ON n1 CANCELLED AT 2026-01-02T03:04:05 DUE TO PREEMPTION ***") ==
        "ended due to preemption on n1 at 2026-01-02T03:04:05");
  CHECK(taskEndReason("slurmstepd: error: Detected 1 oom-kill event(s) in StepId=80.batch. Some of your processes "
                      "may have been killed by the cgroup out-of-memory handler.") ==
        "killed for running out of memory (oom-kill)");
  CHECK(taskEndReason("error: mc-task: /c was written by flatsat 0.1, but n2 runs flatsat 0.2: install the same") ==
        "error: mc-task: /c was written by flatsat 0.1, but n2 runs flatsat 0.2: install the same");
  CHECK(taskEndReason("/var/spool/slurmd/job00012/slurm_script: line 9: /opt/flatsat: No such file or directory") ==
        "/var/spool/slurmd/job00012/slurm_script: line 9: /opt/flatsat: No such file or directory");
  CHECK(taskEndReason("mc-task: run 3 ended with exit status 0\n").empty());
}

TEST_CASE("a campaign directory must be shared when the partition has other hosts", "[slurm]") {
  constexpr long kExt4 = 0xEF53, kTmpfs = 0x01021994, kNfs = 0x6969, kLustre = 0x0BD00BD0;
  CHECK(sharedDirectoryProblem("/tmp/c", kExt4, {}).empty());  // every node is this host
  CHECK(sharedDirectoryProblem("/home/c", kNfs, {"n1", "n2"}).empty());
  CHECK(sharedDirectoryProblem("/scratch/c", kLustre, {"n1"}).empty());
  const std::string problem = sharedDirectoryProblem("/tmp/c", kTmpfs, {"n1", "n2", "n3", "n4", "n5", "n6"});
  CHECK(problem.find("--out /tmp/c is on a local filesystem (type 0x1021994)") == 0);
  CHECK(problem.find("n1, n2, n3, n4 and 2 more") != std::string::npos);
  CHECK(sharedFileSystemName(kNfs) == "NFS");
  CHECK(sharedFileSystemName(kExt4).empty());
}
