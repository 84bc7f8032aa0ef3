// SPDX-License-Identifier: Apache-2.0
#include "bus/Scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ios>

#include "bus/InstallPaths.hpp"
#include "bus/ScenarioPlaces.hpp"

namespace flatsat::bus {

Schedule Scenario::schedule() const {
  Schedule schedule;
  for (const auto& component : components) {
    if (component.scheduled) schedule[component.name] = component.rate_divider;
  }
  return schedule;
}

double Scenario::componentStep_s(const std::string& name) const {
  for (const auto& component : components) {
    if (component.name == name && component.scheduled) return step_s * component.rate_divider;
  }
  return step_s;
}

bool Scenario::hasComponent(const std::string& component) const {
  for (const auto& entry : components) {
    if (entry.name == component) return true;
  }
  return false;
}

ParamReader Scenario::componentParams(const std::string& component,
                                      ConfigProblems& problems) const {
  ParamReader reader(root["components"][component], file, "components." + component, problems);
  std::uint32_t divider = 1;
  bool external = false;
  std::string role;
  double start_after_s = 0.0;
  reader.read("rate_divider", divider);  // marks the keys as known; checked at load
  reader.read("external", external);
  reader.read("role", role);
  reader.read("start_after_s", start_after_s, "s");
  return reader;
}

ParamReader Scenario::section(const std::string& key, ConfigProblems& problems) const {
  return ParamReader(root[key], file, key, problems);
}

std::uint64_t Scenario::seedFor(const std::string& component) const {
  std::uint64_t hash = 14695981039346656037ULL;
  for (char c : component) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  }
  return seed ^ hash;
}

namespace {

std::vector<BusFault> readBusFaults(ParamReader& top) {
  std::vector<BusFault> faults;
  for (auto& entry : top.list("bus_faults")) {
    BusFault fault;
    std::string kind;
    entry.read("kind", kind);
    if (!parseBusFaultKind(kind, fault.kind)) {
      entry.problem("kind", "'" + kind + "' is not one of " + kBusFaultKinds);
    }
    entry.read("topic", fault.topic);
    if (!isSteppedTopic(fault.topic)) entry.problem("topic", "'" + fault.topic + "' is not a stepped topic");
    entry.read("magnitude", fault.magnitude, fault.kind == BusFaultKind::kDelay ? "s" : "-");
    double start_s = 0.0, duration_s = 0.0;
    entry.read("start_s", start_s, "s");
    entry.read("duration_s", duration_s, "s");
    fault.start_ns = std::llround(start_s * 1e9);
    fault.duration_ns = std::llround(duration_s * 1e9);
    entry.problems(fault.validate());
    entry.finish();
    faults.push_back(fault);
  }
  return faults;
}

std::vector<ProgramEntry> readPrograms(ParamReader& top, const Scenario& scenario) {
  std::vector<ProgramEntry> programs;
  for (auto& entry : top.list("programs")) {
    ProgramEntry program;
    entry.read("name", program.name);
    entry.read("command", program.command);
    entry.read("bridges", program.bridges);
    for (const auto& bridge : program.bridges) {
      const auto it = std::find_if(scenario.components.begin(), scenario.components.end(),
                                   [&](const ComponentEntry& c) { return c.name == bridge; });
      if (it == scenario.components.end() || it->role != "bridge") {
        entry.problem("bridges", "'" + bridge + "' is not a component of this scenario with role: bridge");
      }
    }
    const bool word = !program.name.empty() &&
                      std::all_of(program.name.begin(), program.name.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
                      });
    if (!word) entry.problem("name", "'" + program.name + "' is not a plain word (letters, digits, _ and -)");
    if (scenario.hasComponent(program.name)) entry.problem("name", "'" + program.name + "' is a component's name");
    for (const auto& other : programs) {
      if (other.name == program.name) entry.problem("name", "'" + program.name + "' is given twice");
    }
    if (program.command.empty() || program.command.front().empty()) entry.problem("command", "must give the program to run");
    // A program free-runs on the wall clock: only a paced rig keeps time with it.
    if (scenario.pacing != Pacing::kPaced) entry.problem("", "programs run only beside a paced rig (mode: paced)");
    entry.finish();
    programs.push_back(program);
  }
  return programs;
}

}  // namespace

