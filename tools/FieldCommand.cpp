// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "tools/FieldCommand.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/Geodetic.hpp"
#include "sim/GeomagneticField.hpp"
#include "sim/SpotFieldModel.hpp"
#include "analysis/Conventions.hpp"

namespace flatsat::tools {

using analysis::kDeg;
using analysis::kExitBadInput;
namespace {

constexpr int kExitMissingData = 1;

struct FieldOptions {
  std::string model = "igrf14";
  double date = 0.0;     // [yr] decimal year
  double lat_deg = 0.0;  // [deg] geodetic latitude
  double lon_deg = 0.0;  // [deg] east longitude
  double alt_km = 0.0;   // [km] height above the WGS-84 ellipsoid
};

// The data file in the first data folder holding it; empty if none does.
std::string dataFile(const std::string& relative) {
  const auto found = bus::findIn(bus::dataDirs(), relative);
  return found ? found->string() : std::string();
}

// The seed's first-harmonic model at a point: the ascending pass of a polar orbit
// through it (u = geocentric latitude), where the orbit frame's −X is north, Y east
// and −Z down; B0 from IGRF-14's g₁⁰ at the date.
Eigen::Vector3d spotField_G_nT(const std::string& igrf_file, const FieldOptions& o, const sim::GeodeticPosition& p) {
  const sim::DipoleCoefficients dipole = sim::igrfDipoleAt(igrf_file, o.date);
  const sim::SpotFieldModel spot =
      sim::SpotFieldModel::firstHarmonic(-dipole.g10_nT * 1e-9, sim::kIgrfReferenceRadius_m);
  const sim::GeocentricPosition c = sim::geocentricFromGeodetic(p);
  const Eigen::Vector3d b_O_nT = 1e9 * spot.b_O_T(c.latitude_rad, c.radius_m);
  const Eigen::Vector3d b_C_nT(-b_O_nT.x(), b_O_nT.y(), -b_O_nT.z());
  return sim::R_GC(p.latitude_rad, c.latitude_rad) * b_C_nT;
}

int runField(const FieldOptions& o) {
  const bool wmm = o.model == "wmm2025";
  if (!wmm && o.model != "igrf14" && o.model != "dipole" && o.model != "spot") {
    std::cerr << "error: unknown model '" << o.model << "' (choose igrf14, wmm2025, dipole or spot)\n";
    return kExitBadInput;
  }
  const double max_alt_km = wmm ? 850.0 : 36000.0;  // the WMM's stated range; else up to GEO
  if (!(o.lat_deg >= -90.0 && o.lat_deg <= 90.0) || !(o.lon_deg >= -180.0 && o.lon_deg <= 360.0) ||
      !(o.alt_km >= -1.0 && o.alt_km <= max_alt_km)) {
    std::cerr << "error: need --lat in [-90, 90] deg, --lon in [-180, 360] deg and --alt-km in [-1, " << max_alt_km
              << "] km for " << o.model << "\n";
    return kExitBadInput;
  }
  const std::string file = dataFile(wmm ? "wmm/WMM2025.COF" : "igrf/igrf14coeffs.txt");
  if (file.empty()) {
    std::cerr << "error: no " << (wmm ? "wmm/WMM2025.COF" : "igrf/igrf14coeffs.txt") << " under "
              << bus::listOfDirs(bus::dataDirs()) << " (FLATSAT_DATA_DIR adds folders)\n";
    return kExitMissingData;
  }
  const sim::GeodeticPosition p{o.lat_deg * kDeg, o.lon_deg * kDeg, o.alt_km * 1e3};
  Eigen::Vector3d b_G_nT;
  sim::MagneticElementRates rates{Eigen::Vector3d::Zero()};
  bool has_rates = false;  // the degree-1 and SPOT models carry no secular variation
  try {
    if (o.model == "dipole") {
      const sim::TiltedDipoleField dipole(sim::igrfDipoleAt(file, o.date));
      b_G_nT = 1e9 * (sim::R_EG(p).transpose() * dipole.b_E_T(sim::earthFixedFromGeodetic(p)));
    } else if (o.model == "spot") {
      b_G_nT = spotField_G_nT(file, o, p);
    } else {
      const sim::SphericalHarmonicField field = wmm ? sim::wmm2025(file, o.date) : sim::igrf14(file, o.date);
      b_G_nT = field.b_G_nT(p);
      rates = sim::magneticElementRates(b_G_nT, field.bDot_G_nT_yr(p));
      has_rates = true;
    }
  } catch (const std::runtime_error& e) {
    // The shipped files parse; what is left is a date outside the model's span.
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  }
  const sim::MagneticElements e = sim::magneticElements(b_G_nT);
  std::printf("model %s, date %.4f, latitude %.4f deg, longitude %.4f deg, height %.3f km (WGS-84)\n", o.model.c_str(),
              o.date, o.lat_deg, o.lon_deg, o.alt_km);
  const auto line = [has_rates](const char* name, double value, const char* unit, double rate) {
    const int decimals = unit[0] == 'n' ? 1 : 3;  // nT to 0.1, degrees to 0.001
    std::printf("  %-10s %11.*f ", name, decimals, value);
    if (has_rates) {
      std::printf("%-3s  %+9.*f %s/yr\n", unit, decimals + 1, rate, unit);
    } else {
      std::printf("%s\n", unit);
    }
  };
  line("X (north)", e.b_G_nT.x(), "nT", rates.b_dot_G_nT_yr.x());
  line("Y (east)", e.b_G_nT.y(), "nT", rates.b_dot_G_nT_yr.y());
  line("Z (down)", e.b_G_nT.z(), "nT", rates.b_dot_G_nT_yr.z());
  line("H", e.h_nT, "nT", rates.h_dot_nT_yr);
  line("F", e.f_nT, "nT", rates.f_dot_nT_yr);
  line("D", e.declination_rad / kDeg, "deg", rates.declination_dot_rad_yr / kDeg);
  line("I", e.inclination_rad / kDeg, "deg", rates.inclination_dot_rad_yr / kDeg);
  return 0;
}

}  // namespace

CLI::App* addFieldCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<FieldOptions>();
  auto* cmd = app.add_subcommand("field", "geomagnetic field at a point: X Y Z H F D I like the public calculators");
  cmd->add_option("--model", options->model, "igrf14 (default), wmm2025, dipole (IGRF degree 1) or spot (seed S2)");
  cmd->add_option("--date", options->date, "decimal year, e.g. 2025.5")->required();
  cmd->add_option("--lat", options->lat_deg, "geodetic latitude [deg]")->required();
  cmd->add_option("--lon", options->lon_deg, "east longitude [deg]")->required();
  cmd->add_option("--alt-km", options->alt_km, "height above the WGS-84 ellipsoid [km] (default 0)");
  cmd->callback([options, &exit_code] { exit_code = runField(*options); });
  return cmd;
}

double fieldEvaluationMicroseconds(const sim::SphericalHarmonicField& field, int evaluations) {
  // A running sum the optimiser must keep, so that every evaluation is done.
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < evaluations; ++i) {
    const double f = (i + 0.5) / evaluations;
    const sim::GeodeticPosition p{(f - 0.5) * std::numbers::pi, 2.0 * std::numbers::pi * 37.0 * f, 500e3};
    sink += field.b_G_nT(p).x();
  }
  const auto stop = std::chrono::steady_clock::now();
  volatile double keep = sink;
  (void)keep;
  return std::chrono::duration<double, std::micro>(stop - start).count() / evaluations;
}

}  // namespace flatsat::tools
