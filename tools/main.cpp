// SPDX-License-Identifier: Apache-2.0
// flatsat: run, check and benchmark rig scenarios.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "bus/InstallPaths.hpp"
#include "bus/NearestName.hpp"
#include "bus/ScenarioPlaces.hpp"
#include "bus/Security.hpp"
#include "bus/Shutdown.hpp"
#include "components/Registry.hpp"
#include "tools/CmdCommand.hpp"
#include "rig/ComposedRun.hpp"
#include "analysis/Conventions.hpp"
#include "analysis/RunFigures.hpp"
#include "tools/EchoCommand.hpp"
#include "tools/ExportCommand.hpp"
#include "tools/FieldCommand.hpp"
#include "tools/FoxgloveCommand.hpp"
#include "tools/GrantsCommand.hpp"
#include "rig/Fleet.hpp"
#include "tools/HealthCommand.hpp"
#include "tools/HzCommand.hpp"
#include "tools/InfoCommand.hpp"
#include "rig/Launcher.hpp"
#include "tools/McCommand.hpp"
#include "tools/MiddlewareBench.hpp"
#include "tools/PlainGraphBench.hpp"
#include "tools/OrbitCommand.hpp"
#include "tools/ParamCommand.hpp"
#include "tools/PhysicsBench.hpp"
#include "tools/PlotCommand.hpp"
#include "analysis/Quantile.hpp"
#include "tools/RecordCommand.hpp"
#include "tools/ScenarioName.hpp"
#include "tools/ScenariosCommand.hpp"
#include "tools/ReplayCommand.hpp"
#include "rig/Resume.hpp"
#include "rig/RunDirectory.hpp"
#include "rig/ShmClean.hpp"
#include "tools/SoakCommand.hpp"
#include "tools/StudyCommand.hpp"
#include "analysis/Summary.hpp"
#include "tools/TopicsCommand.hpp"
#include "tools/TypesCommand.hpp"
#include "flatsat_version.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

constexpr int kExitFailed = 1;
using analysis::kExitBadInput;

/// Where a resolved scenario came from: its file and the --set overrides laid over it.
struct ScenarioOrigin {
  std::string file;
  std::vector<std::string> overrides;
};

/// Loads a scenario and checks every component's parameters; prints every
/// problem and returns false when there is any. A scenario resolved from
/// `origin` has its problems told at the user's file or --set argument.
bool loadChecked(const std::string& file, const std::string& out_dir, bus::Scenario& scenario,
                 const ScenarioOrigin* origin = nullptr) {
  auto told = [&](const std::string& problem) {
    return origin ? rig::attributeProblem(problem, file, origin->file, origin->overrides) : problem;
  };
  const std::string header = (origin ? origin->file : file) + ": invalid scenario:";
  try {
    scenario = bus::loadScenario(file);
  } catch (const bus::ScenarioError& e) {
    // One problem a line after a header line, or a single-line error.
    std::istringstream lines(e.what());
    std::string line;
    std::getline(lines, line);
    if (lines.eof()) {
      std::cerr << "error: " << told(line) << "\n";
      return false;
    }
    std::cerr << "error: " << header << "\n";
    while (std::getline(lines, line)) {
      if (const auto text = line.find_first_not_of(' '); text != std::string::npos) {
        std::cerr << "  " << told(line.substr(text)) << "\n";
      }
    }
    return false;
  }
  const auto problems = checkScenario(scenario, out_dir.empty() ? "." : out_dir);
  if (problems.empty()) return true;
  std::cerr << "error: " << header << "\n";
  for (const auto& p : problems) {
    std::cerr << "  " << (origin ? told(p) : bus::placeProblem(p, scenario.file, scenario.files)) << "\n";
  }
  return false;
}

/// Parses the command line. --help and --version print theirs (exit 0); a
/// command-line error prints the error and the usage of the command it was
/// for and gives exit status 2, as every Unix tool does (not CLI11's 106..109).
std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (!first.empty() && first[0] != '-' &&
      app.get_subcommands([&](CLI::App* s) { return s->check_name(first); }).empty()) {
    std::string commands;
    std::vector<std::string> names;
    for (const auto* sub : app.get_subcommands([](CLI::App* s) { return !s->get_group().empty(); })) {
      commands += (commands.empty() ? "" : ", ") + sub->get_name();
      names.push_back(sub->get_name());
    }
    std::cerr << "error: unknown command '" << argv[1] << "'" << bus::didYouMean(first, names)
              << "; the commands: " << commands
              << "\nRun 'flatsat --help' for what each does.\n";
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const CLI::App* command = &app;
    std::string name = "flatsat";
    while (!command->get_subcommands().empty()) {
      command = command->get_subcommands().front();
      name += " " + command->get_name();
    }
    std::cerr << "error: " << e.what() << "\n"
              << CLI::Formatter().make_usage(command, name) << "Run '" << name << " --help' for more.\n";
    return kExitBadInput;
  }
}

