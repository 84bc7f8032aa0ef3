// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>

#include "sim/GeomagneticField.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "sim/Time.hpp"
#include "tests/support/ReferenceData.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

const std::string kWmmFile = kDataDir + "/wmm/WMM2025.COF";

// A scratch coefficient file, removed when the test ends.
struct TempFile {
  explicit TempFile(const std::string& text, const std::string& name = "coefficients")
      : path((std::filesystem::temp_directory_path() /
              ("flatsat_shf_" + std::to_string(::getpid()) + "_" + name + ".txt"))
                 .string()) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::filesystem::remove(path); }
  std::string path;
};

// [nT·m] The potential V = a Σ (a/r)^(n+1) Σ (g cos mλ + h sin mλ) Pₙᵐ(cos θ), summed
// independently of the library: std::assoc_legendre (Ferrers functions, no
// Condon–Shortley phase) times the Schmidt factor √(2 (n−m)!/(n+m)!) for m > 0.
double potential(const GaussCoefficients& c, double a, const Eigen::Vector3d& r_E) {
  const double r = r_E.norm();
  const double lon = std::atan2(r_E.y(), r_E.x());
  double v = 0.0;
  for (int n = 1; n <= c.degree; ++n) {
    for (int m = 0; m <= n; ++m) {
      const double schmidt =
          m == 0 ? 1.0 : std::sqrt(2.0 * std::exp(std::lgamma(n - m + 1.0) - std::lgamma(n + m + 1.0)));
      v += a * std::pow(a / r, n + 1) * (c.g_nT[n][m] * std::cos(m * lon) + c.h_nT[n][m] * std::sin(m * lon)) *
           schmidt * std::assoc_legendre(n, m, r_E.z() / r);
    }
  }
  return v;
}

// [nT/m] Jacobian ∂B_i/∂x_j of the Earth-fixed field by central differences.
Eigen::Matrix3d fieldJacobian(const SphericalHarmonicField& field, const Eigen::Vector3d& r_E, double step_m) {
  Eigen::Matrix3d J;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d d = step_m * Eigen::Vector3d::Unit(j);
    J.col(j) = (field.b_E_T(r_E + d) - field.b_E_T(r_E - d)) * 1e9 / (2.0 * step_m);
  }
  return J;
}

}  // namespace

TEST_CASE("WMM2025 reproduces all 100 rows of the official test table", "[sim][geomag]") {
  std::ifstream in(kDataDir + "/wmm/WMM2025_TEST_VALUES.txt");
  REQUIRE(in);
  int rows = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream words(line);
    // year, height [km], lat, lon, D, I [deg], H, X, Y, Z, F [nT], then the rates per year.
    std::vector<double> v(18);
    for (double& value : v) REQUIRE(words >> value);
    ++rows;
    const SphericalHarmonicField wmm = wmm2025(kWmmFile, v[0]);
    const GeodeticPosition p{v[2] * kDeg, v[3] * kDeg, v[1] * 1e3};
    const MagneticElements e = wmm.elements(p);
    const MagneticElementRates rate = magneticElementRates(e.b_G_nT, wmm.bDot_G_nT_yr(p));
    INFO("row " << rows << ": " << line);
    // D and I are printed to 0.01°.
    CHECK(e.declination_rad / kDeg == Approx(v[4]).margin(0.01));
    CHECK(e.inclination_rad / kDeg == Approx(v[5]).margin(0.01));
    CHECK(e.h_nT == Approx(v[6]).margin(0.01));
    CHECK(e.b_G_nT.x() == Approx(v[7]).margin(0.01));
    CHECK(e.b_G_nT.y() == Approx(v[8]).margin(0.01));
    CHECK(e.b_G_nT.z() == Approx(v[9]).margin(0.01));
    CHECK(e.f_nT == Approx(v[10]).margin(0.01));
    // The rates are printed to 1e-6; the agreement found is within 2e-6.
    CHECK(rate.declination_dot_rad_yr / kDeg == Approx(v[11]).margin(1e-5));
    CHECK(rate.inclination_dot_rad_yr / kDeg == Approx(v[12]).margin(1e-5));
    CHECK(rate.h_dot_nT_yr == Approx(v[13]).margin(1e-4));
    CHECK(rate.b_dot_G_nT_yr.x() == Approx(v[14]).margin(1e-4));
    CHECK(rate.b_dot_G_nT_yr.y() == Approx(v[15]).margin(1e-4));
    CHECK(rate.b_dot_G_nT_yr.z() == Approx(v[16]).margin(1e-4));
    CHECK(rate.f_dot_nT_yr == Approx(v[17]).margin(1e-4));
    // The model is linear in time: the rate is the finite difference of the field.
    const Eigen::Vector3d difference = wmm2025(kWmmFile, v[0] + 0.25).b_G_nT(p) - wmm2025(kWmmFile, v[0]).b_G_nT(p);
    CHECK((rate.b_dot_G_nT_yr - difference / 0.25).norm() < 1e-8);
  }
  CHECK(rows == 100);
}

