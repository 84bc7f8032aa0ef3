// SPDX-License-Identifier: Apache-2.0
#include "sim/GeomagneticField.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// IGRF releases predict the secular variation for five years past the last epoch.
constexpr double kSecularVariationSpan_yr = 5.0;

// The degree-1 rows in the order g10, g11, h11.
constexpr std::array<const char*, 3> kDipoleRowNames = {"g 1 0", "g 1 1", "h 1 1"};

[[noreturn]] void fail(const std::string& file, int line, const std::string& reason) {
  throw std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + reason);
}

bool parseNumber(const std::string& token, double& value) {
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// Header "g/h n m 1900.0 … 2025.0 2025-30": the epochs, then the label of the SV column.
std::vector<double> parseEpochs(std::istringstream& words, const std::string& file, int line) {
  std::string token;
  if (!(words >> token) || token != "n" || !(words >> token) || token != "m") {
    fail(file, line, "header must start with \"g/h n m\"");
  }
  std::vector<double> epochs;
  double epoch = 0.0;
  while (words >> token && parseNumber(token, epoch)) {
    if (!epochs.empty() && epoch <= epochs.back()) fail(file, line, "epochs must increase, found " + token);
    epochs.push_back(epoch);
  }
  if (epochs.size() < 2) fail(file, line, "header lists fewer than two epochs");
  if (token.empty() || parseNumber(token, epoch)) fail(file, line, "header lacks the secular-variation column");
  if (words >> token) fail(file, line, "unexpected header column after the secular variation: " + token);
  return epochs;
}

// Piecewise linear between epochs; extrapolated with the secular variation after the last.
double coefficientAt(const std::vector<double>& values, const std::vector<double>& epochs, double year) {
  const std::size_t last = epochs.size() - 1;
  if (year >= epochs[last]) return values[last] + (year - epochs[last]) * values[last + 1];
  std::size_t k = 0;
  while (year >= epochs[k + 1]) ++k;
  return values[k] + (year - epochs[k]) / (epochs[k + 1] - epochs[k]) * (values[k + 1] - values[k]);
}

}  // namespace

DipoleCoefficients igrfDipoleAt(const std::string& igrf_coeff_file, double decimal_year) {
  std::ifstream in(igrf_coeff_file);
  if (!in) fail(igrf_coeff_file, 0, "cannot open the IGRF coefficient file");

  std::vector<double> epochs;
  std::array<std::vector<double>, 3> rows;  // epochs' values then SV, for g10, g11, h11
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::istringstream words(text);
    std::string kind;
    if (!(words >> kind) || kind.front() == '#' || kind == "c/s") continue;
    if (kind == "g/h") {
      epochs = parseEpochs(words, igrf_coeff_file, line);
      continue;
    }
    if (kind != "g" && kind != "h") fail(igrf_coeff_file, line, "row type \"" + kind + "\" is neither g nor h");
    if (epochs.empty()) fail(igrf_coeff_file, line, "coefficient row before the \"g/h n m\" header");
    int n = 0;
    int m = 0;
    if (!(words >> n >> m)) fail(igrf_coeff_file, line, "expected degree n and order m after \"" + kind + "\"");
    if (n != 1 || m < 0 || m > 1 || (kind == "h" && m == 0)) continue;

    std::vector<double> values;
    std::string token;
    double value = 0.0;
    while (words >> token) {
      if (!parseNumber(token, value)) fail(igrf_coeff_file, line, "\"" + token + "\" is not a number");
      values.push_back(value);
    }
    if (values.size() != epochs.size() + 1) {
      fail(igrf_coeff_file, line,
           "expected " + std::to_string(epochs.size() + 1) +
               " values (one per epoch, then the secular variation), found " + std::to_string(values.size()));
    }
    rows[kind == "h" ? 2 : m] = std::move(values);
  }
  if (epochs.empty()) fail(igrf_coeff_file, 0, "no \"g/h n m\" header line");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].empty()) fail(igrf_coeff_file, 0, std::string("no \"") + kDipoleRowNames[i] + "\" row");
  }

  const double first = epochs.front();
  const double end = epochs.back() + kSecularVariationSpan_yr;
  if (!(decimal_year >= first && decimal_year <= end)) {
    fail(igrf_coeff_file, 0,
         "decimal year " + formatNumber(decimal_year) + " is outside [" + formatNumber(first) + ", " +
             formatNumber(end) + "] covered by the file");
  }
  return DipoleCoefficients{coefficientAt(rows[0], epochs, decimal_year), coefficientAt(rows[1], epochs, decimal_year),
                            coefficientAt(rows[2], epochs, decimal_year)};
}

TiltedDipoleField::TiltedDipoleField(const DipoleCoefficients& coefficients, double reference_radius_m)
    : g_E_nT_(coefficients.g11_nT, coefficients.h11_nT, coefficients.g10_nT), reference_radius_m_(reference_radius_m) {}

Eigen::Vector3d TiltedDipoleField::b_E_T(const Eigen::Vector3d& r_E_m) const {
  // IGRF scalar potential (Alken et al. 2021, "International Geomagnetic Reference
  // Field: the thirteenth generation", Earth Planets Space 73:49, Eq. 1):
  //   V = a Σ_n Σ_m (a/r)^(n+1) [g_n^m cos mφ + h_n^m sin mφ] P_n^m(cos θ),  B = −∇V.
  // Degree 1 with Schmidt P_1^0 = cos θ, P_1^1 = sin θ and the unit vector
  // r̂ = (sin θ cos φ, sin θ sin φ, cos θ) in Earth-fixed axes:
  //   V = a (a/r)² (g·r̂) = a³ (g·r)/r³,  g = (g11, h11, g10),
  //   B = −∇V = −a³ [g/r³ − 3 (g·r) r/r⁵] = (a/r)³ [3 (g·r̂) r̂ − g].
  const double r = r_E_m.norm();
  const Eigen::Vector3d r_hat = r_E_m / r;
  const double scale = std::pow(reference_radius_m_ / r, 3) * 1e-9;  // nT → T
  return scale * (3.0 * g_E_nT_.dot(r_hat) * r_hat - g_E_nT_);
}

}  // namespace flatsat::sim