struct RunOptions {
  std::string scenario;
  std::string out;
  std::vector<std::string> overrides;
  std::optional<std::uint64_t> seed;  // --seed: replaces the scenario's seed (dispersed initial conditions, noise)
  std::string log_level = "info";
  std::vector<std::string> prefixes;  // --prefix COMPONENT=COMMAND
  std::vector<std::string> externals;  // --external COMPONENT|*: not started here, awaited on the bus
  std::string secure;                 // --secure DIR: DDS Security with deploy/security/make-certs.sh's files
  bool quiet = false;
  bool json = false;
  bool plots = true;  // the review figures into <run>/plots (flatsat plot)
  bool composed = false;  // every component in this process, in-process bus (rig/ComposedRun.hpp)
  std::string resume;     // --resume DIR: a killed lockstep run goes on (rig/Resume.hpp)
  bool restart = false;   // --restart: paced, a component that dies is started again
  int max_restarts = 20;  // --max-restarts
};

/// `--prefix COMPONENT=COMMAND` into component -> argv words. `*` stands
/// for every component without a prefix of its own; a placement table may
/// name components this scenario does not start (absent or external).
bool parsePrefixes(const std::vector<std::string>& options, const bus::Scenario& scenario,
                   std::map<std::string, std::vector<std::string>>& prefixes) {
  std::map<std::string, std::vector<std::string>> given;
  for (const auto& option : options) {
    const auto equals = option.find('=');
    const std::string name = option.substr(0, equals);
    std::istringstream words(equals == std::string::npos ? "" : option.substr(equals + 1));
    std::vector<std::string> argv{std::istream_iterator<std::string>(words), {}};
    std::string problem;
    if (argv.empty()) problem = "expected COMPONENT=COMMAND with a command";
    else if (name != "*" && findComponentKind(name) == nullptr) problem = "no component kind '" + name + "'";
    if (!problem.empty()) {
      std::cerr << "error: --prefix " << option << ": " << problem << "\n";
      return false;
    }
    given[name] = argv;
  }
  for (const auto& c : scenario.components) {
    if (!c.launched) continue;
    if (auto it = given.find(c.name); it != given.end()) prefixes[c.name] = it->second;
    else if (auto all = given.find("*"); all != given.end()) prefixes[c.name] = all->second;
  }
  return true;
}