TEST_CASE("The synthesis is the gradient of the Gauss potential", "[sim][geomag]") {
  const SphericalHarmonicField igrf = igrf14(kIgrfFile, 2025.0);
  const GaussCoefficients& c = igrf.coefficients();
  const double a = igrf.referenceRadius_m();
  for (const Eigen::Vector3d& r_E : {Eigen::Vector3d(3.1e6, -4.2e6, 4.4e6), Eigen::Vector3d(-6.0e6, 2.5e6, -2.6e6),
                                     Eigen::Vector3d(1.0e3, -2.0e3, 6.9e6)}) {
    WHEN("differentiating an independently summed potential") {
      const double h = 10.0;
      Eigen::Vector3d minus_grad;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = h * Eigen::Vector3d::Unit(k);
        minus_grad(k) = -(potential(c, a, r_E + d) - potential(c, a, r_E - d)) / (2.0 * h);
      }
      THEN("B = −∇V to 1e-4 nT") { CHECK((igrf.b_E_T(r_E) * 1e9 - minus_grad).norm() < 1e-4); }
    }
    WHEN("differentiating the field itself") {
      const Eigen::Matrix3d J = fieldJacobian(igrf, r_E, 10.0);
      THEN("div B = 0 and curl B = 0 (a potential field in free space)") {
        CHECK(J.norm() > 1e-3);  // [nT/m] the gradients themselves
        CHECK(std::abs(J.trace()) < 1e-9);
        CHECK((J - J.transpose()).norm() < 1e-9);
      }
    }
  }
}

TEST_CASE("Degree 1 is the tilted dipole", "[sim][geomag]") {
  const DipoleCoefficients d = igrfDipoleAt(kIgrfFile, 2026.3);
  GaussCoefficients c;
  c.degree = 1;
  c.g_nT[1][0] = d.g10_nT;
  c.g_nT[1][1] = d.g11_nT;
  c.h_nT[1][1] = d.h11_nT;
  const SphericalHarmonicField field(c);
  const TiltedDipoleField dipole(d);
  for (const Eigen::Vector3d& r_E : {Eigen::Vector3d(7e6, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, -6.9e6),
                                     Eigen::Vector3d(3.1e6, -4.2e6, 4.4e6), Eigen::Vector3d(-1e7, 2e6, 3e5)}) {
    CHECK((field.b_E_T(r_E) - dipole.b_E_T(r_E)).norm() < 1e-12 * dipole.b_E_T(r_E).norm());
  }
}

