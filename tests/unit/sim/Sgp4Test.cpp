// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Sgp4.hpp"
#include "sim/Tle.hpp"

using namespace flatsat::sim;

namespace {

std::string sgp4Data(const std::string& file) { return std::string(FLATSAT_DATA_DIR) + "/sgp4/" + file; }

/// One object of Vallado's verification run: its TLE and the times on line 2 after column 69.
struct VerificationCase {
  Tle tle;
  double start_min = 0.0;
  double stop_min = 0.0;
  double step_min = 0.0;
};

/// A row of tcppver.out: tsince [min], position [km], velocity [km/s] (TEME).
struct Row {
  double t_min;
  Eigen::Vector3d r_km;
  Eigen::Vector3d v_km_s;
};

struct ExpectedOutput {
  int catalog_number;
  std::vector<Row> rows;
};

std::vector<VerificationCase> readVerificationTles() {
  std::ifstream in(sgp4Data("SGP4-VER.TLE"));
  REQUIRE(in);
  std::vector<VerificationCase> cases;
  for (const TleLines& lines : splitTleText(in)) {
    // Three of the sets are edited copies with stale checksums (TleTest checks which).
    VerificationCase c{parseTle(lines.line1, lines.line2, TleChecksum::kIgnore)};
    std::istringstream times(lines.line2.substr(69));
    times >> c.start_min >> c.stop_min >> c.step_min;
    REQUIRE(times);
    cases.push_back(c);
  }
  return cases;
}

/// tcppver.out: "<satnum> xx" per object, then rows "tsince x y z xdot ydot zdot …".
std::vector<ExpectedOutput> readTcppver() {
  std::ifstream in(sgp4Data("tcppver.out"));
  REQUIRE(in);
  std::vector<ExpectedOutput> objects;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    if (line.find("xx") != std::string::npos) {
      objects.push_back({0, {}});
      fields >> objects.back().catalog_number;
      continue;
    }
    Row row;
    fields >> row.t_min >> row.r_km.x() >> row.r_km.y() >> row.r_km.z() >> row.v_km_s.x() >> row.v_km_s.y() >>
        row.v_km_s.z();
    REQUIRE(fields);
    REQUIRE(!objects.empty());
    objects.back().rows.push_back(row);
  }
  return objects;
}

/// Where Vallado's code stops with an error in this set, by catalogue number and start
/// time (the SL-12 R/B 20413 appears twice): the seven early ends of tcppver.out, with
/// the codes python-sgp4's tests also assert.
const std::map<std::pair<int, double>, Sgp4::Error> kExpectedErrors = {
    {{22312, 54.2028672}, Sgp4::Error::kMeanEccentricity},
    {{28350, 0.0}, Sgp4::Error::kMeanEccentricity},
    {{28872, 0.0}, Sgp4::Error::kDecayed},
    {{29141, 0.0}, Sgp4::Error::kDecayed},
    {{33333, 0.0}, Sgp4::Error::kSemiLatusRectum},
    {{33334, 0.0}, Sgp4::Error::kPerturbedEccentricity},
    {{20413, 1844000.0}, Sgp4::Error::kDecayed},
};

}  // namespace

TEST_CASE("The WGS-72 constant xke is 60 / sqrt(R^3 / mu) to the last bit", "[sim][sgp4]") {
  using namespace sgp4_wgs72;
  CHECK(kXke == 60.0 / std::sqrt(kRadius_km * kRadius_km * kRadius_km / kMu_km3_s2));
}

SCENARIO("SGP4 reproduces Vallado's verification output (tcppver.out)", "[sim][sgp4]") {
  GIVEN("the 33 element sets of SGP4-VER.TLE and Vallado's C++ output for them") {
    const std::vector<VerificationCase> cases = readVerificationTles();
    const std::vector<ExpectedOutput> expected = readTcppver();
    REQUIRE(cases.size() == 33);
    REQUIRE(expected.size() == cases.size());

    WHEN("each is propagated at the times of Vallado's verification driver") {
      double max_dr_km = 0.0;
      double max_dv_km_s = 0.0;
      std::size_t rows_compared = 0;
      std::size_t error_count = 0;
      const Row* previous_row = nullptr;
      for (std::size_t i = 0; i < cases.size(); ++i) {
        const VerificationCase& c = cases[i];
        const ExpectedOutput& out = expected[i];
        INFO("object " << i << ", catalogue number " << c.tle.catalog_number);
        REQUIRE(out.catalog_number == c.tle.catalog_number);
        REQUIRE(!out.rows.empty());
        const Sgp4 sgp4(c.tle);
        std::size_t next = 0;

        const auto compare = [&](double t, const Sgp4::Result& result) {
          INFO("tsince " << t << " min");
          REQUIRE(next < out.rows.size());
          const Row& row = out.rows[next++];
          CHECK(std::abs(row.t_min - t) < 1e-7);
          const double dr = (result.r_T_km - row.r_km).cwiseAbs().maxCoeff();
          const double dv = (result.v_T_km_s - row.v_km_s).cwiseAbs().maxCoeff();
          CHECK(dr < 1e-6);
          CHECK(dv < 1e-9);
          max_dr_km = std::max(max_dr_km, dr);
          max_dv_km_s = std::max(max_dv_km_s, dv);
          ++rows_compared;
        };

        // The driver prints the state at epoch first. When that fails it prints its
        // output buffer unchanged: the previous object's last row.
        Sgp4::Result result = sgp4.propagate(0.0);
        if (result.ok()) {
          compare(0.0, result);
        } else {
          REQUIRE(previous_row != nullptr);
          CHECK(out.rows[next].r_km == previous_row->r_km);
          CHECK(out.rows[next].v_km_s == previous_row->v_km_s);
          ++next;
        }
        // Vallado's loop: steps from start (one step earlier unless start is 0), the
        // last step clipped to stop, until stop or the first error.
        double t = c.start_min;
        if (std::abs(t) > 1e-8) t -= c.step_min;
        while (result.ok() && t < c.stop_min) {
          t += c.step_min;
          if (t > c.stop_min) t = c.stop_min;
          result = sgp4.propagate(t);
          if (result.ok()) compare(t, result);
        }
        if (!result.ok()) {
          INFO(result.message);
          CHECK(!result.message.empty());
          CHECK(std::isnan(result.r_T_km.x()));
          ++error_count;
          const auto it = kExpectedErrors.find({c.tle.catalog_number, c.start_min});
          REQUIRE(it != kExpectedErrors.end());
          CHECK(result.error == it->second);
        }
        CHECK(next == out.rows.size());  // the file stops where propagation stops
        previous_row = &out.rows.back();
      }
      THEN("every row agrees to 1e-6 km and 1e-9 km/s, and the seven errors are Vallado's") {
        CHECK(rows_compared + 1 == 700 - 33);  // 700 lines: 33 headers and 33334's repeated row
        CHECK(max_dr_km < 1e-6);
        CHECK(max_dv_km_s < 1e-9);
        CHECK(error_count == kExpectedErrors.size());
      }
    }
  }
}