namespace {

/// `over` laid over `base`: mappings key by key, anything else replaced.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& entry : over) {
    const std::string key = entry.first.as<std::string>();
    out[key] = out[key] ? merged(out[key], entry.second) : YAML::Clone(entry.second);
  }
  return out;
}

/// The file `base:` names: beside the scenario naming it, else (a bare name
/// such as `default`) the installed or FLATSAT_SCENARIO_PATH scenario.
std::string basePath(const std::string& path, const std::string& base) {
  const auto beside = std::filesystem::path(path).parent_path() / base;
  if (std::filesystem::exists(beside)) return beside.string();
  if (const auto named = resolveScenario(base)) return *named;
  return beside.string();
}

/// `chain`: canonical paths (a loop's proof); `files`: the same as opened, the user's first.
YAML::Node loadWithBases(const std::string& path, std::vector<std::string>& chain, std::vector<std::string>& files) {
  if (!std::filesystem::exists(path)) throw ScenarioError(path + ": no such file");
  // A directory opens as a stream that throws on its first read (fuzz.scenario: `base: !0`).
  if (std::filesystem::is_directory(path)) throw ScenarioError(path + ": is a directory, not a scenario file");
  const std::string canonical = std::filesystem::weakly_canonical(path).string();
  if (std::find(chain.begin(), chain.end(), canonical) != chain.end()) {
    throw ScenarioError(path + ": base: the scenario is its own base (through " + chain.front() + ")");
  }
  chain.push_back(canonical);
  files.push_back(path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(path + ":" + std::to_string(e.mark.line + 1) + ":" +
                        std::to_string(e.mark.column + 1) + ": not valid YAML: " + e.msg);
  } catch (const std::ios_base::failure& e) {
    throw ScenarioError(path + ": cannot be read: " + e.what());
  }
  if (const auto duplicates = duplicateKeys(root, path); !duplicates.empty()) {
    std::string listed;
    for (const auto& d : duplicates) listed += "  " + d + "\n";
    throw ScenarioError(path + ": invalid scenario:\n" + listed);
  }
  if (!root.IsMap() || !root["base"]) return root;
  if (!root["base"].IsScalar() || root["base"].Scalar().empty()) {
    throw ScenarioError(path + ":" + std::to_string(root["base"].Mark().line + 1) + ": base: must be a file name");
  }
  const std::string base_path = basePath(path, root["base"].as<std::string>());
  YAML::Node own = YAML::Clone(root);
  own.remove("base");
  return merged(loadWithBases(base_path, chain, files), own);
}

}  // namespace

YAML::Node loadScenarioYaml(const std::string& path, std::vector<std::string>* files) {
  std::vector<std::string> chain, opened;
  YAML::Node root = loadWithBases(path, chain, opened);
  if (files != nullptr) *files = opened;
  return root;
}

namespace {

/// duration_s or duration_orbits, one of them, each within what a run can
/// step (kMaxRunDuration_s, kMaxRunOrbits; the step count is bounded where
/// the orbit's period is known, in the dynamics server's reader).
void readDuration(ParamReader& top, Scenario& scenario) {
  top.read("duration_s", scenario.duration_s, "s");
  top.read("duration_orbits", scenario.duration_orbits, "-");
  const bool by_time = top.has("duration_s"), by_orbits = top.has("duration_orbits");
  if (by_time && by_orbits) {
    // A base sets one and the user the other: the common case, so say how to drop the base's.
    top.problem("duration_s", "give duration_s or duration_orbits, not both (to run by time, also set "
                              "`duration_orbits: null`, or --set duration_orbits=null)");
  } else if (!by_time && !by_orbits) {
    top.problem("", "give one of duration_s or duration_orbits");
  } else if (by_time && !top.failed("duration_s") &&
             !(scenario.duration_s > 0.0 && scenario.duration_s <= kMaxRunDuration_s)) {
    top.problem("duration_s", "must be in (0, 3.16e8 s] (ten years)");
  } else if (by_orbits && !top.failed("duration_orbits") &&
             !(scenario.duration_orbits > 0.0 && scenario.duration_orbits <= kMaxRunOrbits)) {
    top.problem("duration_orbits", "must be in (0, 100000]");
  }
}

}  // namespace

