// SPDX-License-Identifier: Apache-2.0
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <catch2/catch.hpp>

#include "sim/Atmosphere.hpp"
#include "sim/Constants.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

const Eigen::Vector3d kSunAtEquinox = Eigen::Vector3d::UnitX();

// Point on the equator at right ascension ra and height h above the ellipsoid.
Eigen::Vector3d equatorial(double ra_rad, double height_m) {
  return (kEarthEquatorialRadius_m + height_m) * Eigen::Vector3d(std::cos(ra_rad), std::sin(ra_rad), 0.0);
}

// Exact geodetic height: fixed-point iteration φ = atan2(z + e² N sin φ, p), then
// h = p cos φ + z sin φ − a √(1 − e² sin² φ) (valid at the poles too).
double geodeticHeight(const Eigen::Vector3d& r) {
  const double a = kEarthEquatorialRadius_m;
  const double e2 = kEarthFlattening * (2.0 - kEarthFlattening);
  const double p = std::hypot(r.x(), r.y());
  double lat = std::atan2(r.z(), p);
  for (int i = 0; i < 50; ++i) {
    const double n = a / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
    lat = std::atan2(r.z() + e2 * n * std::sin(lat), p);
  }
  return p * std::cos(lat) + r.z() * std::sin(lat) - a * std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
}

}  // namespace

TEST_CASE("Harris-Priester reproduces M&G Table 3.8 at its heights", "[sim][atmosphere][orbit]") {
  const Atmosphere atmosphere{AtmosphereParams{}};
  // Rows of the table typed from the book: height [km], antapex and apex density [g/km³].
  const double rows[][3] = {{100, 497400.0, 497400.0}, {200, 255.7, 316.2},      {300, 17.08, 35.26},
                            {400, 2.249, 7.492},       {500, 0.3916, 2.042},     {700, 0.02043, 0.2185},
                            {800, 0.007069, 0.08059},  {1000, 0.001150, 0.01810}};
  GIVEN("the Sun at the equinox, so the apex is on the equator at right ascension 30°") {
    THEN("below the apex the density is the maximum, below the antapex the minimum") {
      for (const auto& row : rows) {
        const double h = row[0] * 1e3;
        CHECK(atmosphere.density_kg_m3(equatorial(30.0 * kDeg, h), kSunAtEquinox) ==
              Approx(row[2] * 1e-12).epsilon(1e-9));
        CHECK(atmosphere.density_kg_m3(equatorial(210.0 * kDeg, h), kSunAtEquinox) ==
              Approx(row[1] * 1e-12).epsilon(1e-9));
      }
    }
  }
  GIVEN("a height half-way between two table heights") {
    THEN("each profile is the geometric mean of its neighbours (exponential interpolation)") {
      const double h = 410e3;
      CHECK(atmosphere.density_kg_m3(equatorial(210.0 * kDeg, h), kSunAtEquinox) ==
            Approx(std::sqrt(2.249 * 1.558) * 1e-12).epsilon(1e-9));
      CHECK(atmosphere.density_kg_m3(equatorial(30.0 * kDeg, h), kSunAtEquinox) ==
            Approx(std::sqrt(7.492 * 5.684) * 1e-12).epsilon(1e-9));
    }
  }
}

TEST_CASE("Harris-Priester density decreases with height", "[sim][atmosphere][orbit]") {
  const Atmosphere atmosphere{AtmosphereParams{}};
  for (const double ra_deg : {0.0, 30.0, 120.0, 210.0, 300.0}) {
    double previous = atmosphere.density_kg_m3(equatorial(ra_deg * kDeg, 80e3), kSunAtEquinox);
    for (double h = 81e3; h <= 1200e3; h += 1e3) {
      const double rho = atmosphere.density_kg_m3(equatorial(ra_deg * kDeg, h), kSunAtEquinox);
      CHECK(rho < previous);
      CHECK(rho > 0.0);
      previous = rho;
    }
  }
}