/// --secure DIR: every component and the launcher must find their certificate,
/// key and grant there; the children inherit FLATSAT_SECURE_DIR.
bool enableSecurity(const std::string& dir, const bus::Scenario& scenario) {
  const std::string absolute = fs::absolute(dir).string();
  try {
    eprosima::fastdds::dds::DomainParticipantQos scratch;
    bus::addSecurity(scratch, absolute, bus::kOperatorIdentity);
    for (const auto& component : scenario.components) {
      if (component.launched) bus::addSecurity(scratch, absolute, component.name);
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: --secure " << dir << ": " << e.what() << "\n";
    return false;
  }
  ::setenv("FLATSAT_SECURE_DIR", absolute.c_str(), 1);
  return true;
}

/// --resume DIR: DIR's own scenario, its recording readied (rig/Resume.hpp), its
/// earlier logs kept aside. False (after saying why) when it cannot be resumed.
bool prepareResumedRun(const RunOptions& o, const bus::Scenario& original, bus::Scenario& scenario) {
  if (!o.out.empty() && fs::path(o.out) != fs::path(o.resume)) {
    std::cerr << "error: --resume " << o.resume << ": the run goes on in that directory; drop --out\n";
    return false;
  }
  if (!o.overrides.empty() || o.seed || !o.externals.empty()) {
    std::cerr << "error: --resume " << o.resume << ": the run keeps its own " << o.resume
              << "/scenario.yaml; --set, --seed and --external do not apply\n";
    return false;
  }
  const std::string resolved = (fs::path(o.resume) / "scenario.yaml").string();
  if (!fs::exists(resolved)) {
    std::cerr << "error: --resume " << o.resume << ": no scenario.yaml: not a run directory\n";
    return false;
  }
  if (!loadChecked(resolved, o.resume, scenario)) return false;
  if (scenario.name != original.name) {
    std::cerr << "error: --resume " << o.resume << ": it holds a run of '" << scenario.name << "', not of '"
              << original.name << "' (" << o.scenario << ")\n";
    return false;
  }
  const std::string recording = (fs::path(o.resume) / "recording.sqlite").string();
  try {
    const auto after = rig::prepareResume(scenario, recording);
    if (!after) {
      fs::remove(recording);
      fs::remove(recording + "-wal");
      fs::remove(recording + "-shm");
    }
    if (!o.quiet) {
      std::cerr << "flatsat: resuming '" << scenario.name << "' in " << o.resume << ": "
                << (after ? "steps 0.." + std::to_string(*after) + " are recorded; the rig computes them again, "
                                                                    "checked against the recording, then goes on"
                          : std::string("no complete step recorded; starting from step 0"))
                << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "error: --resume " << o.resume << ": " << e.what() << "\n";
    return false;
  }
  const fs::path logs = fs::path(o.resume) / "logs";
  if (fs::exists(logs)) {
    fs::path kept = fs::path(o.resume) / "logs-before-resume";
    for (int n = 2; fs::exists(kept); ++n) kept = fs::path(o.resume) / ("logs-before-resume-" + std::to_string(n));
    fs::rename(logs, kept);
  }
  return true;
}

/// The summary of a run that failed: what its recording shows, where it
/// can still be read, with `completed: false` and the launcher's reason.
nlohmann::ordered_json writeFailedSummary(const bus::Scenario& scenario, const std::string& run_dir,
                                          const rig::LaunchResult& result) {
  nlohmann::ordered_json summary;
  try {
    summary = scenario.spacecraft_count > 1
                  ? rig::fleetSummary(scenario, run_dir, result)
                  : analysis::summarize(scenario, (fs::path(run_dir) / "recording.sqlite").string(), result);
  } catch (const std::exception& e) {
    summary["scenario"] = scenario.name;
    summary["summary_error"] = e.what();
  }
  summary["completed"] = false;
  summary["end_reason"] = result.failure;
  std::ofstream(fs::path(run_dir) / "summary.json") << summary.dump(2) << "\n";
  return summary;
}

/// Exit status of a run stopped by Ctrl-C or SIGTERM, as shells report a
/// process killed by SIGINT (128 + 2).
constexpr int kExitInterrupted = 130;

/// What an interrupted run tells: the step its recording reached, and how it goes on.
void sayInterrupted(const RunOptions& o, const bus::Scenario& scenario, const std::string& run_dir,
                    const nlohmann::ordered_json& summary) {
  const auto steps = summary.value("steps", std::uint64_t{0});
  std::cerr << "flatsat: interrupted; the recording holds steps 0.." << (steps > 0 ? steps - 1 : 0) << " ("
            << summary.value("sim_seconds", 0.0) << " s simulated), summary.json says completed: false\n";
  if (scenario.pacing == bus::Pacing::kLockstep && scenario.spacecraft_count == 1) {
    std::cerr << "flatsat: to go on from there: flatsat run " << o.scenario << " --resume " << run_dir
              << (o.composed ? " --composed" : "") << "\n";
  } else {
    std::cerr << "flatsat: a paced run (or a fleet) cannot be resumed: run it again\n";
  }
}

int run(const RunOptions& o, nlohmann::ordered_json* summary_out = nullptr) {
  bus::Scenario original;
  if (!loadChecked(o.scenario, o.out, original)) return kExitBadInput;
  const std::string run_dir = !o.resume.empty() ? o.resume
                              : o.out.empty()   ? rig::defaultRunDirectory(original.name)
                                                : o.out;
  bus::Scenario scenario;
  if (!o.resume.empty()) {
    if (!prepareResumedRun(o, original, scenario)) return kExitBadInput;
  } else if (fs::exists(fs::path(run_dir) / "recording.sqlite") || fs::exists(fs::path(run_dir) / "spacecraft-0")) {
    std::cerr << "error: " << run_dir << " already holds a recording; choose another --out\n";
    return kExitBadInput;
  }
  if (o.composed && !o.prefixes.empty()) {
    std::cerr << "error: --prefix: a composed run starts no processes to prefix\n";
    return kExitBadInput;
  }
  const bool new_run_dir = !fs::exists(run_dir);
  if (o.resume.empty()) try {
    auto overrides = o.overrides;
    if (o.seed) overrides.push_back("seed=" + std::to_string(*o.seed));
    for (const auto& name : o.externals) {
      bool found = false;
      for (const auto& c : original.components) {
        if (name != "*" && name != c.name) continue;
        overrides.push_back("components." + c.name + ".external=true");
        found = true;
      }
      if (!found) {
        std::cerr << "error: --external " << name << ": " << o.scenario << " has no component '" << name << "'\n";
        return kExitBadInput;
      }
    }
    const std::string resolved = rig::writeRunScenario(o.scenario, run_dir, overrides);
    const ScenarioOrigin origin{o.scenario, overrides};
    if (!loadChecked(resolved, run_dir, scenario, &origin)) {
      if (new_run_dir) fs::remove_all(run_dir);  // a run that never started leaves no folder
      return kExitBadInput;
    }
    for (const auto& caution : scenarioCautions(scenario)) spdlog::warn("{}", caution);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (new_run_dir) fs::remove_all(run_dir);
    return kExitBadInput;
  }
  if (const auto problems = o.composed ? rig::composedProblems(scenario) : std::vector<std::string>{};
      !problems.empty()) {
    std::cerr << "error: " << o.scenario << ": cannot run composed (--composed):\n";
    for (const auto& p : problems) std::cerr << "  " << o.scenario << ": " << p << "\n";
    if (new_run_dir) fs::remove_all(run_dir);
    return kExitBadInput;
  }
  if (scenario.spacecraft_count > 1 &&
      (!o.resume.empty() || o.restart || !o.externals.empty() || !o.prefixes.empty() || !o.secure.empty())) {
    std::cerr << "error: " << o.scenario << ": spacecraft_count " << scenario.spacecraft_count
              << ": --resume, --restart, --external, --prefix and --secure take a run of one spacecraft\n";
    if (new_run_dir) fs::remove_all(run_dir);
    return kExitBadInput;
  }
  const std::string bin_dir = fs::canonical("/proc/self/exe").parent_path().string();
  rig::LaunchOptions launch_options{bin_dir, run_dir, fs::absolute(scenario.file).string(),
                                      o.log_level, !o.quiet};
  if (!parsePrefixes(o.prefixes, scenario, launch_options.prefixes)) return kExitBadInput;
  if (o.restart && (scenario.pacing != bus::Pacing::kPaced || o.composed)) {
    std::cerr << "error: --restart: only a paced multi-process run starts a dead component again "
                 "(a lockstep run stops; continue it with --resume)\n";
    return kExitBadInput;
  }
  launch_options.restart = o.restart;
  launch_options.max_restarts = o.max_restarts;
  if (!o.secure.empty() && !enableSecurity(o.secure, scenario)) return kExitBadInput;
  if (o.composed && !o.quiet) {
    std::cerr << "flatsat: running '" << scenario.name << "' composed (" << scenario.components.size()
              << " components in this process, no DDS) into " << run_dir << "\n";
  } else if (!o.composed) {
    // Segments left by processes killed in an earlier run go first.
    rig::cleanStaleSharedMemory(rig::kShmGrace);
    if (!o.quiet) {
      std::cerr << "flatsat: running '" << scenario.name << "' (" << scenario.components.size()
                << " processes, domain " << bus::domainFromEnvironment(scenario.domain_id)
                << ") into " << run_dir << "\n";
    }
  }
  rig::LaunchResult result;
  try {
    result = o.composed                      ? rig::runComposed(scenario, launch_options)
             : scenario.spacecraft_count > 1 ? rig::launchFleet(scenario, launch_options)
                                             : rig::launch(scenario, launch_options);
  } catch (const std::exception& e) {  // the launcher's own participant (FLATSAT_PEERS, ...)
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailed;
  }
  // Segments of processes killed mid-run and restarted (--restart) go now; those
  // of processes killed just now stay for kShmGrace: the next start or
  // `flatsat clean-shm` removes them.
  if (!o.composed) rig::cleanStaleSharedMemory(rig::kShmGrace);
  if (!result.ok) {
    const auto summary = writeFailedSummary(scenario, run_dir, result);
    if (bus::shutdownRequested()) {  // the operator's stop: said as such, not as an error
      sayInterrupted(o, scenario, run_dir, summary);
      return kExitInterrupted;
    }
    std::cerr << "error: " << result.failure << "\n";
    return kExitFailed;
  }
  if (!o.resume.empty()) {
    try {
      if (const auto differing = rig::resumeMismatches((fs::path(run_dir) / "recording.sqlite").string());
          differing > 0) {
        std::cerr << "error: --resume: " << differing << " samples of the recorded steps came out different "
                  << "in the resumed rig (see " << run_dir << "/logs/recorder.log): the recording is not one run\n";
        return kExitFailed;
      }
    } catch (const std::exception& e) {
      std::cerr << "error: --resume: " << e.what() << "\n";
      return kExitFailed;
    }
  }
  nlohmann::ordered_json summary;
  try {
    summary = scenario.spacecraft_count > 1
                  ? rig::fleetSummary(scenario, run_dir, result)
                  : analysis::summarize(scenario, (fs::path(run_dir) / "recording.sqlite").string(), result);
  } catch (const std::exception& e) {  // the recording is kept as it is for a look
    std::cerr << "error: the run ended but its summary failed: " << e.what() << "\n";
    return kExitFailed;
  }
  std::ofstream(fs::path(run_dir) / "summary.json") << summary.dump(2) << "\n";
  // Every process exited 0, yet the recording may end early (a stop grant
  // forged by another writer ends the components that took it) or the bus
  // may have had an intruder: neither is a run to trust.
  const bool completed = summary.value("completed", false);
  const auto intruders = summary.value("intruders", std::uint64_t{0});
  if (!completed || intruders > 0) {
    std::cerr << "error: " << (completed ? "" : "the run did not complete: " + summary.value("end_reason", std::string()))
              << (completed || intruders == 0 ? "" : "; ")
              << (intruders > 0 ? std::to_string(intruders) + " intruder(s) wrote on the rig's topics (summary.json: "
                                      "intruder_writers)"
                                : "")
              << "\n";
  }
  if (o.json) {
    std::cout << summary.dump(2) << "\n";
  } else if (!o.quiet) {
    std::cout << "summary (" << (fs::path(run_dir) / "summary.json").string() << "):\n"
              << analysis::summaryTable(summary);
  }
  if (o.plots) {
    // A run that worked stays a success when only its figures fail (no gnuplot).
    const fs::path plots = fs::path(run_dir) / "plots";
    const fs::path first = rig::spacecraftDirectory(run_dir, scenario.spacecraft_count, 0);
    if (tools::plotRecording((first / "recording.sqlite").string(), plots.string(),
                             false) != 0) {
      std::cerr << "flatsat: warning: the figures were not drawn; the run itself succeeded\n";
    } else if (!o.quiet && !o.json) {
      std::cout << "figures: " << plots.string() << "\n";
    }
  }
  if (summary_out != nullptr) *summary_out = summary;
  return completed && intruders == 0 ? 0 : kExitFailed;
}

std::string defaultScenario() { return bus::installedScenario("default.yaml"); }

/// The rig paced at 100 Hz for paced_s of wall time, recorder on: how evenly
/// its ticks come (the target: p99 lateness <= 200 µs, no missed step).
int pacedBench(const std::string& scenario, double paced_s) {
  RunOptions o;
  o.scenario = scenario;
  o.out = (fs::temp_directory_path() / ("flatsat-bench-paced-" + std::to_string(::getpid()))).string();
  o.overrides = {"mode=paced", "step_s=0.01", "duration_s=" + std::to_string(paced_s), "duration_orbits=null"};
  o.quiet = true;
  o.plots = false;
  o.log_level = "warn";
  nlohmann::ordered_json summary;
  const int rc = run(o, &summary);
  if (rc != 0) return rc;
  std::printf("paced_jitter_us_p50=%.1f\n", summary["tick_jitter_us_p50"].get<double>());
  std::printf("paced_jitter_us_p99=%.1f\n", summary["tick_jitter_us_p99"].get<double>());
  std::printf("paced_jitter_us_max=%.1f\n", summary["tick_jitter_us_max"].get<double>());
  std::printf("paced_ticks_missed=%llu\n", summary["ticks_missed"].get<unsigned long long>());
  // The same ticks as the time master granted them: how late against its grid.
  std::printf("paced_tick_lateness_us_p50=%.1f\n", summary["tick_lateness_us_p50"].get<double>());
  std::printf("paced_tick_lateness_us_p99=%.1f\n", summary["tick_lateness_us_p99"].get<double>());
  std::printf("paced_tick_lateness_us_max=%.1f\n", summary["tick_lateness_us_max"].get<double>());
  fs::remove_all(o.out);
  return 0;
}

/// N = 1, 4, 16 spacecraft of the composed run `composed` side by side in
/// one process (spacecraft_count): the cost of a spacecraft-step at each N,
/// and how it grew from N = 1 (the target: at most linearly, so <= 1).
int fleetBench(RunOptions composed, bool quick) {
  // Long enough that each spacecraft's first steps (its recording's first
  // pages, its models' first calls) weigh little against the rest.
  composed.overrides.push_back(quick ? "duration_s=1000" : "duration_s=3000");
  double us_alone = 0.0;
  for (const int n : {1, 4, 16}) {
    RunOptions o = composed;
    o.overrides.push_back("spacecraft_count=" + std::to_string(n));
    nlohmann::ordered_json summary;
    if (const int rc = run(o, &summary); rc != 0) return rc;
    const double per_s = summary["steps_per_second"].get<double>() * n;
    const double us = 1e6 / per_s;
    if (n == 1) us_alone = us;
    std::printf("fleet_n%d_spacecraft_steps_per_s=%.1f\n", n, per_s);
    std::printf("fleet_n%d_us_per_spacecraft_step=%.2f\n", n, us);
    if (n > 1) std::printf("fleet_n%d_cost_growth=%.3f\n", n, us / us_alone);
    fs::remove_all(o.out);
  }
  return 0;
}

/// [s] simulated time of bench's composed figure, at least.
constexpr double kComposedBenchSeconds = 20000.0;

/// "a,b,c", one decimal each.
std::string joined(const std::vector<double>& values) {
  std::string text;
  for (const double v : values) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%s%.1f", text.empty() ? "" : ",", v);
    text += buffer;
  }
  return text;
}

/// Runs of each figure that machine noise moves: pairs of the bare graph and
/// the rig's lockstep run in turn, and the composed run. On this machine kind
/// either moved by a quarter from one minute to the next (780 and 1,046
/// steps/s, the same rig a minute apart), so the figures are medians and the
/// fraction lockstep_fraction_of_limit is the medians' ratio.
constexpr int kRunsPerFigure = 3;

/// [s] simulated time of bench's composed resume figure: 20,000 steps, about a
/// second to record each time, where 600 s (a third of a second) is the noise's.
constexpr double kComposedResumeSeconds = 2000.0;

/// `--resume` of a run that completed: K is its last step, so the resumed
/// run is all check phase (every sample compared with the recording, none
/// stored). Its steps/s against the recording run's is how fast a resume
/// re-checks (the target: at least half as fast). Every step is
/// recorded: decimated, a resume checks only the recorded steps' samples.
/// `o` runs the scenario as processes or composed; its figures are printed
/// under `prefix`, each a median of pairs run one after the other.
int resumeBench(RunOptions o, const std::string& prefix, int pairs) {
  std::vector<double> recorded, checked, ratios;
  std::uint64_t steps = 0;
  for (int i = 0; i < pairs; ++i) {
    nlohmann::ordered_json summary;
    if (const int rc = run(o, &summary); rc != 0) return rc;
    recorded.push_back(summary["steps_per_second"].get<double>());
    RunOptions resume;
    resume.scenario = o.scenario;
    resume.resume = o.out;
    resume.composed = o.composed;
    resume.quiet = true;
    resume.plots = false;
    resume.log_level = o.log_level;
    // Fails (exit 1) when any sample of the recorded steps came out different.
    if (const int rc = run(resume, &summary); rc != 0) return rc;
    checked.push_back(summary["steps_per_second"].get<double>());
    // Each pair's own ratio: its two runs saw the same phase of the machine.
    ratios.push_back(checked.back() / recorded.back());
    steps = summary["steps"].get<std::uint64_t>();
    fs::remove_all(o.out);
  }
  std::string ratio_runs;
  for (const double r : ratios) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%s%.3f", ratio_runs.empty() ? "" : ",", r);
    ratio_runs += buffer;
  }
  std::printf("%s_steps=%llu\n", prefix.c_str(), static_cast<unsigned long long>(steps));
  std::printf("%s_record_steps_per_s=%.1f\n", prefix.c_str(), analysis::quantile(recorded, 0.5));
  std::printf("%s_check_steps_per_s=%.1f\n", prefix.c_str(), analysis::quantile(checked, 0.5));
  std::printf("%s_check_speed_ratio=%.3f\n", prefix.c_str(), analysis::quantile(ratios, 0.5));
  std::printf("%s_check_speed_ratio_runs=%s\n", prefix.c_str(), ratio_runs.c_str());
  return 0;
}

