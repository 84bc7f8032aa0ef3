// SPDX-License-Identifier: Apache-2.0
#include "sim/Atmosphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <numbers>
#include <stdexcept>

#include "sim/Constants.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// M&G Table 3.8 in its own units: height [km], antapex and apex density [g/km³].
constexpr std::array<std::array<double, 3>, 50> kMeanActivityTable = {{
    {100, 497400.0, 497400.0}, {120, 24900.0, 24900.0},   {130, 8377.0, 8710.0},    {140, 3899.0, 4059.0},
    {150, 2122.0, 2215.0},     {160, 1263.0, 1344.0},     {170, 800.8, 875.8},      {180, 528.3, 601.0},
    {190, 361.7, 429.7},       {200, 255.7, 316.2},       {210, 183.9, 239.6},      {220, 134.1, 185.3},
    {230, 99.49, 145.5},       {240, 74.88, 115.7},       {250, 57.09, 93.08},      {260, 44.03, 75.55},
    {270, 34.30, 61.82},       {280, 26.97, 50.95},       {290, 21.39, 42.26},      {300, 17.08, 35.26},
    {320, 10.99, 25.11},       {340, 7.214, 18.19},       {360, 4.824, 13.37},      {380, 3.274, 9.955},
    {400, 2.249, 7.492},       {420, 1.558, 5.684},       {440, 1.091, 4.355},      {460, 0.7701, 3.362},
    {480, 0.5474, 2.612},      {500, 0.3916, 2.042},      {520, 0.2819, 1.605},     {540, 0.2042, 1.267},
    {560, 0.1488, 1.005},      {580, 0.1092, 0.7997},     {600, 0.08070, 0.6390},   {620, 0.06012, 0.5123},
    {640, 0.04519, 0.4121},    {660, 0.03430, 0.3325},    {680, 0.02632, 0.2691},   {700, 0.02043, 0.2185},
    {720, 0.01607, 0.1779},    {740, 0.01281, 0.1452},    {760, 0.01036, 0.1190},   {780, 0.008496, 0.09776},
    {800, 0.007069, 0.08059},  {840, 0.004680, 0.05741},  {880, 0.003200, 0.04210}, {920, 0.002210, 0.03130},
    {960, 0.001560, 0.02360},  {1000, 0.001150, 0.01810},
}};
constexpr double kGramPerKm3ToKgPerM3 = 1e-12;

// Vallado Table 8-4: base height h0 [km], nominal density ρ0 [kg/m³], scale height H [km].
struct ExponentialBand {
  double base_km;
  double density_kg_m3;
  double scale_height_km;
};
constexpr std::array<ExponentialBand, 28> kExponentialBands = {{
    {0, 1.225, 7.249},        {25, 3.899e-2, 6.349},    {30, 1.774e-2, 6.682},    {40, 3.972e-3, 7.554},
    {50, 1.057e-3, 8.382},    {60, 3.206e-4, 7.714},    {70, 8.770e-5, 6.549},    {80, 1.905e-5, 5.799},
    {90, 3.396e-6, 5.382},    {100, 5.297e-7, 5.877},   {110, 9.661e-8, 7.263},   {120, 2.438e-8, 9.473},
    {130, 8.484e-9, 12.636},  {140, 3.845e-9, 16.149},  {150, 2.070e-9, 22.523},  {180, 5.464e-10, 29.740},
    {200, 2.789e-10, 37.105}, {250, 7.248e-11, 45.546}, {300, 2.418e-11, 53.628}, {350, 9.518e-12, 53.298},
    {400, 3.725e-12, 58.515}, {450, 1.585e-12, 60.828}, {500, 6.967e-13, 63.822}, {600, 1.454e-13, 71.835},
    {700, 3.614e-14, 88.667}, {800, 1.170e-14, 124.64}, {900, 5.245e-15, 181.05}, {1000, 3.019e-15, 268.00},
}};

// M&G §3.5.2: the bulge apex trails the subsolar point by 30° in right ascension.
constexpr double kCosApexLag = 0.5 * std::numbers::sqrt3;
constexpr double kSinApexLag = 0.5;

}  // namespace

std::vector<HarrisPriesterRow> harrisPriesterMeanSolarActivity() {
  std::vector<HarrisPriesterRow> rows;
  rows.reserve(kMeanActivityTable.size());
  for (const auto& row : kMeanActivityTable) {
    rows.push_back({row[0] * 1e3, row[1] * kGramPerKm3ToKgPerM3, row[2] * kGramPerKm3ToKgPerM3});
  }
  return rows;
}

std::vector<HarrisPriesterRow> readHarrisPriesterTable(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::vector<HarrisPriesterRow> rows;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    double height_km = 0.0, min_g_km3 = 0.0, max_g_km3 = 0.0;
    std::string extra;
    if (!(fields >> height_km)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank or comment
      throw std::runtime_error(path + ":" + std::to_string(number) + ": '" + line + "' is not a number");
    }
    if (!(fields >> min_g_km3 >> max_g_km3) || (fields >> extra)) {
      throw std::runtime_error(path + ":" + std::to_string(number) +
                               ": needs three numbers: height [km], antapex and apex density [g/km^3]");
    }
    rows.push_back({height_km * 1e3, min_g_km3 * kGramPerKm3ToKgPerM3, max_g_km3 * kGramPerKm3ToKgPerM3});
  }
  return rows;
}