Scenario loadScenario(const std::string& path) {
  Scenario scenario;
  scenario.file = path;
  scenario.root = loadScenarioYaml(path, &scenario.files);
  ConfigProblems problems;
  ParamReader top(scenario.root, path, "", problems);
  if (!scenario.root.IsMap()) throw ScenarioError(path + ": must be a YAML mapping");

  top.read("name", scenario.name);
  std::string description;
  top.read("description", description);
  std::string mode = "lockstep";
  top.read("mode", mode);
  if (mode == "paced") {
    scenario.pacing = Pacing::kPaced;
  } else if (mode != "lockstep") {
    top.problem("mode", "'" + mode + "' is not a run mode (lockstep, paced)");
  }
  top.read("domain_id", scenario.domain_id);
  if (scenario.domain_id > 232) top.problem("domain_id", "must be in 0..232");
  top.read("seed", scenario.seed);
  top.read("spacecraft_count", scenario.spacecraft_count);
  if (scenario.spacecraft_count < 1 || scenario.spacecraft_count > kMaxSpacecraft) {
    top.problem("spacecraft_count", "must be in 1.." + std::to_string(kMaxSpacecraft));
  }
  top.read("step_s", scenario.step_s, "s");
  // Lockstep steps are simulated time only: a station-keeping year steps by
  // the minute (seed S3). A paced step is a wall-clock tick of the rig.
  if (!(scenario.step_s >= 1e-3 && scenario.step_s <= 600.0)) {
    top.problem("step_s", "must be in [1 ms, 600 s]");
  } else if (scenario.pacing == Pacing::kPaced && scenario.step_s > 10.0) {
    top.problem("step_s", "must be at most 10 s in a paced run");
  }
  readDuration(top, scenario);
  top.read("liveliness_lease_s", scenario.liveliness_lease_s, "s");
  if (!(scenario.liveliness_lease_s >= 0.05 && scenario.liveliness_lease_s <= 60.0)) {
    top.problem("liveliness_lease_s", "must be in [50 ms, 60 s]");
  }
  auto metrics = top.section("metrics");
  metrics.read("acquisition_s", scenario.acquisition_s, "s");
  if (scenario.acquisition_s < 0) metrics.problem("acquisition_s", "must be >= 0");
  metrics.finish();

  top.section("components");
  if (!top.has("components")) top.problem("", "missing key 'components'");
  const YAML::Node listed = scenario.root["components"];
  if (listed && !listed.IsMap()) top.problem("components", "must map component names to sections");
  for (const auto& entry : listed.IsMap() ? listed : YAML::Node(YAML::NodeType::Map)) {
    ComponentEntry component;
    if (!entry.first.IsScalar()) {  // e.g. `? {a: 1}`: found by tests/fuzz (scenario)
      top.problem("components", "a component name must be a plain word");
      continue;
    }
    component.name = entry.first.as<std::string>();
    // Every sample is stamped with its producer's name (SampleHeader.source, Common.idl).
    if (component.name.size() > kMaxComponentName) {
      top.problem("components", "'" + component.name + "' is longer than " + std::to_string(kMaxComponentName) +
                                    " characters: a sample's header could not name it");
    }
    ParamReader reader(entry.second, path, "components." + component.name, problems);
    reader.read("rate_divider", component.rate_divider);
    bool external = false;
    reader.read("external", external);
    if (external) component.role = "external";
    reader.read("role", component.role);
    reader.read("start_after_s", component.start_after_s, "s");
    if (component.role == "external") {
      component.launched = false;
    } else if (component.role == "bridge") {
      component.scheduled = false;
    } else if (component.role != "emulated") {
      reader.problem("role", "must be emulated, bridge or external, not '" + component.role + "'");
    }
    if (!(component.start_after_s >= 0.0) || (component.start_after_s > 0.0 && component.role != "bridge")) {
      reader.problem("start_after_s", "must be >= 0, and only a bridge starts late");
    }
    if (component.rate_divider < 1 || component.rate_divider > 1000) {
      reader.problem("rate_divider", "must be in 1..1000");
    }
    scenario.components.push_back(component);
  }
  scenario.bus_faults = readBusFaults(top);
  scenario.programs = readPrograms(top, scenario);
  for (const auto& section : kPlantSections) top.section(section);
  top.finish();
  if (!problems.empty()) {
    std::string listed;
    for (const auto& problem : problems.list()) listed += "  " + placeProblem(problem, path, scenario.files) + "\n";
    throw ScenarioError(path + ": invalid scenario:\n" + listed);
  }
  return scenario;
}

}  // namespace flatsat::bus