TEST_CASE("The field is regular at the geographic poles", "[sim][geomag]") {
  const SphericalHarmonicField wmm = wmm2025(kWmmFile, 2025.0);
  for (const double pole : {90.0, -90.0}) {
    GIVEN("the pole at latitude " << pole) {
      const double lon = 0.6;
      const Eigen::Vector3d at = wmm.b_G_nT({pole * kDeg, lon, 300e3});
      const Eigen::Vector3d near = wmm.b_G_nT({(pole - std::copysign(1e-9, pole)) * kDeg, lon, 300e3});
      THEN("X, Y and Z are finite and the limit of the nearby values") {
        CHECK(at.allFinite());
        CHECK((at - near).norm() < 1e-3);
        CHECK(std::hypot(at.x(), at.y()) > 1000.0);  // the horizontal field does not vanish there
      }
      THEN("D turns with the meridian chosen: D ∓ λ (the grid variation) is the same for every λ") {
        const double sign = pole > 0.0 ? 1.0 : -1.0;
        const double grid0 = wmm.elements({pole * kDeg, 0.0, 300e3}).declination_rad;
        for (double l : {0.6, 2.0, -2.5}) {
          const double grid = wmm.elements({pole * kDeg, l, 300e3}).declination_rad - sign * l;
          CHECK(std::cos(grid - grid0) == Approx(1.0).margin(1e-12));
        }
      }
      THEN("the Earth-fixed field on the axis is the same from any meridian") {
        const Eigen::Vector3d r_E(0.0, 0.0, std::copysign(6.7e6, pole));
        const Eigen::Vector3d off(1e-6, 1e-6, 0.0);
        CHECK((wmm.b_E_T(r_E) - wmm.b_E_T(r_E + off)).norm() < 1e-15);
      }
    }
  }
}

TEST_CASE("WMM2025 and IGRF-14 agree within their model difference at 2025.0", "[sim][geomag]") {
  const SphericalHarmonicField wmm = wmm2025(kWmmFile, 2025.0);
  const SphericalHarmonicField igrf = igrf14(kIgrfFile, 2025.0);
  double sum_sq = 0.0;
  double worst = 0.0;
  int points = 0;
  for (double lat = -88.0; lat <= 88.0; lat += 8.0) {
    for (double lon = -180.0; lon < 180.0; lon += 10.0) {
      const GeodeticPosition p{lat * kDeg, lon * kDeg, 0.0};
      const double d = (wmm.b_G_nT(p) - igrf.b_G_nT(p)).norm();
      sum_sq += d * d;
      worst = std::max(worst, d);
      ++points;
    }
  }
  // Separate fits to the same satellite era (g₁⁰ differs by 1.8 nT; IGRF goes to
  // degree 13, WMM to 12). Measured at the surface: RMS 13 nT, worst 30 nT of ~50 000.
  CHECK(std::sqrt(sum_sq / points) < 20.0);
  CHECK(worst < 50.0);
  CHECK(std::sqrt(sum_sq / points) > 1.0);  // they are different models
}

TEST_CASE("Inertial field turns with the Earth", "[sim][geomag]") {
  const SphericalHarmonicField igrf = igrf14(kIgrfFile, 2025.0);
  const double jd = 2460676.5 + 0.3;
  const Eigen::Vector3d r_N(4.0e6, -3.0e6, 4.5e6);
  const Eigen::Matrix3d R = R_EN(jd);
  CHECK((igrf.b_N_T(r_N, jd) - R.transpose() * igrf.b_E_T(R * r_N)).norm() < 1e-18);
  CHECK(igrf.b_N_T(r_N, jd).norm() == Approx(igrf.b_E_T(R * r_N).norm()).epsilon(1e-14));
}