std::vector<std::string> AtmosphereParams::validate() const {
  std::vector<std::string> errors;
  if (!(bulge_exponent >= 2.0 && bulge_exponent <= 6.0)) {
    errors.push_back("bulge_exponent: " + formatNumber(bulge_exponent) + " must be in [2, 6]");
  }
  const auto& table = harris_priester_table;
  if (table.size() < 2) {
    errors.push_back("harris_priester_table: needs at least 2 rows, has " + std::to_string(table.size()));
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string where = "harris_priester_table[" + std::to_string(i) + "]: ";
    const HarrisPriesterRow& row = table[i];
    if (!std::isfinite(row.height_m) || !(row.density_min_kg_m3 > 0.0) ||
        !(row.density_max_kg_m3 >= row.density_min_kg_m3) || !std::isfinite(row.density_max_kg_m3)) {
      errors.push_back(where + "needs a finite height and 0 < density_min_kg_m3 ≤ density_max_kg_m3 < ∞");
    } else if (i > 0 &&
               !(row.height_m > table[i - 1].height_m && row.density_min_kg_m3 < table[i - 1].density_min_kg_m3 &&
                 row.density_max_kg_m3 < table[i - 1].density_max_kg_m3)) {
      errors.push_back(where + "height must increase and both densities decrease from the row before");
    }
  }
  return errors;
}

double approximateHeight_m(const Eigen::Vector3d& r_m) {
  const double r = r_m.norm();
  const double sin_latitude = r_m.z() / r;
  return r - kEarthEquatorialRadius_m * (1.0 - kEarthFlattening * sin_latitude * sin_latitude);
}

double exponentialDensity_kg_m3(double height_m) {
  const double height_km = height_m * 1e-3;
  // The band with the highest base not above the height (the first band below 0 km).
  auto band = std::upper_bound(kExponentialBands.begin(), kExponentialBands.end(), height_km,
                               [](double h, const ExponentialBand& b) { return h < b.base_km; });
  if (band != kExponentialBands.begin()) --band;
  return band->density_kg_m3 * std::exp(-(height_km - band->base_km) / band->scale_height_km);
}

Atmosphere::Atmosphere(const AtmosphereParams& params) : params_(params) {
  const std::vector<std::string> errors = params.validate();
  if (!errors.empty()) {
    std::string message = "invalid AtmosphereParams: " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }
  // M&G §3.5.2: within a layer each profile is exponential, with the scale height
  // that joins the two tabulated values.
  const auto& table = params_.harris_priester_table;
  for (std::size_t i = 0; i + 1 < table.size(); ++i) {
    const double thickness_m = table[i + 1].height_m - table[i].height_m;
    scale_height_min_m_.push_back(thickness_m / std::log(table[i].density_min_kg_m3 / table[i + 1].density_min_kg_m3));
    scale_height_max_m_.push_back(thickness_m / std::log(table[i].density_max_kg_m3 / table[i + 1].density_max_kg_m3));
  }
}

double Atmosphere::density_kg_m3(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& sun_N_unit) const {
  const double height_m = approximateHeight_m(r_N_m);
  if (params_.model == DensityModel::kExponential) return exponentialDensity_kg_m3(height_m);
  // Apex: right ascension of the Sun + 30°, declination of the Sun — the Sun
  // direction turned about the pole.
  const Eigen::Vector3d apex_N(kCosApexLag * sun_N_unit.x() - kSinApexLag * sun_N_unit.y(),
                               kSinApexLag * sun_N_unit.x() + kCosApexLag * sun_N_unit.y(), sun_N_unit.z());
  return harrisPriester_kg_m3(height_m, apex_N.dot(r_N_m) / (apex_N.norm() * r_N_m.norm()));
}

double Atmosphere::harrisPriester_kg_m3(double height_m, double cos_psi) const {
  const auto& table = params_.harris_priester_table;
  auto above = std::upper_bound(table.begin(), table.end(), height_m,
                                [](double h, const HarrisPriesterRow& row) { return h < row.height_m; });
  // The layer below the height, held to the first and last layers outside the table.
  const std::size_t layer =
      std::clamp<std::ptrdiff_t>(above - table.begin() - 1, 0, static_cast<std::ptrdiff_t>(table.size()) - 2);
  const HarrisPriesterRow& base = table[layer];
  const double dh = height_m - base.height_m;
  const double density_min = base.density_min_kg_m3 * std::exp(-dh / scale_height_min_m_[layer]);
  const double density_max = base.density_max_kg_m3 * std::exp(-dh / scale_height_max_m_[layer]);
  // cosⁿ(ψ/2) = ((1 + cos ψ)/2)^(n/2), M&G §3.5.2.
  const double weight = std::pow(std::max(0.0, 0.5 * (1.0 + cos_psi)), 0.5 * params_.bulge_exponent);
  return density_min + (density_max - density_min) * weight;
}

}  // namespace flatsat::sim