SCENARIO("Sgp4 is deterministic and independent of the order of calls", "[sim][sgp4]") {
  GIVEN("the 12-hour resonant Molniya 1-83 (21897) and the 24-hour resonant ITALSAT 2 (24208)") {
    const std::vector<VerificationCase> cases = readVerificationTles();
    WHEN("a time is propagated before and after other times, forwards and backwards") {
      THEN("the results are bit-identical to a fresh propagator's") {
        for (const int catalog : {21897, 24208}) {
          const auto it = std::find_if(cases.begin(), cases.end(),
                                       [&](const VerificationCase& c) { return c.tle.catalog_number == catalog; });
          REQUIRE(it != cases.end());
          const Sgp4 sgp4(it->tle);
          REQUIRE(sgp4.isDeepSpace());
          const Sgp4::Result first = sgp4.propagate(5000.0);
          sgp4.propagate(-3000.0);
          sgp4.propagate(10000.0);
          const Sgp4::Result again = sgp4.propagate(5000.0);
          CHECK(first.ok());
          CHECK(first.r_T_km == again.r_T_km);
          CHECK(first.v_T_km_s == again.v_T_km_s);
          CHECK(Sgp4(it->tle).propagate(5000.0).r_T_km == first.r_T_km);
        }
      }
    }
  }
}

SCENARIO("Sgp4 agrees with two-body geometry for a near-circular orbit", "[sim][sgp4]") {
  GIVEN("CBERS 2 (28057): e = 8.84e-5, i = 98.4283 deg, 14.35478080 rev/d") {
    const std::vector<VerificationCase> cases = readVerificationTles();
    const auto it = std::find_if(cases.begin(), cases.end(),
                                 [](const VerificationCase& c) { return c.tle.catalog_number == 28057; });
    REQUIRE(it != cases.end());
    const Sgp4 sgp4(it->tle);
    CHECK_FALSE(sgp4.isDeepSpace());
    // a from Kepler's third law with the TLE's mean motion; J2 shifts it by ~10 km.
    const double n_rad_s = 14.35478080 * 2.0 * std::numbers::pi / 86400.0;
    const double a_km = std::cbrt(sgp4_wgs72::kMu_km3_s2 / (n_rad_s * n_rad_s));
    WHEN("it is propagated over a day") {
      THEN("radius, speed and orbit normal match a circular orbit of that inclination") {
        for (double t = 0.0; t <= 1440.0; t += 97.0) {
          const Sgp4::Result s = sgp4.propagate(t);
          REQUIRE(s.ok());
          CHECK(s.r_T_km.norm() == Approx(a_km).epsilon(3e-3));
          CHECK(s.v_T_km_s.norm() == Approx(std::sqrt(sgp4_wgs72::kMu_km3_s2 / a_km)).epsilon(3e-3));
          const Eigen::Vector3d h = s.r_T_km.cross(s.v_T_km_s).normalized();
          CHECK(std::acos(h.z()) * 180.0 / std::numbers::pi == Approx(98.4283).margin(0.05));
        }
      }
    }
  }
}

TEST_CASE("Sgp4 reports its epoch and rejects invalid element sets", "[sim][sgp4]") {
  const std::vector<VerificationCase> cases = readVerificationTles();
  // 00005: epoch 2000 day 179.78495062 = JD 2451544.5 (1 Jan 2000 0 h) + 178.78495062.
  const Sgp4 sgp4(cases.front().tle);
  CHECK(sgp4.epochJulianDate() == Approx(2451723.28495062).margin(1e-9));

  Tle bad = cases.front().tle;
  bad.eccentricity = 1.2;
  bad.mean_motion_rev_day = -1.0;
  try {
    Sgp4 rejected(bad);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    CHECK(message.find("eccentricity") != std::string::npos);
    CHECK(message.find("mean_motion_rev_day") != std::string::npos);
  }
}
