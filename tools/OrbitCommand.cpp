// SPDX-License-Identifier: Apache-2.0
#include "tools/OrbitCommand.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/Sgp4.hpp"
#include "sim/Tle.hpp"
#include "analysis/Conventions.hpp"

namespace flatsat::tools {

using analysis::kExitBadInput;
namespace {

constexpr int kExitPropagationError = 1;

struct OrbitOptions {
  std::string tle_file;
  double from_min = 0.0;
  double to_min = 1440.0;
  double step_min = 120.0;
  bool ignore_checksums = false;
};

/// Reads and parses every set; prints every problem and returns false when there is any.
bool readTles(const OrbitOptions& o, std::vector<sim::Tle>& tles) {
  std::ifstream in(o.tle_file);
  if (!in) {
    std::cerr << "error: cannot read " << o.tle_file << "\n";
    return false;
  }
  std::vector<sim::TleLines> sets;
  try {
    sets = sim::splitTleText(in);
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << o.tle_file << ": " << e.what() << "\n";
    return false;
  }
  if (sets.empty()) {
    std::cerr << "error: " << o.tle_file << ": no element sets\n";
    return false;
  }
  const auto checksum = o.ignore_checksums ? sim::TleChecksum::kIgnore : sim::TleChecksum::kVerify;
  bool ok = true;
  for (const sim::TleLines& set : sets) {
    try {
      tles.push_back(sim::parseTle(set.line1, set.line2, checksum));
    } catch (const std::invalid_argument& e) {
      std::cerr << "error: " << o.tle_file << ", element set at line " << set.line_number << ": " << e.what() << "\n";
      ok = false;
    }
  }
  return ok;
}

int runOrbit(const OrbitOptions& o) {
  if (!std::isfinite(o.from_min) || !std::isfinite(o.to_min) || o.to_min < o.from_min) {
    std::cerr << "error: --from and --to must be finite with --from <= --to\n";
    return kExitBadInput;
  }
  if (!(o.step_min > 0.0) || !std::isfinite(o.step_min)) {
    std::cerr << "error: --step must be positive\n";
    return kExitBadInput;
  }
  std::vector<sim::Tle> tles;
  if (!readTles(o, tles)) return kExitBadInput;

  int status = 0;
  std::size_t stopped = 0;
  // Then per set Vallado's tcppver.out layout: "<catalogue number> xx", a row per time.
  std::printf("# t [min after epoch], r x y z [km], v x y z [km/s]: SGP4, TEME frame\n");
  for (const sim::Tle& tle : tles) {
    std::printf("%d xx\n", tle.catalog_number);
    const sim::Sgp4 sgp4(tle);
    // Vallado's driver: add the step to the previous time, clip the last one to the end.
    for (double t = o.from_min;;) {
      const sim::Sgp4::Result s = sgp4.propagate(t);
      if (!s.ok()) {
        std::cerr << "error: catalogue number " << tle.catalog_number << " at " << t << " min: " << s.message << "\n";
        status = kExitPropagationError;
        ++stopped;
        break;
      }
      std::printf(" %16.8f %16.8f %16.8f %16.8f %12.9f %12.9f %12.9f\n", t, s.r_T_km.x(), s.r_T_km.y(), s.r_T_km.z(),
                  s.v_T_km_s.x(), s.v_T_km_s.y(), s.v_T_km_s.z());
      if (t >= o.to_min) break;
      t += o.step_min;
      if (t > o.to_min) t = o.to_min;
    }
  }
  std::fflush(stdout);
  if (stopped > 0) {
    std::cerr << "flatsat orbit: " << stopped << " of " << tles.size()
              << " element sets stopped early at an SGP4 error (above); exit status " << status << "\n";
  }
  return status;
}

}  // namespace

CLI::App* addOrbitCommand(CLI::App& app, int& exit_code) {
  // The options live as long as the callback that reads them.
  auto options = std::make_shared<OrbitOptions>();
  auto* cmd =
      app.add_subcommand("orbit", "propagate TLEs with SGP4: TEME position [km] and velocity [km/s] per time step");
  cmd->add_option("--tle", options->tle_file, "element set file (two- or three-line format)")->required();
  cmd->add_option("--from", options->from_min, "first time [min after each set's epoch]")->capture_default_str();
  cmd->add_option("--to", options->to_min, "last time [min after each set's epoch]")->capture_default_str();
  cmd->add_option("--step", options->step_min, "time step [min]")->capture_default_str();
  cmd->add_flag("--no-checksum", options->ignore_checksums,
                "accept lines whose column-69 checksum does not match (Vallado's verification file has three)");
  cmd->callback([options, &exit_code] { exit_code = runOrbit(*options); });
  return cmd;
}

}  // namespace flatsat::tools
