// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bus/BusFaults.hpp"
#include "bus/Node.hpp"
#include "bus/Params.hpp"

namespace flatsat::bus {

/// A scenario file that failed to load; what() lists every problem.
struct ScenarioError : std::runtime_error {
  explicit ScenarioError(const std::string& what) : std::runtime_error(what) {}
};

/// One process of the rig as the scenario lists it.
struct ComponentEntry {
  std::string name;               ///< component name (= its kind for now)
  std::uint32_t rate_divider = 1; ///< [-] runs when step % divider == 0, 1..1000
  /// false (`role: external`): runs elsewhere (another host, a real box);
  /// the launcher does not start it but the rig waits for it on the bus.
  bool launched = true;
  /// false (`role: bridge`): a hardware bridge or a device stand-in. It is not
  /// stepped (it publishes as its device delivers, at a higher ownership
  /// strength than the emulator it overrides) and its death does not stop the
  /// rig: readers fall back to the emulator.
  bool scheduled = true;
  double start_after_s = 0.0;  ///< [s] wall time after the launch before it is started, >= 0
  /// "emulated", "bridge" or "external", as the scenario names it.
  std::string role = "emulated";
};

/// A program the launcher starts beside the rig's components that is not on the bus:
/// a flight computer's own software talking to the rig over serial lines, a gateway.
struct ProgramEntry {
  std::string name;                  ///< a plain word, not a component's; its log is <run>/logs/<name>.log
  /// argv; "{run}" in any argument is the run directory. A bare first word is looked
  /// up beside the flatsat tool first, then on PATH.
  std::vector<std::string> command;
  /// The bridges (role: bridge components) that carry what it writes onto the bus: the
  /// summary names the topics they published as the program's.
  std::vector<std::string> bridges;
};

inline constexpr std::uint32_t kMaxSpacecraft = 64;
/// The longest component name: SampleHeader.source holds 32 characters, NUL padded.
inline constexpr std::size_t kMaxComponentName = 31;

/// The top level of a scenario file. Component parameters stay as YAML
/// nodes: each component reads its own section (componentParams()).
/// The longest run a scenario may ask for: ten years, 100000 orbits (fifteen
/// years in low orbit), and 1e9 steps (a day of wall time composed).
inline constexpr double kMaxRunDuration_s = 3.16e8;
inline constexpr double kMaxRunOrbits = 1e5;
inline constexpr double kMaxRunSteps = 1e9;

struct Scenario {
  std::string file;
  /// `file` and the bases it names, in that order: where problems are placed (bus/ScenarioPlaces.hpp).
  std::vector<std::string> files;
  YAML::Node root;
  std::string name;
  Pacing pacing = Pacing::kLockstep;  ///< mode: lockstep | paced
  std::uint32_t domain_id = 0;     ///< [-] 0..232; FLATSAT_DOMAIN overrides
  std::uint64_t seed = 1;          ///< [-] base seed; each component derives its own
  /// [-] 1..kMaxSpacecraft copies of the rig, spacecraft i on its own bus
  /// (composed: its own in-process hub; else domain_id + i) with seed + i.
  std::uint32_t spacecraft_count = 1;
  double step_s = 0.1;             ///< [s] base period, 1e-3..600 (paced: ..10)
  double duration_s = 0.0;         ///< [s] run length (or duration_orbits)
  double duration_orbits = 0.0;    ///< [-] run length in orbital periods
  double acquisition_s = 0.0;      ///< [s] metrics ignore pointing before this
  double liveliness_lease_s = 1.0; ///< [s] paced: a silent producer is dead after this, 0.05..60
  std::vector<ComponentEntry> components;
  /// `programs:` started with the rig, paced only; one that exits before the run ends fails it.
  std::vector<ProgramEntry> programs;
  /// `bus_faults:` samples of a topic dropped, delayed or duplicated (bus/BusFaults.hpp).
  std::vector<BusFault> bus_faults;

  Schedule schedule() const;
  /// [s] A component's own step: step_s times its rate divider (1 when it is not scheduled).
  double componentStep_s(const std::string& name) const;
  bool hasComponent(const std::string& name) const;
  /// A reader over components.<name> with rate_divider already consumed.
  ParamReader componentParams(const std::string& name, ConfigProblems& problems) const;
  /// A reader over a top-level section (spacecraft, orbit, ...).
  ParamReader section(const std::string& key, ConfigProblems& problems) const;
  /// The component's seed: the scenario seed mixed with its name (FNV-1a).
  std::uint64_t seedFor(const std::string& component) const;
};

/// Top-level sections that describe the spacecraft and its start (vehicle/
/// and the dynamics server read and check them).
inline const std::vector<std::string> kPlantSections = {"spacecraft", "orbit", "environment",
                                                        "initial", "onboard"};

/// The scenario file's YAML with its `base:` resolved: `base: other.yaml`
/// (relative to the file, else a scenario name as `flatsat run` takes) takes
/// that scenario and lays this file's keys over it, mappings merged key by
/// key, anything else replaced; bases may have bases. `files` gets the file
/// and its bases, the user's first.
/// @throws ScenarioError naming the file: missing, not YAML, a key written
/// twice in one mapping, a base loop.
YAML::Node loadScenarioYaml(const std::string& path, std::vector<std::string>* files = nullptr);

/// Loads and checks the top level; throws ScenarioError listing every
/// problem as "file:line:col: key: reason".
Scenario loadScenario(const std::string& path);

}  // namespace flatsat::bus