/// resumeBench() of `scenario` as processes (`--duration-s`), as `flatsat run
/// --resume` runs it, and composed (kComposedResumeSeconds) when it can be.
int resumeFigures(const std::string& scenario, double duration_s, bool quick) {
  bus::Scenario loaded;
  if (!loadChecked(scenario, "", loaded)) return kExitBadInput;
  RunOptions o;
  o.scenario = scenario;
  o.out = (fs::temp_directory_path() / ("flatsat-bench-resume-" + std::to_string(::getpid()))).string();
  o.overrides = {"duration_s=" + std::to_string(duration_s), "duration_orbits=null"};
  o.quiet = true;
  o.plots = false;
  o.log_level = "warn";
  if (const int rc = resumeBench(o, "resume", quick ? 1 : kRunsPerFigure); rc != 0) return rc;
  if (!rig::composedProblems(loaded).empty()) return 0;
  o.composed = true;
  o.overrides.push_back("duration_s=" + std::to_string(kComposedResumeSeconds));
  return resumeBench(o, "resume_composed", kRunsPerFigure);
}

int bench(const std::string& scenario, double duration_s, bool quick) {
  const double paced_s = quick ? 30.0 : 60.0;
  bus::Scenario loaded;
  if (!loadChecked(scenario, "", loaded)) return kExitBadInput;
  tools::printPhysicsBench();
  tools::printHopBench(quick);
  const std::string out = (fs::temp_directory_path() /
                           ("flatsat-bench-" + std::to_string(::getpid()))).string();
  RunOptions o;
  o.scenario = scenario;
  o.out = out;
  o.overrides = {"duration_s=" + std::to_string(duration_s), "duration_orbits=null"};
  o.quiet = true;
  o.plots = false;
  o.log_level = "warn";
  nlohmann::ordered_json summary;
  std::vector<double> plains, limits, locksteps, startups;
  for (int i = 0; i < kRunsPerFigure; ++i) {
    plains.push_back(tools::measurePlainGraphStepsPerSecond(quick));
    limits.push_back(tools::measureLimitStepsPerSecond(quick));
    if (const int rc = run(o, &summary); rc != 0) return rc;
    locksteps.push_back(summary["steps_per_second"].get<double>());
    // Launch (the first component spawned) to the first step granted, as the
    // launcher's own reader saw the grant.
    startups.push_back(1e3 * summary["startup_seconds"].get<double>());
    fs::remove_all(out);
  }
  const double plain = analysis::quantile(plains, 0.5);
  const double limit = analysis::quantile(limits, 0.5);
  const double lockstep = analysis::quantile(locksteps, 0.5);
  std::printf("plain_graph_steps_per_s=%.1f\n", plain);
  std::printf("plain_graph_steps_per_s_runs=%s\n", joined(plains).c_str());
  std::printf("limit_steps_per_s=%.1f\n", limit);
  std::printf("limit_steps_per_s_runs=%s\n", joined(limits).c_str());
  std::printf("scenario=%s\n", summary["scenario"].get<std::string>().c_str());
  std::printf("processes=%zu\n", summary["processes"].get<std::size_t>());
  std::printf("steps=%llu\n", summary["steps"].get<unsigned long long>());
  std::printf("lockstep_steps_per_s=%.1f\n", lockstep);
  std::printf("lockstep_steps_per_s_runs=%s\n", joined(locksteps).c_str());
  // The target: the rig should reach >= 0.75 of the bare graph's rate.
  std::printf("lockstep_fraction_of_limit=%.3f\n", lockstep / limit);
  // Issue 36's target: >= 0.75 of what plain Fast DDS gives the same graph.
  std::printf("lockstep_fraction_of_plain=%.3f\n", lockstep / plain);
  std::printf("speed_factor=%.1f\n", lockstep * loaded.step_s);
  std::printf("startup_ms=%.0f\n", analysis::quantile(startups, 0.5));
  // The same scenario composed into one process, its recording decimated to
  // 1 Hz as 42 writes its output files (the composed figure).
  if (!rig::composedProblems(loaded).empty()) {
    std::cerr << "flatsat bench: " << scenario << " cannot run composed; no composed figures\n";
    if (const int rc = resumeFigures(scenario, duration_s, quick); rc != 0) return rc;
    return pacedBench(scenario, paced_s);
  }
  o.composed = true;
  o.overrides.push_back(rig::recordOnceASecond(loaded.step_s));
  // At least 20,000 s (200,000 steps, a second or two): 600 s composed is
  // 50 ms of stepping, where the first steps' page faults and a noisy
  // neighbour's moment decide the figure. Three runs, the median (the
  // figure moved between 11k and 15k within minutes).
  RunOptions composed = o;
  composed.overrides.push_back("duration_s=" + std::to_string(std::max(duration_s, kComposedBenchSeconds)));
  std::vector<double> composed_rates;
  for (int i = 0; i < kRunsPerFigure; ++i) {
    if (const int composed_rc = run(composed, &summary); composed_rc != 0) return composed_rc;
    composed_rates.push_back(summary["steps_per_second"].get<double>());
    fs::remove_all(out);
  }
  const double composed_rate = analysis::quantile(composed_rates, 0.5);
  std::printf("composed_steps=%llu\n", summary["steps"].get<unsigned long long>());
  std::printf("composed_steps_per_s=%.1f\n", composed_rate);
  std::printf("composed_steps_per_s_runs=%s\n", joined(composed_rates).c_str());
  std::printf("composed_speed_factor=%.1f\n", composed_rate * loaded.step_s);
  if (const int rc = fleetBench(o, quick); rc != 0) return rc;
  if (const int rc = resumeFigures(scenario, duration_s, quick); rc != 0) return rc;
  return pacedBench(scenario, paced_s);
}

}  // namespace

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("flatsat");
  spdlog::set_default_logger(logger);
  bus::installShutdownHandlers();
  analysis::recordRunFigures();  // a composed rig's recorder accumulates the summary

  CLI::App app{"flatsat: a flight-network attitude and orbit control rig"};
  app.require_subcommand(1);
  app.set_version_flag("--version", kFlatsatVersion);

  RunOptions run_options;
  auto* run_cmd = app.add_subcommand("run", "run a scenario: every component its own process");
  run_cmd->add_option("scenario", run_options.scenario, "scenario file (YAML) or name (flatsat scenarios)")
      ->required()
      ->transform(tools::scenarioByName());
  run_cmd->add_option("--out", run_options.out, "run directory (default runs/<name>-<time>)");
  run_cmd->add_option("--set", run_options.overrides, "override a scenario key: key.path=value");
  run_cmd->add_option("--log", run_options.log_level, "components' log level");
  run_cmd->add_flag("-q,--quiet", run_options.quiet, "no progress, no table");
  run_cmd->add_flag("--json", run_options.json, "print the summary as JSON");
  run_cmd->add_flag("!--no-plots", run_options.plots,
                    "skip the review figures (default: flatsat plot into <run>/plots)");
  run_cmd->add_flag("--restart", run_options.restart,
                    "paced: start a component that dies again (not the dynamics server), recorded");
  run_cmd->add_option("--max-restarts", run_options.max_restarts, "--restart: at most this often per component")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  run_cmd->add_option("--resume", run_options.resume,
                      "go on with the killed lockstep run in this directory from its last complete step");
  run_cmd->add_flag("--composed", run_options.composed,
                    "every component in this one process on an in-process bus (no DDS), "
                    "scheduled in data-flow order: same recording, much faster; lockstep only");
  run_cmd->add_option("--seed", run_options.seed, "scenario seed: dispersed initial conditions and noise");
  run_cmd->add_option("--external", run_options.externals,
                      "COMPONENT (or * for all): runs elsewhere (a container, another host); "
                      "not started here, the rig waits for it on the bus");
  run_cmd->add_option("--prefix", run_options.prefixes,
                      "COMPONENT=COMMAND: start that component under COMMAND (split at spaces), "
                      "e.g. gyro='ip netns exec fs-b'; * for every other component");
  run_cmd->add_option("--secure", run_options.secure,
                      "DDS Security on: certificates, keys and signed grants from this directory "
                      "(deploy/security/make-certs.sh DIR)");

  std::string check_file;
  auto* check_cmd = app.add_subcommand(
      "check", "check a scenario without running it: file:line:col, key and reason per problem");
  check_cmd->alias("validate");
  check_cmd->add_option("scenario", check_file, "scenario file (YAML) or name")->required()->transform(tools::scenarioByName());
  std::vector<std::string> check_overrides;
  check_cmd->add_option("--set", check_overrides, "override a scenario key, as flatsat run does: key.path=value");

  std::string bench_scenario = defaultScenario();
  double bench_duration_s = 600.0;
  auto* bench_cmd = app.add_subcommand("bench", "measure the lockstep rig; prints key=value");
  bench_cmd->add_option("scenario", bench_scenario, "scenario file or name (default: the default rig)")
      ->transform(tools::scenarioByName());
  bench_cmd->add_option("--duration-s", bench_duration_s, "simulated seconds to run");
  bool bench_quick = false;
  bench_cmd->add_flag("--quick", bench_quick, "the paced run lasts 30 s instead of 60 s, fewer hops and bare-graph steps");
  bool bench_middleware = false;
  bench_cmd->add_flag("--middleware", bench_middleware,
                      "only the middleware figures: hop_us, hop_us_p99, plain_graph_steps_per_s, limit_steps_per_s");
  bool bench_resume = false;
  bench_cmd->add_flag("--resume", bench_resume,
                      "only the resume figures: a run recorded, then re-checked by --resume (resume_*)");

  int orbit_exit = 0;
  auto* orbit_cmd = tools::addOrbitCommand(app, orbit_exit);
  int field_exit = 0;
  auto* field_cmd = tools::addFieldCommand(app, field_exit);
  int study_exit = 0;
  auto* study_cmd = tools::addStudyCommand(app, study_exit);
  int soak_exit = 0;
  auto* soak_cmd = tools::addSoakCommand(app, soak_exit);
  int mc_exit = 0;
  auto* mc_cmd = tools::addMcCommand(app, mc_exit);
  int tool_exit = 0;
  std::vector<CLI::App*> tool_cmds = {
      tools::addTopicsCommand(app, tool_exit), tools::addTypesCommand(app, tool_exit),
      tools::addEchoCommand(app, tool_exit),
      tools::addHzCommand(app, tool_exit),     tools::addHealthCommand(app, tool_exit),
      tools::addExportCommand(app, tool_exit), tools::addInfoCommand(app, tool_exit),
      tools::addPlotCommand(app, tool_exit),
      tools::addRecordCommand(app, tool_exit), tools::addReplayCommand(app, tool_exit),
      tools::addCmdCommand(app, tool_exit),    tools::addParamCommand(app, tool_exit),
      tools::addFoxgloveCommand(app, tool_exit)};
  for (auto* peer : tools::addBenchPeerCommands(app, tool_exit)) tool_cmds.push_back(peer);
  tool_cmds.push_back(tools::addGrantsCommand(app, tool_exit));
  tool_cmds.push_back(tools::addScenariosCommand(app, tool_exit));

  auto* clean_cmd = app.add_subcommand(
      "clean-shm", "remove Fast DDS shared-memory files no live process uses");
  double clean_min_age_s = 0.0;
  clean_cmd
      ->add_option("--min-age-s", clean_min_age_s,
                   "keep files younger than this [s] (a rig starting now may not have mapped them yet)")
      ->check(CLI::Range(0.0, 86400.0));

  if (const auto exit = parseCommandLine(app, argc, argv)) return *exit;
  if (run_cmd->parsed()) return run(run_options);
  if (orbit_cmd->parsed()) return orbit_exit;
  if (field_cmd->parsed()) return field_exit;
  if (study_cmd->parsed()) return study_exit;
  if (soak_cmd->parsed()) return soak_exit;
  if (mc_cmd->parsed() || app.got_subcommand("mc-task")) return mc_exit;
  for (auto* tool : tool_cmds) {
    if (tool->parsed()) return tool_exit;
  }
  if (clean_cmd->parsed()) {
    const std::chrono::seconds min_age{static_cast<long>(std::ceil(clean_min_age_s))};
    for (const auto& name : rig::cleanStaleSharedMemory(min_age)) std::cout << "removed " << name << "\n";
    return 0;
  }
  if (bench_cmd->parsed() && bench_middleware) {
    bool all_measured = false;
    tools::printMiddlewareBench(bench_quick, &all_measured);
    return all_measured ? 0 : kExitFailed;
  }
  if (bench_cmd->parsed() && bench_resume) return resumeFigures(bench_scenario, bench_duration_s, bench_quick);
  if (bench_cmd->parsed()) return bench(bench_scenario, bench_duration_s, bench_quick);
  bus::Scenario scenario;
  if (!check_overrides.empty()) {
    // The scenario resolved as `flatsat run` resolves it, in a folder of its own.
    char folder[] = "/tmp/flatsat-check-XXXXXX";
    if (::mkdtemp(folder) == nullptr) {
      std::cerr << "error: cannot make a temporary folder\n";
      return kExitFailed;
    }
    bool ok = false;
    try {
      const std::string resolved = rig::writeRunScenario(check_file, folder, check_overrides);
      const ScenarioOrigin origin{check_file, check_overrides};
      ok = loadChecked(resolved, folder, scenario, &origin);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
    }
    fs::remove_all(folder);
    if (!ok) return kExitBadInput;
  } else if (!loadChecked(check_file, "", scenario)) {
    return kExitBadInput;
  }
  for (const auto& caution : scenarioCautions(scenario)) std::cout << "caution: " << caution << "\n";
  std::cout << check_file << ": ok (" << scenario.components.size() << " components)\n";
  return 0;
}