TEST_CASE("Bad coefficient files and years are reported with file, line and reason", "[sim][geomag]") {
  const std::string igrf_header = "g/h n m 2000.0 2005.0 2005-10\n";
  const std::string igrf_dipole = "g 1 0 -100 -200 -10\ng 1 1 10 20 1\nh 1 1 30 60 2\n";
  const std::string wmm_header = "    2025.0            WMM-2025     11/13/2024\n";
  const std::string wmm_dipole = "  1  0  -29351.8 0.0 12.0 0.0\n  1  1 -1410.8 4545.4 9.7 -21.5\n";
  const std::string nines = "999999999999999999999999999999999999999999999999\n";

  CHECK_THROWS_WITH(igrf14("/nonexistent/igrf.txt", 2025.0), Contains("/nonexistent/igrf.txt: cannot open"));
  CHECK_THROWS_WITH(wmm2025("/nonexistent/WMM.COF", 2025.0), Contains("/nonexistent/WMM.COF: cannot open"));
  CHECK_THROWS_WITH(igrf14(kIgrfFile, 1899.9), Contains("igrf14coeffs.txt") && Contains("outside [1900, 2030]"));
  CHECK_THROWS_WITH(wmm2025(kWmmFile, 2024.99), Contains("WMM2025.COF") && Contains("outside [2025, 2030]"));
  CHECK_THROWS_WITH(wmm2025(kWmmFile, 2030.01), Contains("outside [2025, 2030]"));
  CHECK_THROWS_WITH(wmm2025(kWmmFile, std::nan("")), Contains("outside"));

  struct Case {
    const char* what;
    std::string text;
    bool wmm;
    const char* message;
  };
  const Case cases[] = {
      {"a value that is not a number", igrf_header + "g 1 0 -100 x12 -10\n", false, ":2: \"x12\" is not a number"},
      {"a short row", igrf_header + "g 1 0 -100 -200\n", false, ":2: expected 3 values"},
      {"a degree above 13", igrf_header + igrf_dipole + "g 14 0 1 2 3\n", false, ":5: no coefficient g 14 0"},
      {"h of order 0", igrf_header + "h 1 0 1 2 3\n", false, ":2: no coefficient h 1 0"},
      {"a repeated row", igrf_header + igrf_dipole + "g 1 1 1 2 3\n", false, ":5: second row for g 1 1"},
      {"a missing row", igrf_header + igrf_dipole + "g 2 0 1 2 3\n", false, "no \"g 2 1\" row"},
      {"no header", igrf_dipole, false, ":1: coefficient row before the \"g/h n m\" header"},
      {"an unknown row type", igrf_header + "q 1 0 1 2 3\n", false, ":2: row type \"q\" is neither g nor h"},
      {"a WMM header without epoch", "WMM-2025 11/13/2024\n" + wmm_dipole + nines, true, ":1: header must start"},
      {"a WMM row too short", wmm_header + "  1  0  -29351.8 0.0 12.0\n" + nines, true, ":2: expected n m g h"},
      {"a WMM order above the degree", wmm_header + "  1  2  1 2 3 4\n" + nines, true, ":2: no coefficient g 1 2"},
      {"a WMM file cut short", wmm_header + wmm_dipole, true, "no closing line of 9s"},
      {"a WMM missing row", wmm_header + wmm_dipole + "  2  0  1 0 0 0\n" + nines, true, "no \"g 2 1\" row"},
  };
  for (const Case& c : cases) {
    WHEN(c.what) {
      const TempFile f(c.text);
      if (c.wmm) {
        CHECK_THROWS_WITH(wmm2025(f.path, 2025.0), Contains(f.path) && Contains(c.message));
      } else {
        CHECK_THROWS_WITH(igrf14(f.path, 2001.0), Contains(f.path) && Contains(c.message));
      }
    }
  }
  WHEN("small well-formed files") {
    const TempFile igrf(igrf_header + igrf_dipole, "igrf");
    const TempFile wmm(wmm_header + wmm_dipole + nines, "wmm");
    THEN("they are read with their own epochs and degree") {
      const GaussCoefficients c = igrf14(igrf.path, 2008.0).coefficients();
      CHECK(c.degree == 1);
      CHECK(c.g_nT[1][0] == Approx(-230.0));
      CHECK(c.h_dot_nT_yr[1][1] == 2.0);
      CHECK(wmm2025(wmm.path, 2026.0).coefficients().h_nT[1][1] == Approx(4545.4 - 21.5));
      CHECK_THROWS_WITH(igrf14(igrf.path, 2010.5), Contains("outside [2000, 2010]"));
    }
  }
  WHEN("the coefficients' degree or radius is out of range") {
    GaussCoefficients c;
    c.degree = 14;
    CHECK_THROWS_AS(SphericalHarmonicField(c), std::invalid_argument);
    c.degree = 0;
    CHECK_THROWS_AS(SphericalHarmonicField(c), std::invalid_argument);
    c.degree = 1;
    CHECK_THROWS_AS(SphericalHarmonicField(c, 0.0), std::invalid_argument);
  }
}