TEST_CASE("Harris-Priester bulge trails the Sun by 30°", "[sim][atmosphere][orbit]") {
  const double h = 500e3;
  const double rho_min = 0.3916e-12;
  const double rho_max = 2.042e-12;
  for (const double n : {2.0, 4.0, 6.0}) {
    AtmosphereParams params;
    params.bulge_exponent = n;
    const Atmosphere atmosphere{params};
    GIVEN("the cosine exponent n = " + std::to_string(static_cast<int>(n))) {
      THEN("around the equator the density peaks at right ascension 30° and is least at 210°") {
        double best_ra = -1.0;
        double worst_ra = -1.0;
        double best = 0.0;
        double worst = 1.0;
        for (double ra = 0.0; ra < 360.0; ra += 1.0) {
          const double rho = atmosphere.density_kg_m3(equatorial(ra * kDeg, h), kSunAtEquinox);
          if (rho > best) {
            best = rho;
            best_ra = ra;
          }
          if (rho < worst) {
            worst = rho;
            worst_ra = ra;
          }
        }
        CHECK(best_ra == 30.0);
        CHECK(worst_ra == 210.0);
        CHECK(atmosphere.density_kg_m3(equatorial(0.0, h), kSunAtEquinox) <
              atmosphere.density_kg_m3(equatorial(15.0 * kDeg, h), kSunAtEquinox));
      }
      THEN("90° from the apex the weight is cosⁿ(45°)") {
        const double expected = rho_min + (rho_max - rho_min) * std::pow(std::cos(45.0 * kDeg), n);
        CHECK(atmosphere.density_kg_m3(equatorial(120.0 * kDeg, h), kSunAtEquinox) == Approx(expected).epsilon(1e-9));
      }
      THEN("the apex follows the Sun's declination: above the pole the Sun at δ = 90° gives the maximum") {
        const Eigen::Vector3d above_pole(0.0, 0.0, kEarthEquatorialRadius_m * (1.0 - kEarthFlattening) + h);
        CHECK(atmosphere.density_kg_m3(above_pole, Eigen::Vector3d::UnitZ()) == Approx(rho_max).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("exponentialDensity_kg_m3 follows Vallado Table 8-4", "[sim][atmosphere][orbit]") {
  // Rows typed from the book: base height [km], nominal density [kg/m³], scale height [km].
  const double rows[][3] = {{0, 1.225, 7.249},        {100, 5.297e-7, 5.877},   {200, 2.789e-10, 37.105},
                            {400, 3.725e-12, 58.515}, {500, 6.967e-13, 63.822}, {700, 3.614e-14, 88.667},
                            {1000, 3.019e-15, 268.00}};
  THEN("at a base height the density is the nominal density") {
    for (const auto& row : rows) CHECK(exponentialDensity_kg_m3(row[0] * 1e3) == Approx(row[1]).epsilon(1e-12));
  }
  THEN("half a scale height above the base (inside the band) it has fallen by √e") {
    for (const auto& row : rows) {
      const double h_km = row[0] + 0.5 * row[2];
      CHECK(exponentialDensity_kg_m3(h_km * 1e3) == Approx(row[1] * std::exp(-0.5)).epsilon(1e-12));
    }
  }
  THEN("above 1000 km the last band continues; below sea level the first") {
    CHECK(exponentialDensity_kg_m3(1268e3) == Approx(3.019e-15 / std::exp(1.0)).epsilon(1e-12));
    CHECK(exponentialDensity_kg_m3(-7.249e3) == Approx(1.225 * std::exp(1.0)).epsilon(1e-12));
  }
  THEN("the Harris-Priester and exponential models agree within a factor of 3 at 400 km") {
    const Atmosphere hp{AtmosphereParams{}};
    const double rho_hp = hp.density_kg_m3(equatorial(120.0 * kDeg, 400e3), kSunAtEquinox);
    CHECK(rho_hp / exponentialDensity_kg_m3(400e3) > 1.0 / 3.0);
    CHECK(rho_hp / exponentialDensity_kg_m3(400e3) < 3.0);
  }
}

TEST_CASE("approximateHeight_m is within 30 m of the geodetic height", "[sim][atmosphere][orbit]") {
  for (double lat = -90.0; lat <= 90.0; lat += 2.5) {
    for (const double h : {0.0, 200e3, 500e3, 1000e3}) {
      // Spherical placement; the exact geodetic height is found by iteration.
      const Eigen::Vector3d r =
          (kEarthEquatorialRadius_m + h) * Eigen::Vector3d(std::cos(lat * kDeg), 0.0, std::sin(lat * kDeg));
      CHECK(std::abs(approximateHeight_m(r) - geodeticHeight(r)) < 30.0);
    }
  }
}

TEST_CASE("AtmosphereParams::validate lists every violation", "[sim][atmosphere][orbit]") {
  CHECK(AtmosphereParams{}.validate().empty());
  AtmosphereParams bad;
  bad.bulge_exponent = 7.0;
  std::swap(bad.harris_priester_table[49].density_min_kg_m3, bad.harris_priester_table[49].density_max_kg_m3);
  bad.harris_priester_table[10].height_m = bad.harris_priester_table[9].height_m;
  const auto errors = bad.validate();
  CHECK(errors.size() == 3);
  CHECK(anyStartsWith(errors, "bulge_exponent:"));
  CHECK(anyStartsWith(errors, "harris_priester_table[10]:"));
  CHECK(anyStartsWith(errors, "harris_priester_table[49]:"));
  CHECK_THROWS_AS(Atmosphere{bad}, std::invalid_argument);

  AtmosphereParams tiny;
  tiny.harris_priester_table.resize(1);
  CHECK(anyStartsWith(tiny.validate(), "harris_priester_table:"));
}

TEST_CASE("Harris-Priester tables from a file: the shipped one is M&G Table 3.8, another flux level scales",
          "[sim][atmosphere][orbit]") {
  namespace fs = std::filesystem;
  const fs::path shipped = fs::path(FLATSAT_DATA_DIR) / "atmosphere" / "harris_priester_mean.txt";
  const auto table = readHarrisPriesterTable(shipped.string());
  const auto builtin = harrisPriesterMeanSolarActivity();
  REQUIRE(table.size() == builtin.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    CHECK(table[i].height_m == builtin[i].height_m);
    CHECK(table[i].density_min_kg_m3 == Approx(builtin[i].density_min_kg_m3).epsilon(1e-15));
    CHECK(table[i].density_max_kg_m3 == Approx(builtin[i].density_max_kg_m3).epsilon(1e-15));
  }

  // A table for a higher flux with every density k times the mean one: the layers' scale
  // heights are unchanged, so the model's density is k times as large everywhere.
  const fs::path dir = fs::temp_directory_path() / ("flatsat-hp-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double k = 2.7;
  {
    std::ofstream out(dir / "scaled.txt");
    out << "# test table\n\n";
    for (const auto& row : builtin) {
      out << row.height_m / 1e3 << " " << k * row.density_min_kg_m3 / 1e-12 << " "
          << k * row.density_max_kg_m3 / 1e-12 << "  # g/km^3\n";
    }
  }
  AtmosphereParams scaled;
  scaled.harris_priester_table = readHarrisPriesterTable((dir / "scaled.txt").string());
  const Atmosphere mean{AtmosphereParams{}};
  const Atmosphere high{scaled};
  for (const double h : {150e3, 333e3, 400e3, 612e3, 987e3}) {
    for (const double ra : {0.0, 1.0, 3.0}) {
      const Eigen::Vector3d r = equatorial(ra, h);
      CHECK(high.density_kg_m3(r, kSunAtEquinox) == Approx(k * mean.density_kg_m3(r, kSunAtEquinox)).epsilon(1e-12));
    }
  }

  // Bad rows are named by file and line.
  {
    std::ofstream(dir / "short.txt") << "100 497400 497400\n120 24900\n";
    std::ofstream(dir / "words.txt") << "# heading\nheight min max\n";
  }
  CHECK_THROWS_WITH(readHarrisPriesterTable((dir / "short.txt").string()),
                    Catch::Contains("short.txt:2: needs three numbers"));
  CHECK_THROWS_WITH(readHarrisPriesterTable((dir / "words.txt").string()),
                    Catch::Contains("words.txt:2: 'height min max' is not a number"));
  CHECK_THROWS_WITH(readHarrisPriesterTable((dir / "missing.txt").string()), Catch::Contains("cannot be read"));
  fs::remove_all(dir);
}
